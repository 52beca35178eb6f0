// The tokens of USD's text format (usda), for the strict mesh reader
// (usda_reader.cc). Internal to core/io. Follows the grammar of Pixar's
// "USD file format" (crate's text twin, pxr/usd/sdf/textFileFormat.yy):
// `#`, `//` and `/* */` comments, strings in single, double or triple
// quotes, asset paths in `@`, path references in `<>`, numbers with a sign
// and an exponent (and inf / nan words), identifiers with `:` namespaces.
#pragma once

#include <string>
#include <string_view>

#include "core/util/status.h"

namespace tessera::io_detail {

struct UsdaToken {
  enum class Kind { kEnd, kIdentifier, kNumber, kString, kAssetPath, kPathRef, kPunct };
  Kind kind = Kind::kEnd;
  std::string_view text;     // a string's or asset path's contents, without quotes
  int line = 0, column = 0;  // 1-based
};

// Walks the text after the `#usda 1.0` line; next() and peek() give tokens
// in order, or a parse error naming the line and column.
class UsdaLexer {
 public:
  UsdaLexer(std::string_view text, std::string source, int firstLine, size_t firstOffset);

  Expected<UsdaToken> next();
  Expected<UsdaToken> peek();
  // "<source>:<line>:<column>: " of a token, the prefix of every error.
  std::string at(const UsdaToken& token) const;

 private:
  Status skipBlanksAndComments();
  Expected<UsdaToken> scan();

  std::string_view text_;
  std::string source_;
  size_t pos_ = 0;
  int line_ = 1;
  size_t lineStart_ = 0;
  bool peeked_ = false;
  UsdaToken peekedToken_;
};

}  // namespace tessera::io_detail
