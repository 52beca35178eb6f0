// Little-endian byte writing and bounds-checked reading: a ByteReader never
// reads past its end and names what it was reading when data runs out. And
// the big-endian 32-bit numbers of the wire's length prefixes.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>

#include "core/util/status.h"

namespace tessera {

// A 32-bit number in big-endian (network) byte order, as the frames' length
// prefix carries it (protocol/framing.h); spelled out so that the host's
// endianness never matters.
inline void putBigEndian32(uint32_t value, char* out) {
  out[0] = static_cast<char>((value >> 24) & 0xff);
  out[1] = static_cast<char>((value >> 16) & 0xff);
  out[2] = static_cast<char>((value >> 8) & 0xff);
  out[3] = static_cast<char>(value & 0xff);
}
inline uint32_t getBigEndian32(const unsigned char* in) {
  return (uint32_t{in[0]} << 24) | (uint32_t{in[1]} << 16) | (uint32_t{in[2]} << 8) | uint32_t{in[3]};
}
inline uint32_t getBigEndian32(const char* in) {
  return getBigEndian32(reinterpret_cast<const unsigned char*>(in));
}

class ByteWriter {
 public:
  template <typename T>
  void put(T value) {
    static_assert(std::is_trivially_copyable_v<T>);
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));  // hosts are little-endian (x86-64, arm64)
    out_.append(bytes, sizeof(T));
  }
  void putBytes(std::string_view bytes) { out_.append(bytes); }
  // LEB128: 7 bits a byte, low first (Draco's varint too).
  void putVarint(uint64_t value) {
    for (; value >= 0x80; value >>= 7) put<uint8_t>(static_cast<uint8_t>(value | 0x80));
    put<uint8_t>(static_cast<uint8_t>(value));
  }
  std::string& bytes() { return out_; }

 private:
  std::string out_;
};

class ByteReader {
 public:
  ByteReader(const char* data, size_t size, std::string source)
      : data_(data), size_(size), source_(std::move(source)) {}

  template <typename T>
  Status get(T& value, const char* what) {
    static_assert(std::is_trivially_copyable_v<T>);
    if (size_ - offset_ < sizeof(T)) {
      return parseError(source_ + ": truncated at byte " + std::to_string(offset_) + " reading " + what);
    }
    std::memcpy(&value, data_ + offset_, sizeof(T));
    offset_ += sizeof(T);
    return Status::ok();
  }
  // A count of items of `itemSize` bytes each, refused if the rest of the
  // data cannot hold them (so a corrupt count cannot trigger a huge allocation).
  Status getCount(uint32_t& count, size_t itemSize, const char* what) {
    TESSERA_RETURN_IF_ERROR(get(count, what));
    if (static_cast<uint64_t>(count) * itemSize > size_ - offset_) {
      return parseError(source_ + ": " + what + " " + std::to_string(count) + " exceeds the remaining " +
                        std::to_string(size_ - offset_) + " bytes");
    }
    return Status::ok();
  }
  // An LEB128 varint of a value below 2^bits (1..64), in at most
  // ceil(bits / 7) bytes; anything longer or larger is refused.
  Status getVarint(uint64_t& value, int bits, const char* what) {
    value = 0;
    for (int shift = 0; shift < bits; shift += 7) {
      uint8_t byte = 0;
      TESSERA_RETURN_IF_ERROR(get(byte, what));
      const uint64_t payload = byte & 0x7f;
      if (bits - shift < 7 && (payload >> (bits - shift)) != 0) break;  // bits beyond the value's width
      value |= payload << shift;
      if ((byte & 0x80) == 0) return Status::ok();
    }
    return parseError(source_ + ": " + what + " is not a " + std::to_string(bits) + "-bit varint");
  }
  // Takes `size` bytes as they are (a blob inside the data).
  Status getBytes(std::string& out, size_t size, const char* what) {
    if (size_ - offset_ < size) {
      return parseError(source_ + ": " + what + " of " + std::to_string(size) +
                        " bytes exceeds the remaining " + std::to_string(size_ - offset_));
    }
    out.assign(data_ + offset_, size);
    offset_ += size;
    return Status::ok();
  }
  size_t offset() const { return offset_; }
  size_t remaining() const { return size_ - offset_; }
  const std::string& source() const { return source_; }

 private:
  const char* data_;
  size_t size_;
  size_t offset_ = 0;
  std::string source_;
};

}  // namespace tessera
