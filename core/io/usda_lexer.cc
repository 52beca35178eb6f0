#include "core/io/usda_lexer.h"

#include <cctype>

namespace tessera::io_detail {
namespace {

bool isIdentifierStart(char c) {
  return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}
bool isIdentifierPart(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == ':';
}
bool isNumberPart(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '+' || c == '-';
}

}  // namespace

UsdaLexer::UsdaLexer(std::string_view text, std::string source, int firstLine, size_t firstOffset)
    : text_(text), source_(std::move(source)), pos_(firstOffset), line_(firstLine), lineStart_(firstOffset) {}

std::string UsdaLexer::at(const UsdaToken& token) const {
  return source_ + ":" + std::to_string(token.line) + ":" + std::to_string(token.column) + ": ";
}

Status UsdaLexer::skipBlanksAndComments() {
  while (pos_ < text_.size()) {
    const char c = text_[pos_];
    if (c == '\n') {
      ++pos_;
      ++line_;
      lineStart_ = pos_;
    } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
      ++pos_;
    } else if (c == '#' || text_.substr(pos_, 2) == "//") {
      while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    } else if (text_.substr(pos_, 2) == "/*") {
      const int startLine = line_;
      const size_t end = text_.find("*/", pos_ + 2);
      if (end == std::string_view::npos)
        return parseError(source_ + ":" + std::to_string(startLine) + ": a /* comment is never closed");
      for (size_t k = pos_; k < end; ++k) {
        if (text_[k] == '\n') {
          ++line_;
          lineStart_ = k + 1;
        }
      }
      pos_ = end + 2;
    } else {
      return Status::ok();
    }
  }
  return Status::ok();
}

Expected<UsdaToken> UsdaLexer::peek() {
  if (!peeked_) {
    TESSERA_ASSIGN_OR_RETURN(peekedToken_, scan());
    peeked_ = true;
  }
  return peekedToken_;
}

Expected<UsdaToken> UsdaLexer::next() {
  if (peeked_) {
    peeked_ = false;
    return peekedToken_;
  }
  return scan();
}

Expected<UsdaToken> UsdaLexer::scan() {
  TESSERA_RETURN_IF_ERROR(skipBlanksAndComments());
  UsdaToken token;
  token.line = line_;
  token.column = static_cast<int>(pos_ - lineStart_) + 1;
  if (pos_ >= text_.size()) return token;  // kEnd
  const char c = text_[pos_];
  const size_t start = pos_;
  if (c == '"' || c == '\'') {
    // Triple quotes may span lines; single ones may not.
    const std::string quote =
        text_.substr(pos_, 3) == std::string(3, c) ? std::string(3, c) : std::string(1, c);
    pos_ += quote.size();
    const size_t contentStart = pos_;
    while (true) {
      if (pos_ >= text_.size() || (quote.size() == 1 && text_[pos_] == '\n'))
        return parseError(at(token) + "a string is never closed");
      if (text_[pos_] == '\\') {
        pos_ += 2;
        continue;
      }
      if (text_.substr(pos_, quote.size()) == quote) break;
      if (text_[pos_] == '\n') {
        ++line_;
        lineStart_ = pos_ + 1;
      }
      ++pos_;
    }
    token.kind = UsdaToken::Kind::kString;
    token.text = text_.substr(contentStart, pos_ - contentStart);
    pos_ += quote.size();
    return token;
  }
  if (c == '@') {
    const bool triple = text_.substr(pos_, 3) == "@@@";
    const std::string_view quote = triple ? "@@@" : "@";
    const size_t end = text_.find(quote, pos_ + quote.size());
    if (end == std::string_view::npos || text_.substr(pos_, end - pos_).find('\n') != std::string_view::npos)
      return parseError(at(token) + "an asset path (@...@) is never closed");
    token.kind = UsdaToken::Kind::kAssetPath;
    token.text = text_.substr(pos_ + quote.size(), end - pos_ - quote.size());
    pos_ = end + quote.size();
    return token;
  }
  if (c == '<') {
    const size_t end = text_.find('>', pos_);
    if (end == std::string_view::npos || text_.substr(pos_, end - pos_).find('\n') != std::string_view::npos)
      return parseError(at(token) + "a path (<...>) is never closed");
    token.kind = UsdaToken::Kind::kPathRef;
    token.text = text_.substr(pos_ + 1, end - pos_ - 1);
    pos_ = end + 1;
    return token;
  }
  if (std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' ||
      (c == '.' && pos_ + 1 < text_.size() && std::isdigit(static_cast<unsigned char>(text_[pos_ + 1])))) {
    ++pos_;
    // Digits, a point, an exponent with its sign; `-inf` and `-nan` too.
    while (
        pos_ < text_.size() && isNumberPart(text_[pos_]) &&
        !((text_[pos_] == '+' || text_[pos_] == '-') && !(text_[pos_ - 1] == 'e' || text_[pos_ - 1] == 'E')))
      ++pos_;
    token.kind = UsdaToken::Kind::kNumber;
    token.text = text_.substr(start, pos_ - start);
    return token;
  }
  if (isIdentifierStart(c)) {
    while (pos_ < text_.size() && isIdentifierPart(text_[pos_])) ++pos_;
    token.kind = UsdaToken::Kind::kIdentifier;
    token.text = text_.substr(start, pos_ - start);
    return token;
  }
  if (std::string_view("()[]{}=,;.").find(c) != std::string_view::npos) {
    ++pos_;
    token.kind = UsdaToken::Kind::kPunct;
    token.text = text_.substr(start, 1);
    return token;
  }
  return parseError(at(token) + "unexpected character '" + std::string(1, c) + "'");
}

}  // namespace tessera::io_detail
