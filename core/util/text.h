// Small text helpers shared by the line-oriented parsers (tag files, the
// OBJ/OFF/PLY/STL pre-scans).
#pragma once

#include <sstream>
#include <string>
#include <vector>

namespace tessera {

// Whitespace-separated tokens of one line.
inline std::vector<std::string> splitTokens(const std::string& line) {
  std::vector<std::string> tokens;
  std::istringstream in(line);
  std::string token;
  while (in >> token) tokens.push_back(token);
  return tokens;
}

}  // namespace tessera
