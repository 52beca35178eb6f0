#include "core/schemes/polygon_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>

#include "core/io/mesh_import.h"
#include "core/io/tag_file.h"
#include "core/util/file_io.h"

namespace tessera::schemes {

namespace {

// A line cursor over text, counting lines from 1.
class Lines {
 public:
  explicit Lines(std::string_view text) : text_(text) {}
  bool next(std::string_view& line) {
    if (pos_ >= text_.size()) return false;
    const size_t end = std::min(text_.find('\n', pos_), text_.size());
    line = text_.substr(pos_, end - pos_);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos_ = end + 1;
    ++number_;
    return true;
  }
  int number() const { return number_; }

 private:
  std::string_view text_;
  size_t pos_ = 0;
  int number_ = 0;
};

// Whitespace-separated tokens of one line.
std::vector<std::string_view> tokens(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
    if (j > i) out.push_back(line.substr(i, j - i));
    i = j;
  }
  return out;
}

bool parseDouble(std::string_view token, double& value) {
  if (!token.empty() && token[0] == '+') token.remove_prefix(1);
  auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size() && std::isfinite(value);
}

bool parseInt(std::string_view token, long long& value) {
  auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size();
}

std::string at(const std::string& name, int line) { return name + ":" + std::to_string(line) + ": "; }

std::string_view stripComment(std::string_view line) {
  const size_t hash = line.find('#');
  return hash == std::string_view::npos ? line : line.substr(0, hash);
}

// Every edge of the faces as (min, max), sorted.
std::vector<std::pair<int, int>> meshEdges(const PolyTopology& t) {
  std::vector<std::pair<int, int>> edges;
  for (int f = 0; f < t.numFaces(); ++f) {
    const int from = t.faceOffsets[f], size = t.faceOffsets[f + 1] - from;
    for (int j = 0; j < size; ++j) edges.push_back(std::minmax(t.indices[from + j], t.indices[from + (j + 1) % size]));
  }
  std::sort(edges.begin(), edges.end());
  return edges;
}

}  // namespace

Expected<PolygonSoup> readObjPolygons(std::string_view text, const std::string& name) {
  if (text.find('\0') != std::string_view::npos) return parseError(name + ": binary data, not a text OBJ file");
  PolygonSoup soup;
  Lines lines(text);
  std::string_view line;
  std::vector<int> face;
  while (lines.next(line)) {
    const auto t = tokens(stripComment(line));
    if (t.empty()) continue;
    if (t[0] == "v") {
      if (t.size() != 4 && t.size() != 5) return parseError(at(name, lines.number()) + "a vertex needs 3 coordinates");
      Vec3 p;
      for (int k = 0; k < 3; ++k) {
        if (!parseDouble(t[1 + k], p[k])) {
          return parseError(at(name, lines.number()) + "bad coordinate '" + std::string(t[1 + k]) + "'");
        }
      }
      soup.points.push_back(p);
    } else if (t[0] == "f") {
      if (t.size() < 4) return parseError(at(name, lines.number()) + "a face needs 3 or more corners");
      face.clear();
      for (size_t k = 1; k < t.size(); ++k) {
        const std::string_view index = t[k].substr(0, t[k].find('/'));
        long long i = 0;
        if (!parseInt(index, i) || i == 0) {
          return parseError(at(name, lines.number()) + "bad vertex index '" + std::string(t[k]) + "'");
        }
        // 1-based; negative counts back from the last vertex read so far.
        const long long v = i > 0 ? i - 1 : static_cast<long long>(soup.points.size()) + i;
        if (v < 0 || v >= static_cast<long long>(soup.points.size())) {
          return parseError(at(name, lines.number()) + "vertex index " + std::string(index) +
                            " names no vertex read so far (" + std::to_string(soup.points.size()) + ")");
        }
        face.push_back(static_cast<int>(v));
      }
      soup.addFace(face);
    }
    // vt, vn, g, o, s, usemtl, mtllib, l, ...: not geometry the schemes use.
  }
  if (soup.points.empty()) return parseError(name + ": no vertices");
  if (soup.numFaces() == 0) return parseError(name + ": no faces");
  return soup;
}

