// Hex text: bytes as pairs of lower-case digits (keys and tokens), and
// numbers as "0x" and a fixed count of digits (magic numbers, checksums and
// control characters in error messages).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace tessera {

inline constexpr char kHexDigits[] = "0123456789abcdef";

// Two lower-case digits per byte, most significant first: "00ff10".
inline std::string hexBytes(std::string_view bytes) {
  std::string out;
  out.reserve(2 * bytes.size());
  for (const unsigned char c : bytes) {
    out.push_back(kHexDigits[c >> 4]);
    out.push_back(kHexDigits[c & 15]);
  }
  return out;
}

// "0x" and the low 4 * digits bits of `value` as `digits` lower-case
// digits, zero-padded as printf's "0x%0<digits>x" would print a value that
// fits: hexNumber(42, 8) is "0x0000002a".
inline std::string hexNumber(uint64_t value, int digits) {
  std::string out = "0x";
  for (int i = digits - 1; i >= 0; --i) out.push_back(kHexDigits[(value >> (4 * i)) & 15]);
  return out;
}

}  // namespace tessera
