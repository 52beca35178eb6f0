// Strict pre-scans of the text and binary mesh formats that OpenMesh reads
// leniently (see format_prescan.h for why).
#include "core/io/format_prescan.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <vector>

#include "core/util/text.h"
#include "core/util/vec3.h"

namespace tessera {
namespace {

// A whole-token number. OpenMesh parses coordinates as float, so a value
// outside float range would be dropped by it: report it instead.
bool parseNumber(const std::string& token, double& value) {
  const char* begin = token.data() + (token.size() > 1 && token[0] == '+' ? 1 : 0);
  const char* end = token.data() + token.size();
  auto [ptr, ec] = std::from_chars(begin, end, value);
  return ec == std::errc() && ptr == end;
}

bool parseInt(const std::string& token, int& value) {
  const char* end = token.data() + token.size();
  auto [ptr, ec] = std::from_chars(token.data(), end, value);
  return ec == std::errc() && ptr == end && !token.empty();
}

// "<src>:<line>: " -- the prefix of pre-scan errors.
std::string at(const std::string& src, int line) { return src + ":" + std::to_string(line) + ": "; }

// Checks one coordinate triple the way buildBaseMesh() would, but with the line.
Status checkCoordinates(const std::vector<std::string>& tokens, size_t first, const std::string& where,
                        const std::string& element) {
  double xyz[3];
  for (int k = 0; k < 3; ++k) {
    const std::string& token = tokens[first + k];
    if (!parseNumber(token, xyz[k])) {
      return parseError(where + element + ": bad coordinate '" + token + "'");
    }
  }
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(xyz[k])) {
      return invalidMesh(where + element + ": coordinate is " + (std::isnan(xyz[k]) ? "NaN" : "infinite"));
    }
    if (std::abs(xyz[k]) > std::numeric_limits<float>::max()) {
      return invalidMesh(where + element + ": coordinate " + tokens[first + k] + " is outside float range");
    }
  }
  return Status::ok();
}

Status checkNumeric(const std::vector<std::string>& tokens, size_t first, const std::string& where,
                    const std::string& element) {
  double unused;
  for (size_t k = first; k < tokens.size(); ++k) {
    if (!parseNumber(tokens[k], unused)) return parseError(where + element + ": unexpected '" + tokens[k] + "'");
  }
  return Status::ok();
}

bool isKeyword(const std::string& token) {
  return std::all_of(token.begin(), token.end(),
                     [](unsigned char c) { return std::isalnum(c) || c == '_'; });
}


