// STL reader (see text_mesh_readers.h): facets to an indexed soup, welding
// corners with equal positions.
#include <array>
#include <cstring>
#include <map>
#include <tuple>

#include "core/io/text_mesh_readers.h"
#include "core/io/text_scan.h"

namespace tessera::io_detail {
namespace {

using Corner = std::array<float, 3>;

// Welds corners to vertices numbered by first appearance.
class Welder {
 public:
  explicit Welder(PolygonSoup& soup) : soup_(soup) {}
  // A facet whose corners coincide is refused; `where` prefixes the error.
  Status addFacet(const std::array<Corner, 3>& corners, size_t facet, const std::string& where) {
    const std::string element = "facet " + std::to_string(facet);
    for (int k = 0; k < 3; ++k) {
      for (float c : corners[k]) {
        if (!std::isfinite(c))
          return invalidMesh(where + element + ": corner " + std::to_string(k) + " is not finite");
      }
    }
    for (int a = 0; a < 3; ++a) {
      for (int b = a + 1; b < 3; ++b) {
        if (corners[a] == corners[b]) {
          return invalidMesh(where + element + ": degenerate, corners " + std::to_string(a) + " and " +
                             std::to_string(b) + " are the same point");
        }
      }
    }
    std::vector<int> face(3);
    for (int k = 0; k < 3; ++k) {
      auto [it, inserted] = index_.emplace(corners[k], static_cast<int>(soup_.points.size()));
      if (inserted) soup_.points.emplace_back(corners[k][0], corners[k][1], corners[k][2]);
      face[k] = it->second;
    }
    soup_.addFace(face);
    return Status::ok();
  }

 private:
  PolygonSoup& soup_;
  std::map<Corner, int> index_;
};

Status readBinaryStl(std::string_view text, const std::string& src, uint32_t facets, PolygonSoup& soup) {
  Welder welder(soup);
  for (uint32_t i = 0; i < facets; ++i) {
    std::array<Corner, 3> corners;
    for (int k = 0; k < 3; ++k) {
      std::memcpy(corners[k].data(), text.data() + 84 + 50 * static_cast<size_t>(i) + 12 + 12 * k, 12);
    }
    TESSERA_RETURN_IF_ERROR(welder.addFacet(corners, i, src + ": "));
  }
  return Status::ok();
}

// A strict walk over the keyword sequence of ASCII STL.
Status readAsciiStl(std::string_view text, const std::string& src, PolygonSoup& soup) {
  Welder welder(soup);
  LineCursor cursor(text);
  std::string_view line;
  std::vector<std::string_view> tokens;
  int corner = -1;  // -1: outside a facet
  std::array<Corner, 3> corners;
  bool started = false, ended = false;
  while (!ended && cursor.next(line)) {
    splitLine(line, tokens);
    if (tokens.empty()) continue;
    const std::string where = at(src, cursor.lineNumber());
    const std::string_view key = tokens[0];
    const std::string element = "facet " + std::to_string(soup.numFaces());
    if (!started) {
      if (key != "solid") return parseError(where + "expected 'solid', found '" + clip(key) + "'");
      started = true;
    } else if (key == "facet" && corner == -1) {
      if (tokens.size() != 5 || tokens[1] != "normal")
        return parseError(where + element + ": expected 'facet normal X Y Z'");
      TESSERA_RETURN_IF_ERROR(checkNumeric(tokens, 2, where, element));
      corner = 0;
    } else if (key == "outer" || key == "endloop") {
      if (corner == -1) return parseError(where + "'" + std::string(key) + "' outside a facet");
    } else if (key == "vertex" && corner >= 0 && corner < 3) {
      if (tokens.size() != 4) return parseError(where + element + ": expected 'vertex X Y Z'");
      double xyz[3];
      TESSERA_RETURN_IF_ERROR(parseCoordinates(tokens, 1, where, element, xyz));
      corners[corner++] = {static_cast<float>(xyz[0]), static_cast<float>(xyz[1]),
                           static_cast<float>(xyz[2])};
    } else if (key == "endfacet" && corner == 3) {
      TESSERA_RETURN_IF_ERROR(welder.addFacet(corners, soup.numFaces(), where));
      corner = -1;
    } else if (key == "endsolid" && corner == -1) {
      ended = true;
    } else {
      return parseError(where + "unexpected '" + clip(key) + "'" +
                        (corner >= 0 ? " in " + element : std::string()));
    }
  }
  if (!ended)
    return parseError(src + ": truncated, no 'endsolid' (" + std::to_string(soup.numFaces()) +
                      " complete facets)");
  return Status::ok();
}

}  // namespace

Status readStl(std::string_view text, const std::string& src, PolygonSoup& soup) {
  uint32_t declared = 0;
  if (text.size() >= 84) std::memcpy(&declared, text.data() + 80, 4);
  if (text.size() >= 84 && text.size() == 84 + 50 * static_cast<uint64_t>(declared)) {
    return readBinaryStl(text, src, declared, soup);
  }
  const size_t first = text.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos || text.substr(first, 5) != "solid") {
    return parseError(
        src + ": neither ASCII STL (starting with 'solid') nor binary STL (84 + 50 * N bytes)" +
        (text.size() >= 84 ? ", binary header declares " + std::to_string(declared) + " facets" : ""));
  }
  return readAsciiStl(text, src, soup);
}

}  // namespace tessera::io_detail