Expected<PolygonSoup> readOffPolygons(std::string_view text, const std::string& name) {
  if (text.find('\0') != std::string_view::npos) return parseError(name + ": binary data, not a text OFF file");
  Lines lines(text);
  std::string_view line;
  std::vector<std::string_view> t;
  // The next line with tokens, comments removed.
  auto nextTokens = [&]() {
    while (lines.next(line)) {
      t = tokens(stripComment(line));
      if (!t.empty()) return true;
    }
    return false;
  };
  if (!nextTokens() || t[0] != "OFF") return parseError(name + ":1: not an OFF file (it must start with 'OFF')");
  std::vector<std::string_view> counts(t.begin() + 1, t.end());
  if (counts.empty()) {
    if (!nextTokens()) return parseError(name + ": missing vertex and face counts");
    counts = t;
  }
  long long nv = 0, nf = 0;
  if (counts.size() < 2 || !parseInt(counts[0], nv) || !parseInt(counts[1], nf) || nv < 0 || nf < 0 ||
      nv > 100'000'000 || nf > 100'000'000) {
    return parseError(at(name, lines.number()) + "bad counts (expected 'vertices faces edges')");
  }
  PolygonSoup soup;
  soup.points.reserve(static_cast<size_t>(nv));
  for (long long i = 0; i < nv; ++i) {
    if (!nextTokens()) return parseError(name + ": truncated: " + std::to_string(i) + " of " + std::to_string(nv) + " vertices");
    if (t.size() < 3) return parseError(at(name, lines.number()) + "a vertex needs 3 coordinates");
    Vec3 p;
    for (int k = 0; k < 3; ++k) {
      if (!parseDouble(t[k], p[k])) return parseError(at(name, lines.number()) + "bad coordinate '" + std::string(t[k]) + "'");
    }
    soup.points.push_back(p);
  }
  std::vector<int> face;
  for (long long i = 0; i < nf; ++i) {
    if (!nextTokens()) return parseError(name + ": truncated: " + std::to_string(i) + " of " + std::to_string(nf) + " faces");
    long long n = 0;
    if (!parseInt(t[0], n) || n < 3 || static_cast<size_t>(n) + 1 > t.size()) {
      return parseError(at(name, lines.number()) + "bad face (expected a corner count of 3 or more, then the corners)");
    }
    face.clear();
    for (long long k = 1; k <= n; ++k) {
      long long v = 0;
      if (!parseInt(t[k], v) || v < 0 || v >= nv) {
        return parseError(at(name, lines.number()) + "bad vertex index '" + std::string(t[k]) + "' (0.." +
                          std::to_string(nv - 1) + ")");
      }
      face.push_back(static_cast<int>(v));
    }
    soup.addFace(face);  // a colour may follow: ignored
  }
  if (nf == 0) return parseError(name + ": no faces");
  return soup;
}

Status applyPolygonTags(const std::string& text, const std::string& tagsName, PolygonMesh& mesh) {
  TESSERA_ASSIGN_OR_RETURN(const std::vector<FeatureTag> tags, parseTags(text, tagsName));
  std::map<std::pair<int, int>, int> seen;  // (v0, v1) or (v, -1) -> line
  std::vector<std::pair<int, int>> edges;    // sorted (min, max), built at the first crease
  const int n = mesh.topology.numVertices;
  if (mesh.topology.vertexSharpness.empty()) mesh.topology.vertexSharpness.assign(n, 0.0f);
  for (const FeatureTag& tag : tags) {
    const std::string where = tagsName + ":" + std::to_string(tag.line) + ": ";
    const bool crease = tag.kind == FeatureTag::Kind::kCrease;
    for (int v : {tag.v0, crease ? tag.v1 : 0}) {
      if (v < 0 || v >= n) {
        return notFound(where + "vertex " + std::to_string(v) + " does not exist (the mesh has " + std::to_string(n) +
                        " vertices)");
      }
    }
    const auto key = crease ? std::pair<int, int>(std::minmax(tag.v0, tag.v1)) : std::pair<int, int>(tag.v0, -1);
    auto [it, inserted] = seen.emplace(key, tag.line);
    if (!inserted) {
      return invalidArgument(where + "duplicate tag, the same " + (crease ? "edge" : "vertex") +
                             " is already tagged at line " + std::to_string(it->second));
    }
    if (crease) {
      if (edges.empty()) edges = meshEdges(mesh.topology);
      if (!std::binary_search(edges.begin(), edges.end(), key)) {
        return notFound(where + "vertices " + std::to_string(tag.v0) + " and " + std::to_string(tag.v1) +
                        " share no edge");
      }
      mesh.topology.creases.push_back({tag.v0, tag.v1, tag.sharpness});
    } else {
      mesh.topology.vertexSharpness[tag.v0] = tag.sharpness;
    }
  }
  return Status::ok();
}

Expected<PolygonMesh> importPolygonMesh(const std::string& path, const std::string& tagsPath) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  PolygonMesh mesh;
  if (ext == ".obj" || ext == ".off") {
    TESSERA_ASSIGN_OR_RETURN(const std::string text, readFile(path));
    TESSERA_ASSIGN_OR_RETURN(PolygonSoup soup, ext == ".obj" ? readObjPolygons(text, path) : readOffPolygons(text, path));
    mesh.topology = PolyTopology::fromSoup(soup);
    mesh.points = std::move(soup.points);
  } else {
    TESSERA_ASSIGN_OR_RETURN(BaseMesh base, importMesh(path));
    mesh.topology = PolyTopology::fromBaseMesh(base);
    mesh.points = base.positions();
  }
  if (!tagsPath.empty()) {
    TESSERA_ASSIGN_OR_RETURN(const std::string text, readFile(tagsPath));
    TESSERA_RETURN_IF_ERROR(applyPolygonTags(text, tagsPath, mesh));
  }
  return mesh;
}

}  // namespace tessera::schemes
