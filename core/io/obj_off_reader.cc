// OBJ and ASCII OFF readers (see text_mesh_readers.h for why Tessera reads
// them itself).
#include <algorithm>

#include "core/io/text_mesh_readers.h"
#include "core/io/text_scan.h"

namespace tessera::io_detail {
namespace {

bool isKeyword(std::string_view token) {
  return std::all_of(token.begin(), token.end(), [](unsigned char c) { return std::isalnum(c) || c == '_'; });
}

std::string listOf(const std::vector<int>& face) {
  std::string list;
  for (int v : face) list += (list.empty() ? "" : ", ") + std::to_string(v);
  return list;
}

// A face naming a vertex twice is reported here, where the line is known.
Status checkRepeats(const std::vector<int>& face, const std::string& where, const std::string& element) {
  for (size_t a = 0; a < face.size(); ++a) {
    for (size_t b = a + 1; b < face.size(); ++b) {
      if (face[a] == face[b]) {
        return invalidMesh(where + element + " (vertices " + listOf(face) + "): degenerate, repeats vertex " +
                           std::to_string(face[a]));
      }
    }
  }
  return Status::ok();
}

// One OBJ face corner: v, v/vt, v//vn or v/vt/vn. Returns the 0-based index.
Status parseObjCorner(std::string_view token, int vertexCount, const std::string& where,
                      const std::string& element, int& index) {
  const size_t slash = token.find('/');
  if (!parseInt(token.substr(0, slash), index) || index == 0) {
    return parseError(where + element + ": bad vertex reference '" + clip(token, 40) +
                      "' (expected a non-zero integer, 1-based, optionally /vt/vn)");
  }
  if (slash != std::string_view::npos) {
    const std::string_view rest = token.substr(slash + 1);
    const size_t slash2 = rest.find('/');
    const std::string_view vt = rest.substr(0, slash2);
    const std::string_view vn =
        slash2 == std::string_view::npos ? std::string_view() : rest.substr(slash2 + 1);
    int unused = 0;
    if ((!vt.empty() && !parseInt(vt, unused)) || (!vn.empty() && !parseInt(vn, unused))) {
      return parseError(where + element + ": bad vertex reference '" + clip(token, 40) + "'");
    }
  }
  if (index < 0) {
    // Relative to the vertices read so far.
    if (-static_cast<long long>(index) > vertexCount) {
      return invalidMesh(where + element + ": relative vertex index " + std::to_string(index) +
                         " points before the first vertex");
    }
    index += vertexCount + 1;
  }
  index -= 1;
  return Status::ok();
}

// `t NAME I/F/S` then I integers, F floats and S strings: a subdivision tag
// in OpenSubdiv's dialect (its regression shapes; docs/FORMATS.md "Tags in
// OBJ"). Creases and corners become soup tags; the boundary rule and the
// crease method become the soup's options; any other tag is refused by
// name, since dropping it would change the surface unsaid.
Status readObjTag(const std::vector<std::string_view>& tokens, const std::string& where, int line,
                  PolygonSoup& soup) {
  if (tokens.size() < 3) return parseError(where + "t: expected a tag name and its counts I/F/S");
  const std::string name(tokens[1]);
  const std::string what = where + "t " + clip(tokens[1]) + ": ";
  int counts[3] = {0, 0, 0};
  {
    const std::string_view c = tokens[2];
    const size_t a = c.find('/'), b = a == std::string_view::npos ? a : c.find('/', a + 1);
    if (b == std::string_view::npos || !parseInt(c.substr(0, a), counts[0]) ||
        !parseInt(c.substr(a + 1, b - a - 1), counts[1]) || !parseInt(c.substr(b + 1), counts[2]) ||
        counts[0] < 0 || counts[1] < 0 || counts[2] < 0)
      return parseError(what + "expected counts I/F/S, found '" + clip(c) + "'");
  }
  const size_t given = tokens.size() - 3, wanted = static_cast<size_t>(counts[0] + counts[1] + counts[2]);
  if (given != wanted)
    return parseError(what + std::to_string(wanted) + " values announced, " + std::to_string(given) +
                      " given");
  std::vector<int> ints(static_cast<size_t>(counts[0]));
  for (int k = 0; k < counts[0]; ++k) {
    if (!parseInt(tokens[3 + k], ints[k]) || ints[k] < 0)
      return parseError(what + "integer " + std::to_string(k + 1) + " is not a vertex number: '" +
                        clip(tokens[3 + k]) + "'");
  }
  std::vector<float> floats(static_cast<size_t>(counts[1]));
  for (int k = 0; k < counts[1]; ++k) {
    const std::string_view t = tokens[3 + counts[0] + k];
    double value = 0;
    if (!parseNumber(t, value) || !(value >= 0))
      return parseError(what + "sharpness " + std::to_string(k + 1) + " is not a number >= 0: '" + clip(t) +
                        "'");
    floats[k] = static_cast<float>(value);
  }
  const std::string_view text = counts[2] == 1 ? tokens[3 + counts[0] + counts[1]] : std::string_view();
  if (name == "crease") {
    // Pairs of vertices: one sharpness for all, or one per pair.
    const int pairs = counts[0] / 2;
    if (counts[0] < 2 || counts[0] % 2 != 0 || counts[2] != 0 || (counts[1] != 1 && counts[1] != pairs))
      return parseError(what + "expected pairs of vertices and 1 sharpness or one per pair (2/1/0)");
    for (int k = 0; k < pairs; ++k)
      soup.tags.push_back({true, ints[2 * k], ints[2 * k + 1], floats[counts[1] == 1 ? 0 : k], line});
  } else if (name == "corner") {
    if (counts[0] < 1 || counts[2] != 0 || (counts[1] != 1 && counts[1] != counts[0]))
      return parseError(what + "expected vertices and 1 sharpness or one per vertex (1/1/0)");
    for (int k = 0; k < counts[0]; ++k)
      soup.tags.push_back({false, ints[k], -1, floats[counts[1] == 1 ? 0 : k], line});
  } else if (name == "interpolateboundary") {
    if (counts[0] != 1 || counts[1] != 0 || counts[2] != 0)
      return parseError(what + "expected one integer (1/0/0)");
    // OpenSubdiv's numbers: 0 none, 1 edge and corner, 2 edge only.
    if (ints[0] == 1) {
      soup.boundary = "edge-and-corner";
    } else if (ints[0] == 2) {
      soup.boundary = "edge-only";
    } else {
      return unsupported(what + std::to_string(ints[0]) +
                         ": only 1 (edge and corner) and 2 (edge only) are supported");
    }
  } else if (name == "creasemethod") {
    if (counts[0] != 0 || counts[1] != 0 || counts[2] != 1)
      return parseError(what + "expected one string (0/0/1)");
    if (text == "normal") {
      soup.creaseMethod = "uniform";
    } else if (text == "chaikin") {
      soup.creaseMethod = "chaikin";
    } else {
      return parseError(what + "expected normal or chaikin, found '" + clip(text) + "'");
    }
  } else {
    return unsupported(what +
                       "this tag is not supported (crease, corner, interpolateboundary and "
                       "creasemethod are)");
  }
  return Status::ok();
}

}  // namespace

Status readObj(std::string_view text, const std::string& src, PolygonSoup& soup,
               const TextReadOptions& options) {
  if (text.find('\0') != std::string_view::npos)
    return parseError(src + ": binary data, not a text OBJ file");
  LineCursor cursor(text);
  std::string_view line;
  std::vector<std::string_view> tokens;
  std::vector<int> face;
  while (cursor.next(line)) {
    splitLine(withoutComment(line), tokens);
    if (tokens.empty()) continue;
    const std::string_view key = tokens[0];
    if (key == "v") {
      const std::string where = at(src, cursor.lineNumber());
      const std::string element = "vertex " + std::to_string(soup.points.size());
      if (tokens.size() < 4) return parseError(where + element + ": expected 3 coordinates");
      if (tokens.size() > 8) return parseError(where + element + ": too many values");
      double xyz[3];
      TESSERA_RETURN_IF_ERROR(parseCoordinates(tokens, 1, where, element, xyz));
      TESSERA_RETURN_IF_ERROR(checkNumeric(tokens, 4, where, element));  // w, or a colour
      soup.points.emplace_back(xyz[0], xyz[1], xyz[2]);
    } else if (key == "vt" || key == "vn") {
      const size_t need = key == "vt" ? 1 : 3;  // vt: u [v [w]]
      if (tokens.size() < need + 1 || tokens.size() > 4) {
        return parseError(at(src, cursor.lineNumber()) + std::string(key) + ": expected " +
                          (key == "vt" ? "1 to 3" : "3") + " numbers");
      }
      TESSERA_RETURN_IF_ERROR(checkNumeric(tokens, 1, at(src, cursor.lineNumber()), std::string(key)));
    } else if (key == "f") {
      const std::string where = at(src, cursor.lineNumber());
      const std::string element = "face " + std::to_string(soup.numFaces());
      face.clear();
      const int vertexCount = static_cast<int>(soup.points.size());
      for (size_t k = 1; k < tokens.size(); ++k) {
        int index = 0;
        TESSERA_RETURN_IF_ERROR(parseObjCorner(tokens[k], vertexCount, where, element, index));
        if (options.checkIndices && index >= vertexCount) {
          return parseError(where + "vertex index " + clip(tokens[k].substr(0, tokens[k].find('/'))) +
                            " names no vertex read so far (" + std::to_string(vertexCount) + ")");
        }
        face.push_back(index);
      }
      if (face.size() < 3) {
        return invalidMesh(where + element + ": has " + std::to_string(face.size()) +
                           " vertices, a face needs at least 3");
      }
      TESSERA_RETURN_IF_ERROR(checkRepeats(face, where, element));
      soup.addFace(face);
    } else if (key == "t") {
      TESSERA_RETURN_IF_ERROR(readObjTag(tokens, at(src, cursor.lineNumber()), cursor.lineNumber(), soup));
    } else if (!isKeyword(key)) {
      return parseError(at(src, cursor.lineNumber()) + "unexpected '" + clip(key) +
                        "' (not an OBJ statement)");
    }
    // Other statements (o, g, s, usemtl, mtllib, l, p, ...) carry no geometry
    // Tessera uses.
  }
  return Status::ok();
}

Status readOff(std::string_view text, const std::string& src, PolygonSoup& soup,
               const TextReadOptions& options) {
  if (text.find('\0') != std::string_view::npos)
    return parseError(src + ": binary data, not a text OFF file");
  LineCursor cursor(text);
  std::string_view line;
  std::vector<std::string_view> tokens;
  std::vector<int> face;
  enum class Stage { kKeyword, kCounts, kVertices, kFaces, kDone } stage = Stage::kKeyword;
  size_t declaredVertices = 0, declaredFaces = 0;
  while (stage != Stage::kDone && cursor.next(line)) {
    splitLine(withoutComment(line), tokens);
    if (tokens.empty()) continue;
    const std::string where = at(src, cursor.lineNumber());
    size_t first = 0;  // the first token of this line still to read
    if (stage == Stage::kKeyword) {
      const std::string_view key = tokens[0];
      if (key.size() < 3 || key.substr(key.size() - 3) != "OFF") {
        return parseError(where + "header: expected 'OFF', found '" + clip(key) + "'");
      }
      const std::string_view prefix = key.substr(0, key.size() - 3);
      if (prefix != "" && prefix != "C" && prefix != "N" && prefix != "CN" && prefix != "ST" &&
          prefix != "STC" && prefix != "STN" && prefix != "STCN") {
        return unsupported(where + "header: OFF variant '" + clip(key) + "' is not supported");
      }
      if (tokens.size() > 1 && tokens[1] == "BINARY") {
        return unsupported(where + "header: binary OFF is not supported (use ASCII OFF or PLY)");
      }
      stage = Stage::kCounts;
      if (tokens.size() == 1) continue;
      first = 1;  // "OFF 8 12 0" on one line
    }
    if (stage == Stage::kCounts) {
      const size_t n = tokens.size() - first;
      int v = -1, f = -1, e = 0;
      if (n < 2 || n > 3 || !parseInt(tokens[first], v) || !parseInt(tokens[first + 1], f) ||
          (n == 3 && !parseInt(tokens[first + 2], e)) || v < 0 || f < 0 || e < 0) {
        return parseError(where + "header: expected 'VERTICES FACES [EDGES]' counts");
      }
      declaredVertices = static_cast<size_t>(v);
      declaredFaces = static_cast<size_t>(f);
      stage = declaredVertices > 0 ? Stage::kVertices : (declaredFaces > 0 ? Stage::kFaces : Stage::kDone);
    } else if (stage == Stage::kVertices) {
      const std::string element = "vertex " + std::to_string(soup.points.size());
      if (tokens.size() < 3) return parseError(where + element + ": expected 3 coordinates");
      double xyz[3];
      TESSERA_RETURN_IF_ERROR(parseCoordinates(tokens, 0, where, element, xyz));
      TESSERA_RETURN_IF_ERROR(checkNumeric(tokens, 3, where, element));  // normal, colour, texture
      soup.points.emplace_back(xyz[0], xyz[1], xyz[2]);
      if (soup.points.size() == declaredVertices) stage = declaredFaces > 0 ? Stage::kFaces : Stage::kDone;
    } else {
      const std::string element = "face " + std::to_string(soup.numFaces());
      int n = 0;
      if (!parseInt(tokens[0], n) || n < 0)
        return parseError(where + element + ": bad corner count '" + clip(tokens[0]) + "'");
      if (n < 3)
        return invalidMesh(where + element + ": has " + std::to_string(n) +
                           " vertices, a face needs at least 3");
      if (tokens.size() < static_cast<size_t>(n) + 1) {
        return parseError(where + element + ": expected " + std::to_string(n) + " vertex indices");
      }
      face.clear();
      for (int k = 1; k <= n; ++k) {
        int index = 0;
        if (!parseInt(tokens[k], index))
          return parseError(where + element + ": bad vertex index '" + clip(tokens[k]) + "'");
        if (options.checkIndices && (index < 0 || static_cast<size_t>(index) >= declaredVertices)) {
          return parseError(where + "bad vertex index '" + clip(tokens[k]) + "' (0.." +
                            std::to_string(static_cast<long long>(declaredVertices) - 1) + ")");
        }
        face.push_back(index);
      }
      TESSERA_RETURN_IF_ERROR(checkNumeric(tokens, n + 1, where, element));  // an optional colour, ignored
      TESSERA_RETURN_IF_ERROR(checkRepeats(face, where, element));
      soup.addFace(face);
      if (static_cast<size_t>(soup.numFaces()) == declaredFaces) stage = Stage::kDone;
    }
  }
  if (stage == Stage::kKeyword || stage == Stage::kCounts)
    return parseError(src + ": header: truncated, no counts");
  if (stage == Stage::kVertices) {
    return parseError(src + ": truncated: " + std::to_string(soup.points.size()) + " of " +
                      std::to_string(declaredVertices) + " vertices");
  }
  if (stage != Stage::kDone) {
    return parseError(src + ": truncated: " + std::to_string(soup.numFaces()) + " of " +
                      std::to_string(declaredFaces) + " faces");
  }
  while (cursor.next(line)) {
    splitLine(withoutComment(line), tokens);
    if (!tokens.empty())
      return parseError(at(src, cursor.lineNumber()) + "unexpected data after the last face");
  }
  return Status::ok();
}

}  // namespace tessera::io_detail
