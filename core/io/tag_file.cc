// Feature-tag sidecar files: parsing is strict (every token accounted for)
// because a silently ignored tag changes the surface without telling anyone.
#include "core/io/tag_file.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <utility>

#include "core/util/text.h"

namespace tessera {
namespace {

// Whole-token, non-negative decimal integer (no sign, no junk).
bool parseIndex(const std::string& token, int& value) {
  if (token.empty() || token[0] == '+' || token[0] == '-') return false;
  const char* end = token.data() + token.size();
  auto [ptr, ec] = std::from_chars(token.data(), end, value);
  return ec == std::errc() && ptr == end;
}

bool equalsIgnoreCase(const std::string& a, const char* b) {
  size_t i = 0;
  for (; i < a.size() && b[i] != '\0'; ++i) {
    if (std::tolower(static_cast<unsigned char>(a[i])) != b[i]) return false;
  }
  return i == a.size() && b[i] == '\0';
}

std::string describe(const FeatureTag& tag) {
  if (tag.kind == FeatureTag::Kind::kCorner) return "corner " + std::to_string(tag.v0);
  return "crease " + std::to_string(tag.v0) + " " + std::to_string(tag.v1);
}

}  // namespace

bool parseSharpness(const std::string& token, float& sharpness) {
  if (equalsIgnoreCase(token, "inf")) {
    sharpness = kSharpnessInfinite;
    return true;
  }
  // from_chars accepts "nan" and "inf" spellings; only plain numbers pass the
  // checks below. A leading '+' is not accepted by from_chars either.
  double value = 0.0;
  const char* end = token.data() + token.size();
  auto [ptr, ec] = std::from_chars(token.data(), end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value) || value < 0.0) return false;
  sharpness = canonicalSharpness(static_cast<float>(std::min(value, double{kSharpnessInfinite})));
  return true;
}