Status prescanObjImpl(const std::string& text, const std::string& src, PrescanCounts& counts) {
  std::istringstream in(text);
  std::string line;
  int lineNumber = 0;
  while (std::getline(in, line)) {
    ++lineNumber;
    if (auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    const std::vector<std::string> tokens = splitTokens(line);
    if (tokens.empty()) continue;
    const std::string& key = tokens[0];
    const std::string where = at(src, lineNumber);
    if (key == "v") {
      const std::string element = "vertex " + std::to_string(counts.vertices);
      if (tokens.size() < 4) return parseError(where + element + ": expected 3 coordinates");
      if (tokens.size() > 8) return parseError(where + element + ": too many values");
      TESSERA_RETURN_IF_ERROR(checkCoordinates(tokens, 1, where, element));
      TESSERA_RETURN_IF_ERROR(checkNumeric(tokens, 4, where, element));
      ++counts.vertices;
    } else if (key == "vt" || key == "vn") {
      // OpenMesh fails the whole read on a short vt; say where.
      const size_t need = key == "vt" ? 2 : 3;
      if (tokens.size() < need + 1 || tokens.size() > 4) {
        return parseError(where + key + ": expected " + (key == "vt" ? "2 or 3" : "3") + " numbers");
      }
      TESSERA_RETURN_IF_ERROR(checkNumeric(tokens, 1, where, key));
    } else if (key == "f") {
      const std::string element = "face " + std::to_string(counts.faces);
      std::vector<int> face;
      for (size_t k = 1; k < tokens.size(); ++k) {
        // v, v/vt, v//vn or v/vt/vn: only the position index matters here.
        const std::string& token = tokens[k];
        const size_t slash = token.find('/');
        int index = 0;
        if (!parseInt(token.substr(0, slash), index) || index == 0) {
          return parseError(where + element + ": bad vertex reference '" + token +
                            "' (expected a non-zero integer, 1-based, optionally /vt/vn)");
        }
        if (slash != std::string::npos) {
          const std::string rest = token.substr(slash + 1);
          const size_t slash2 = rest.find('/');
          int unused = 0;
          const std::string vt = rest.substr(0, slash2);
          const std::string vn = slash2 == std::string::npos ? "" : rest.substr(slash2 + 1);
          if ((!vt.empty() && !parseInt(vt, unused)) || (!vn.empty() && !parseInt(vn, unused))) {
            return parseError(where + element + ": bad vertex reference '" + token + "'");
          }
        }
        if (index < 0) {
          // Relative to the vertices read so far, as OpenMesh resolves it.
          if (-index > static_cast<int>(counts.vertices)) {
            return invalidMesh(where + element + ": relative vertex index " + std::to_string(index) +
                               " points before the first vertex");
          }
          index += static_cast<int>(counts.vertices) + 1;
        }
        face.push_back(index - 1);
      }
      if (face.size() < 3) {
        return invalidMesh(where + element + ": has " + std::to_string(face.size()) +
                           " vertices, a face needs at least 3");
      }
      for (size_t a = 0; a < face.size(); ++a) {
        for (size_t b = a + 1; b < face.size(); ++b) {
          if (face[a] == face[b]) {
            std::string list;
            for (int v : face) list += (list.empty() ? "" : ", ") + std::to_string(v);
            return invalidMesh(where + element + " (vertices " + list + "): degenerate, repeats vertex " +
                               std::to_string(face[a]));
          }
        }
      }
      ++counts.faces;
    } else if (!isKeyword(key)) {
      return parseError(where + "unexpected '" + key.substr(0, 20) + "' (not an OBJ statement)");
    }
    // Other statements (o, g, s, usemtl, mtllib, l, p, ...) carry no geometry
    // Tessera uses; OpenMesh ignores them too.
  }
  return Status::ok();
}

// Validates ASCII OFF and returns it normalised (comments and blank lines
// removed, counts on their own line): OpenMesh's OFF reader knows no comments.
Status prescanOffImpl(const std::string& text, const std::string& src, PrescanCounts& counts, std::string& normalised) {
  std::istringstream in(text);
  std::string line;
  int lineNumber = 0;
  std::vector<std::string> pending;  // tokens of the header line after the keyword
  enum class Stage { kKeyword, kCounts, kVertices, kFaces, kDone } stage = Stage::kKeyword;
  size_t declaredVertices = 0, declaredFaces = 0;
  std::ostringstream out;
  while (stage != Stage::kDone && std::getline(in, line)) {
    ++lineNumber;
    if (auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::vector<std::string> tokens = splitTokens(line);
    if (tokens.empty()) continue;
    const std::string where = at(src, lineNumber);
    if (stage == Stage::kKeyword) {
      const std::string& key = tokens[0];
      if (key.size() < 3 || key.compare(key.size() - 3, 3, "OFF") != 0) {
        return parseError(where + "header: expected 'OFF', found '" + key.substr(0, 20) + "'");
      }
      const std::string prefix = key.substr(0, key.size() - 3);
      if (prefix != "" && prefix != "C" && prefix != "N" && prefix != "CN" && prefix != "ST" &&
          prefix != "STC" && prefix != "STN" && prefix != "STCN") {
        return unsupported(where + "header: OFF variant '" + key + "' is not supported");
      }
      if (tokens.size() > 1 && tokens[1] == "BINARY") {
        return unsupported(where + "header: binary OFF is not supported (use ASCII OFF or PLY)");
      }
      out << key << "\n";
      stage = Stage::kCounts;
      tokens.erase(tokens.begin());
      if (tokens.empty()) continue;
    }
    if (stage == Stage::kCounts) {
      int v = -1, f = -1, e = 0;
      if (tokens.size() < 2 || tokens.size() > 3 || !parseInt(tokens[0], v) || !parseInt(tokens[1], f) ||
          (tokens.size() == 3 && !parseInt(tokens[2], e)) || v < 0 || f < 0 || e < 0) {
        return parseError(where + "header: expected 'VERTICES FACES [EDGES]' counts");
      }
      declaredVertices = static_cast<size_t>(v);
      declaredFaces = static_cast<size_t>(f);
      out << v << " " << f << " 0\n";
      stage = declaredVertices > 0 ? Stage::kVertices : (declaredFaces > 0 ? Stage::kFaces : Stage::kDone);
      continue;
    }
    if (stage == Stage::kVertices) {
      const std::string element = "vertex " + std::to_string(counts.vertices);
      if (tokens.size() < 3) return parseError(where + element + ": expected 3 coordinates");
      TESSERA_RETURN_IF_ERROR(checkCoordinates(tokens, 0, where, element));
      TESSERA_RETURN_IF_ERROR(checkNumeric(tokens, 3, where, element));
      if (++counts.vertices == declaredVertices) stage = declaredFaces > 0 ? Stage::kFaces : Stage::kDone;
    } else if (stage == Stage::kFaces) {
      const std::string element = "face " + std::to_string(counts.faces);
      int n = 0;
      if (!parseInt(tokens[0], n) || n < 0) return parseError(where + element + ": bad corner count '" + tokens[0] + "'");
      if (n < 3) return invalidMesh(where + element + ": has " + std::to_string(n) + " vertices, a face needs at least 3");
      if (tokens.size() < static_cast<size_t>(n) + 1) {
        return parseError(where + element + ": expected " + std::to_string(n) + " vertex indices");
      }
      for (int k = 1; k <= n; ++k) {
        int index = 0;
        if (!parseInt(tokens[k], index)) return parseError(where + element + ": bad vertex index '" + tokens[k] + "'");
      }
      TESSERA_RETURN_IF_ERROR(checkNumeric(tokens, n + 1, where, element));  // optional colour
      if (++counts.faces == declaredFaces) stage = Stage::kDone;
      // The count and indices only: OpenMesh reads a face's colour into an
      // int, and an out-of-range one (a 40-digit number) left its stream
      // failed with a huge count for the next face, which it then filled
      // with vertex handles until memory ran out (found by fuzz_import_off).
      // Tessera keeps no face colours.
      for (int k = 0; k <= n; ++k) out << (k > 0 ? " " : "") << tokens[k];
      out << "\n";
      continue;
    }
    out << line << "\n";
  }
  if (stage == Stage::kKeyword || stage == Stage::kCounts) return parseError(src + ": header: truncated, no counts");
  if (stage != Stage::kDone) {
    return parseError(src + ": truncated: the header declares " + std::to_string(declaredVertices) +
                      " vertices and " + std::to_string(declaredFaces) + " faces, the file has " +
                      std::to_string(counts.vertices) + " and " + std::to_string(counts.faces));
  }
  while (std::getline(in, line)) {
    ++lineNumber;
    if (auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    if (!splitTokens(line).empty()) return parseError(at(src, lineNumber) + "unexpected data after the last face");
  }
  normalised = out.str();
  return Status::ok();
}

// PLY: the header is parsed strictly and the body walked element by element
// (ASCII: tokens per line; binary: byte sizes, list counts included), so that
// OpenMesh only ever sees a file whose structure is complete. Its reader
// otherwise keeps reading past a truncated or mistyped body, using garbage
// list counts (unbounded allocation) -- found by import_fuzz_test.
struct PlyProperty {
  int size = 0;       // bytes of a scalar, or of a list's items
  int countSize = 0;  // bytes of a list's count; 0 for scalars
};
struct PlyElement {
  std::string name;
  size_t count = 0;
  std::vector<PlyProperty> properties;
};

int plyTypeSize(const std::string& type) {
  static const std::vector<std::pair<std::string, int>> kTypes = {
      {"char", 1},  {"uchar", 1},  {"int8", 1},   {"uint8", 1},   {"short", 2},  {"ushort", 2},
      {"int16", 2}, {"uint16", 2}, {"int", 4},    {"uint", 4},    {"int32", 4},  {"uint32", 4},
      {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  for (const auto& [name, size] : kTypes) {
    if (name == type) return size;
  }
  return 0;
}

uint64_t readUnsigned(const unsigned char* p, int size, bool bigEndian) {
  uint64_t value = 0;
  for (int k = 0; k < size; ++k) value |= static_cast<uint64_t>(p[bigEndian ? size - 1 - k : k]) << (8 * k);
  return value;
}

Status walkPlyBody(const std::string& text, size_t bodyStart, const std::vector<PlyElement>& elements,
                   const std::string& format, const std::string& src) {
  if (format == "ascii") {
    std::istringstream in(text.substr(bodyStart));
    std::string line;
    for (const PlyElement& element : elements) {
      for (size_t i = 0; i < element.count; ++i) {
        const std::string name = element.name + " " + std::to_string(i);
        std::vector<std::string> tokens;
        while (tokens.empty() && std::getline(in, line)) tokens = splitTokens(line);
        if (tokens.empty()) return parseError(src + ": truncated: " + name + " is missing");
        size_t at = 0;
        for (const PlyProperty& property : element.properties) {
          int n = 1;
          if (property.countSize > 0 && (at >= tokens.size() || !parseInt(tokens[at++], n) || n < 0)) {
            return parseError(src + ": " + name + ": bad list length");
          }
          for (int k = 0; k < n; ++k, ++at) {
            double value;
            if (at >= tokens.size()) return parseError(src + ": " + name + ": too few values");
            if (!parseNumber(tokens[at], value)) return parseError(src + ": " + name + ": bad value '" + tokens[at] + "'");
          }
        }
        if (at != tokens.size()) return parseError(src + ": " + name + ": unexpected '" + tokens[at] + "'");
      }
    }
    return Status::ok();
  }
  const bool bigEndian = format == "binary_big_endian";
  const auto* data = reinterpret_cast<const unsigned char*>(text.data());
  size_t at = bodyStart;
  for (const PlyElement& element : elements) {
    for (size_t i = 0; i < element.count; ++i) {
      for (const PlyProperty& property : element.properties) {
        uint64_t n = 1;
        if (property.countSize > 0) {
          if (at + property.countSize > text.size()) break;
          n = readUnsigned(data + at, property.countSize, bigEndian);
          at += property.countSize;
        }
        if (n * property.size > text.size() - std::min(at, text.size())) {
          return parseError(src + ": truncated: " + element.name + " " + std::to_string(i) +
                            " runs past the end of the file");
        }
        at += n * property.size;
      }
      if (at > text.size()) {
        return parseError(src + ": truncated: " + element.name + " " + std::to_string(i) + " runs past the end of the file");
      }
    }
  }
  return Status::ok();
}

Status prescanPlyImpl(const std::string& text, const std::string& src, PrescanCounts& counts) {
  if (text.compare(0, 4, "ply\n") != 0 && text.compare(0, 5, "ply\r\n") != 0) {
    return parseError(src + ": header: missing 'ply' magic");
  }
  // The header ends at a line that is exactly "end_header" (OpenMesh's reader
  // loops forever on e.g. "end_headerx").
  const size_t end = text.find("\nend_header");
  if (end == std::string::npos) return parseError(src + ": header: truncated, no 'end_header'");
  size_t bodyStart = text.find('\n', end + 1);
  if (bodyStart == std::string::npos) return parseError(src + ": header: truncated after 'end_header'");
  const std::string endLine = text.substr(end + 1, bodyStart - end - 1);
  if (endLine != "end_header" && endLine != "end_header\r") {
    return parseError(src + ": header: bad 'end_header' line '" + endLine.substr(0, 30) + "'");
  }
  ++bodyStart;
  std::istringstream in(text.substr(0, end));
  std::string line, format;
  int lineNumber = 0;
  std::vector<PlyElement> elements;
  while (std::getline(in, line)) {
    ++lineNumber;
    const std::vector<std::string> tokens = splitTokens(line);
    const std::string where = at(src, lineNumber) + "header: ";
    if (tokens.empty() || lineNumber == 1 || tokens[0] == "comment" || tokens[0] == "obj_info") continue;
    if (tokens[0] == "format") {
      if (tokens.size() != 3 || tokens[2] != "1.0" ||
          (tokens[1] != "ascii" && tokens[1] != "binary_little_endian" && tokens[1] != "binary_big_endian")) {
        return parseError(where + "bad format line '" + line.substr(0, 60) + "'");
      }
      format = tokens[1];
    } else if (tokens[0] == "element") {
      int n = -1;
      if (tokens.size() != 3 || !parseInt(tokens[2], n) || n < 0) return parseError(where + "bad element line");
      elements.push_back({tokens[1], static_cast<size_t>(n), {}});
    } else if (tokens[0] == "property" && !elements.empty()) {
      PlyProperty property;
      if (tokens.size() == 5 && tokens[1] == "list") {
        property.countSize = plyTypeSize(tokens[2]);
        property.size = plyTypeSize(tokens[3]);
        if (property.countSize == 0 || property.countSize > 4 || property.size == 0) {
          return parseError(where + "bad list property types '" + tokens[2] + " " + tokens[3] + "'");
        }
      } else if (tokens.size() == 3) {
        property.size = plyTypeSize(tokens[1]);
        if (property.size == 0) return parseError(where + "unknown property type '" + tokens[1] + "'");
      } else {
        return parseError(where + "bad property line");
      }
      elements.back().properties.push_back(property);
    } else {
      return parseError(where + "unexpected '" + tokens[0].substr(0, 20) + "'");
    }
  }
  if (format.empty()) return parseError(src + ": header: no 'format' line");
  bool haveVertex = false, haveFace = false;
  for (const PlyElement& element : elements) {
    if (element.name == "vertex") counts.vertices = element.count, haveVertex = true;
    if (element.name == "face") counts.faces = element.count, haveFace = true;
  }
  if (!haveVertex || !haveFace) return parseError(src + ": header: needs 'element vertex' and 'element face'");
  return walkPlyBody(text, bodyStart, elements, format, src);
}

// STL has no indices: OpenMesh merges identical corner positions, and drops
// facets whose corners coincide. Check facets here so that is an error.
Status checkFacet(const std::array<Vec3, 3>& corners, size_t facet, const std::string& where) {
  const std::string element = "facet " + std::to_string(facet);
  for (int k = 0; k < 3; ++k) {
    if (!isFinite(corners[k])) return invalidMesh(where + element + ": corner " + std::to_string(k) + " is not finite");
  }
  for (int a = 0; a < 3; ++a) {
    for (int b = a + 1; b < 3; ++b) {
      if (corners[a] == corners[b]) {
        return invalidMesh(where + element + ": degenerate, corners " + std::to_string(a) + " and " +
                           std::to_string(b) + " are the same point");
      }
    }
  }
  return Status::ok();
}

Status prescanStlImpl(const std::string& text, const std::string& src, PrescanCounts& counts) {
  uint32_t declared = 0;
  if (text.size() >= 84) std::memcpy(&declared, text.data() + 80, 4);
  if (text.size() >= 84 && text.size() == 84 + 50 * static_cast<uint64_t>(declared)) {
    for (uint32_t i = 0; i < declared; ++i) {
      std::array<Vec3, 3> corners;
      for (int k = 0; k < 3; ++k) {
        float xyz[3];
        std::memcpy(xyz, text.data() + 84 + 50 * static_cast<size_t>(i) + 12 + 12 * k, sizeof xyz);
        corners[k] = Vec3(xyz[0], xyz[1], xyz[2]);
      }
      TESSERA_RETURN_IF_ERROR(checkFacet(corners, i, src + ": "));
    }
    counts.faces = declared;
    return Status::ok();
  }
  const size_t first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos || text.compare(first, 5, "solid") != 0) {
    return parseError(src + ": neither ASCII STL (starting with 'solid') nor binary STL (84 + 50 * N bytes)" +
                      (text.size() >= 84 ? ", binary header declares " + std::to_string(declared) + " facets" : ""));
  }
  // ASCII: a strict walk over the expected keyword sequence.
  std::istringstream in(text);
  std::string line;
  int lineNumber = 0;
  int corner = -1;  // -1: outside a facet
  std::array<Vec3, 3> corners;
  bool ended = false;
  while (!ended && std::getline(in, line)) {
    ++lineNumber;
    const std::vector<std::string> tokens = splitTokens(line);
    if (tokens.empty()) continue;
    const std::string where = at(src, lineNumber);
    const std::string& key = tokens[0];
    const std::string element = "facet " + std::to_string(counts.faces);
    if (key == "solid" && lineNumber == static_cast<int>(std::count(text.begin(), text.begin() + first, '\n')) + 1) {
      continue;
    } else if (key == "facet" && corner == -1) {
      if (tokens.size() != 5 || tokens[1] != "normal") return parseError(where + element + ": expected 'facet normal X Y Z'");
      TESSERA_RETURN_IF_ERROR(checkNumeric(tokens, 2, where, element));
      corner = 0;
    } else if (key == "outer" || key == "endloop") {
      if (corner == -1) return parseError(where + "'" + key + "' outside a facet");
    } else if (key == "vertex" && corner >= 0 && corner < 3) {
      if (tokens.size() != 4) return parseError(where + element + ": expected 'vertex X Y Z'");
      TESSERA_RETURN_IF_ERROR(checkCoordinates(tokens, 1, where, element));
      double xyz[3];
      for (int k = 0; k < 3; ++k) parseNumber(tokens[1 + k], xyz[k]);
      // OpenMesh stores STL corners as float; compare them as it will.
      corners[corner++] = Vec3(float(xyz[0]), float(xyz[1]), float(xyz[2]));
    } else if (key == "endfacet" && corner == 3) {
      TESSERA_RETURN_IF_ERROR(checkFacet(corners, counts.faces, where));
      ++counts.faces;
      corner = -1;
    } else if (key == "endsolid" && corner == -1) {
      ended = true;
    } else {
      return parseError(where + "unexpected '" + key.substr(0, 20) + "'" +
                        (corner >= 0 ? " in " + element : std::string()));
    }
  }
  if (!ended) return parseError(src + ": truncated, no 'endsolid' (" + std::to_string(counts.faces) + " complete facets)");
  return Status::ok();
}

}  // namespace

Status prescanObj(const std::string& text, const std::string& src, PrescanCounts& counts) {
  return prescanObjImpl(text, src, counts);
}
Status prescanOff(const std::string& text, const std::string& src, PrescanCounts& counts, std::string& normalised) {
  return prescanOffImpl(text, src, counts, normalised);
}
Status prescanPly(const std::string& text, const std::string& src, PrescanCounts& counts) {
  return prescanPlyImpl(text, src, counts);
}
Status prescanStl(const std::string& text, const std::string& src, PrescanCounts& counts) {
  return prescanStlImpl(text, src, counts);
}

}  // namespace tessera
