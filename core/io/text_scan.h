// Line and token scanning shared by the text mesh readers (OBJ, OFF, ASCII
// PLY, ASCII STL). Internal to core/io.
//
// Numbers are parsed with std::from_chars, which rounds correctly (as strtod
// does): a coordinate keeps every bit the file's decimal text gives a double.
// Tokens are views into the file's text: a reader allocates nothing per line.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "core/util/status.h"

namespace tessera::io_detail {

// A coordinate larger than this is refused: the exports, the wire format and
// the viewer hold positions as float, and squares of larger values overflow
// the checks (areas, bounding boxes) that validation does in double.
inline constexpr double kMaxCoordinate = std::numeric_limits<float>::max();

inline bool isBlank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

// Splits `line` at blanks into `tokens` (cleared first).
inline void splitLine(std::string_view line, std::vector<std::string_view>& tokens) {
  tokens.clear();
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && isBlank(line[i])) ++i;
    const size_t start = i;
    while (i < line.size() && !isBlank(line[i])) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
}

// Walks `text` line by line, counting lines from 1.
class LineCursor {
 public:
  explicit LineCursor(std::string_view text) : text_(text) {}
  // The next line without its '\n'; false at the end.
  bool next(std::string_view& line) {
    if (at_ >= text_.size()) return false;
    const size_t end = text_.find('\n', at_);
    const size_t stop = end == std::string_view::npos ? text_.size() : end;
    line = text_.substr(at_, stop - at_);
    at_ = stop + 1;
    ++lineNumber_;
    return true;
  }
  int lineNumber() const { return lineNumber_; }

 private:
  std::string_view text_;
  size_t at_ = 0;
  int lineNumber_ = 0;
};

// The line with any '#' comment removed.
inline std::string_view withoutComment(std::string_view line) {
  const size_t hash = line.find('#');
  return hash == std::string_view::npos ? line : line.substr(0, hash);
}

// A whole-token decimal number (a leading '+' allowed), correctly rounded.
inline bool parseNumber(std::string_view token, double& value) {
  if (token.size() > 1 && token[0] == '+') token.remove_prefix(1);
  const char* end = token.data() + token.size();
  auto [ptr, ec] = std::from_chars(token.data(), end, value);
  return ec == std::errc() && ptr == end;
}

// A whole-token integer that fits in `int`.
inline bool parseInt(std::string_view token, int& value) {
  if (token.empty()) return false;
  const char* end = token.data() + token.size();
  auto [ptr, ec] = std::from_chars(token.data(), end, value);
  return ec == std::errc() && ptr == end;
}

// "<src>:<line>: " -- the prefix of a reader's errors.
inline std::string at(const std::string& src, int line) {
  return src + ":" + std::to_string(line) + ": ";
}

inline std::string clip(std::string_view token, size_t length = 20) {
  return std::string(token.substr(0, length));
}

// Parses three coordinates from tokens[first..first+3): each a number, finite
// and within kMaxCoordinate; errors say "<where><element>: ...", but for a
// number that is not finite "<where>bad coordinate '<token>' of <element>: NaN"
// (or infinite).
inline Status parseCoordinates(const std::vector<std::string_view>& tokens, size_t first,
                               const std::string& where, const std::string& element, double xyz[3]) {
  for (int k = 0; k < 3; ++k) {
    if (!parseNumber(tokens[first + k], xyz[k])) {
      return parseError(where + element + ": bad coordinate '" + clip(tokens[first + k], 40) + "'");
    }
  }
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(xyz[k])) {
      return invalidMesh(where + "bad coordinate '" + clip(tokens[first + k], 40) + "' of " + element + ": " +
                         (std::isnan(xyz[k]) ? "NaN" : "infinite"));
    }
    if (std::abs(xyz[k]) > kMaxCoordinate) {
      return invalidMesh(where + element + ": coordinate " + clip(tokens[first + k], 40) +
                         " is outside float range (|x| <= 3.4e38)");
    }
  }
  return Status::ok();
}

// Every token from `first` on must be a number (colours, weights).
inline Status checkNumeric(const std::vector<std::string_view>& tokens, size_t first,
                           const std::string& where, const std::string& element) {
  double unused;
  for (size_t k = first; k < tokens.size(); ++k) {
    if (!parseNumber(tokens[k], unused))
      return parseError(where + element + ": unexpected '" + clip(tokens[k]) + "'");
  }
  return Status::ok();
}

}  // namespace tessera::io_detail