Expected<std::vector<FeatureTag>> parseTags(const std::string& text, const std::string& sourceName) {
  std::vector<FeatureTag> tags;
  std::istringstream in(text);
  std::string line;
  int lineNumber = 0;
  while (std::getline(in, line)) {
    ++lineNumber;
    const std::string where = sourceName + ":" + std::to_string(lineNumber) + ": ";
    if (auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    const std::vector<std::string> tokens = splitTokens(line);
    if (tokens.empty()) continue;

    FeatureTag tag;
    tag.line = lineNumber;
    size_t arity = 0;
    if (tokens[0] == "crease") {
      tag.kind = FeatureTag::Kind::kCrease;
      arity = 4;
    } else if (tokens[0] == "corner") {
      tag.kind = FeatureTag::Kind::kCorner;
      arity = 3;
    } else {
      return parseError(where + "unknown keyword '" + tokens[0] + "' (expected 'crease' or 'corner')");
    }
    const std::string usage =
        tag.kind == FeatureTag::Kind::kCrease ? "crease I J SHARPNESS" : "corner I SHARPNESS";
    if (tokens.size() < arity) {
      return parseError(where + tokens[0] + ": too few values, expected '" + usage + "'");
    }
    if (tokens.size() > arity) {
      return parseError(where + tokens[0] + ": unexpected trailing '" + tokens[arity] + "', expected '" +
                        usage + "'");
    }
    if (!parseIndex(tokens[1], tag.v0)) {
      return parseError(where + tokens[0] + ": bad vertex index '" + tokens[1] +
                        "' (expected a non-negative integer)");
    }
    if (tag.kind == FeatureTag::Kind::kCrease) {
      if (!parseIndex(tokens[2], tag.v1)) {
        return parseError(where + tokens[0] + ": bad vertex index '" + tokens[2] +
                          "' (expected a non-negative integer)");
      }
      if (tag.v0 == tag.v1) {
        return parseError(where + describe(tag) + ": names the same vertex twice");
      }
    }
    const std::string& sharpnessToken = tokens[arity - 1];
    if (!parseSharpness(sharpnessToken, tag.sharpness)) {
      return parseError(where + describe(tag) + ": bad sharpness '" + sharpnessToken +
                        "' (expected a number >= 0 or 'inf')");
    }
    tags.push_back(tag);
  }
  return tags;
}

Status applyTags(const std::vector<FeatureTag>& tags, const TagNaming& naming, const TagTarget& target,
                 const VertexRenumbering& renumbering) {
  const int n = target.numVertices;
  const int fileVertices = renumbering.isIdentity() ? n : renumbering.fileVertexCount();
  // The file's vertex v in the mesh; checks first that it exists.
  const auto meshVertex = [&](int v, const std::string& where, int& out) -> Status {
    if (v < 0 || v >= fileVertices) {
      return notFound(where + "vertex " + std::to_string(v) + " does not exist (the " +
                      (renumbering.isIdentity() ? "mesh" : "file") + " has " + std::to_string(fileVertices) +
                      " vertices)");
    }
    out = renumbering.isIdentity() ? v : renumbering.newIndex[v];
    if (out < 0) {
      return notFound(where + "vertex " + std::to_string(v) +
                      " was dropped: no face uses it (--drop-unused)");
    }
    return Status::ok();
  };
  // Validate everything first so that an error leaves the mesh unchanged.
  std::vector<FeatureTag> mapped = tags;
  std::map<std::pair<int, int>, size_t> seen;  // (v0, v1) or (v, -1) -> tag
  for (size_t i = 0; i < tags.size(); ++i) {
    const FeatureTag& tag = tags[i];
    const std::string where = naming.prefix(tag);
    const bool crease = tag.kind == FeatureTag::Kind::kCrease;
    TESSERA_RETURN_IF_ERROR(meshVertex(tag.v0, where, mapped[i].v0));
    if (crease) TESSERA_RETURN_IF_ERROR(meshVertex(tag.v1, where, mapped[i].v1));
    if (!(tag.sharpness >= 0.0f)) return invalidArgument(where + "sharpness must be a number >= 0");
    if (crease && !target.hasEdge(mapped[i].v0, mapped[i].v1)) {
      return notFound(where + "vertices " + std::to_string(tag.v0) + " and " + std::to_string(tag.v1) +
                      " share no edge");
    }
    const std::pair<int, int> key =
        crease ? std::pair<int, int>(std::minmax(tag.v0, tag.v1)) : std::pair<int, int>(tag.v0, -1);
    auto [it, inserted] = seen.emplace(key, i);
    if (!inserted) {
      return invalidArgument(where + "duplicate tag, the same " + (crease ? "edge" : "vertex") +
                             " is already tagged at " + naming.reference(tags[it->second]));
    }
  }
  for (const FeatureTag& tag : mapped) {
    const Status status = target.set(tag);
    if (!status.isOk()) return status.withContext(naming.reference(tag));  // unreachable after the checks
  }
  return Status::ok();
}

Status applyTags(const std::vector<FeatureTag>& tags, const TagLocator& locate, BaseMesh& mesh,
                 const VertexRenumbering& renumbering) {
  const TagNaming naming{[&](const FeatureTag& tag) { return locate(tag) + ": " + describe(tag) + ": "; },
                         locate};
  const TriMesh& m = mesh.mesh();
  const TagTarget target{
      mesh.numVertices(),
      [&](int a, int b) { return m.find_halfedge(m.vertex_handle(a), m.vertex_handle(b)).is_valid(); },
      [&](const FeatureTag& tag) {
        return tag.kind == FeatureTag::Kind::kCrease ? mesh.setCreaseByVertices(tag.v0, tag.v1, tag.sharpness)
                                                     : mesh.setCornerByVertex(tag.v0, tag.sharpness);
      }};
  return applyTags(tags, naming, target, renumbering);
}

Status applyTags(const std::vector<FeatureTag>& tags, const std::string& sourceName, BaseMesh& mesh,
                 const VertexRenumbering& renumbering) {
  return applyTags(
      tags, [&](const FeatureTag& tag) { return sourceName + ":" + std::to_string(tag.line); }, mesh,
      renumbering);
}

std::vector<FeatureTag> featureTagsOf(const std::vector<SoupTag>& tags) {
  std::vector<FeatureTag> out;
  out.reserve(tags.size());
  for (const SoupTag& t : tags)
    out.push_back(
        {t.crease ? FeatureTag::Kind::kCrease : FeatureTag::Kind::kCorner, t.v0, t.v1, t.sharpness, t.line});
  return out;
}

Status applyTagFile(const std::string& path, BaseMesh& mesh, const VertexRenumbering& renumbering) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return notFound(path + ": cannot open tag file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return ioError(path + ": read error");
  auto tags = parseTags(text.str(), path);
  if (!tags) return tags.status();
  return applyTags(*tags, path, mesh, renumbering);
}

}  // namespace tessera
