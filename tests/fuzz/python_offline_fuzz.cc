// The Python package's offline entry points through their C++ side
// (client/python/offline_work.h): what tessera.read_mesh and tessera.refine
// run once pybind11 has turned their arguments into C++ (points, faces of
// any lengths, the import options, the rule names, a level), and the text
// ids every command takes ("v3:1234", "e2:55"; client/python/element_ids.cc).
//
// Input layout: byte 0 the options (bit 0 triangulate, 1 drop unused
// vertices, 2 a crease angle, 3 limit, 4 Chaikin, 5 edge-and-corner, 6-7
// the level 0..2), byte 1 the crease angle in degrees (0..255, so out of
// range too) with bit 2, else the scheme (modulo 6, in schemeNames()'s
// order: 0 Loop as read_mesh and refine run it, the others as refine's
// `scheme=` runs them), byte 2 the number of points (at most 64), then that many
// points as three raw doubles each (NaN and infinities included), then
// faces until a '\n': a corner count byte and that many 2-byte signed
// indices (out of range too); what follows is two lines, parsed as a
// vertex id and an edge id, and the whole of it as a tag file
// (tessera.read_tags), whose tags tessera.write_tags must write as a text
// that reads back to the same tags, or refuse naming the tag.
#include <cstring>
#include <string>

#include "client/python/offline_work.h"
#include "core/hierarchy/ids.h"
#include "fuzz_support.h"

namespace {

using namespace tessera;

class Reader {
 public:
  Reader(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  bool has(size_t n) const { return size_ - at_ >= n; }
  uint8_t byte() { return has(1) ? data_[at_++] : 0; }
  double real() {
    double d = 0;
    if (has(sizeof d)) std::memcpy(&d, data_ + at_, sizeof d);
    at_ += has(sizeof d) ? sizeof d : size_ - at_;
    return d;
  }
  int16_t index() {
    int16_t i = 0;
    if (has(sizeof i)) std::memcpy(&i, data_ + at_, sizeof i);
    at_ += has(sizeof i) ? sizeof i : size_ - at_;
    return i;
  }
  std::string rest() { return std::string(reinterpret_cast<const char*>(data_ + at_), size_ - at_); }
  bool atEnd() const { return at_ >= size_; }
  bool peekNewline() const { return !atEnd() && data_[at_] == '\n'; }

 private:
  const uint8_t* data_;
  size_t size_, at_ = 0;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace tessera::fuzz;
  if (size > 4096) return 0;
  Reader in(data, size);
  const uint8_t flags = in.byte();
  const uint8_t angle = in.byte();
  python::ImportArgs args{.triangulate = (flags & 1) != 0, .dropUnused = (flags & 2) != 0};
  if (flags & 4) args.creaseAngle = angle;
  PolygonSoup soup;
  const int points = in.byte() % 65;
  for (int i = 0; i < points; ++i) {
    const double x = in.real(), y = in.real(), z = in.real();
    soup.points.push_back(Vec3(x, y, z));
  }
  while (!in.atEnd() && !in.peekNewline() && soup.numFaces() < 128) {
    const int corners = in.byte() % 9;
    std::vector<int> face;
    for (int k = 0; k < corners; ++k) face.push_back(in.index());
    soup.addFace(face);
  }
  if (in.peekNewline()) in.byte();

  const std::string& scheme = schemes::schemeNames()[(flags & 4) ? 0 : angle % 6];
  if (scheme != "loop") {
    const bool defaults = (flags & 48) == 0;
    auto options = python::loopOptionsNamed((flags & 16) ? "chaikin" : "uniform",
                                            (flags & 32) ? "edge-and-corner" : "edge-only");
    auto surface = python::refineScheme(scheme, {.soup = std::move(soup)}, args, *options, defaults,
                                        (flags >> 6) % 3, (flags & 8) != 0);
    if (!surface.isOk()) checkError(surface.status(), "refineScheme");
    return 0;
  }
  auto mesh = python::baseMeshFromArrays(std::move(soup), args);
  if (!mesh.isOk()) {
    checkError(mesh.status(), "baseMeshFromArrays");
    require(mesh.status().message().find("arrays") != std::string::npos,
            "an import error that does not name the arrays: " + mesh.status().message());
  } else {
    auto options = python::loopOptionsNamed((flags & 16) ? "chaikin" : "uniform",
                                            (flags & 32) ? "edge-and-corner" : "edge-only");
    require(options.isOk(), "the rule names read_mesh documents are refused");
    const int level = (flags >> 6) % 3;
    const bool limit = (flags & 8) != 0;
    auto surface = python::refineLoop(*mesh, *options, level, limit);
    if (!surface.isOk()) {
      checkError(surface.status(), "refineLoop");
    } else {
      // Each level keeps the vertices of the one before, in order.
      require(surface->positions.size() >= static_cast<size_t>(mesh->numVertices()),
              "a refined surface with fewer vertices than its base mesh");
      require(surface->triangles.size() == (static_cast<size_t>(mesh->numFaces()) << (2 * level)),
              "a refined surface whose triangles are not 4^level times the base's");
    }
  }

  const std::string text = in.rest();
  const size_t newline = text.find('\n');
  auto vertex = parseVertexId(text.substr(0, newline));
  if (!vertex.isOk()) checkError(vertex.status(), "parseVertexId");
  if (newline != std::string::npos) {
    auto edge = parseEdgeId(text.substr(newline + 1));
    if (!edge.isOk()) checkError(edge.status(), "parseEdgeId");
  }

  auto tags = python::tagsFromText(text, "fuzz.tags");
  if (!tags.isOk()) {
    checkError(tags.status(), "tagsFromText");
    return 0;
  }
  auto written = python::tagFileText(*tags);
  if (!written.isOk()) {
    checkError(written.status(), "tagFileText");
    require(written.status().message().rfind("tag ", 0) == 0,
            "a refused tag that is not named: " + written.status().message());
    return 0;
  }
  auto reread = python::tagsFromText(*written, "written.tags");
  require(reread.isOk(), "written tags that do not read back: " + reread.status().message());
  require(reread->size() == tags->size(), "written tags read back to another count");
  for (size_t i = 0; i < tags->size(); ++i) {
    const FeatureTag &a = (*tags)[i], &b = (*reread)[i];
    require(a.kind == b.kind && a.v0 == b.v0 && (a.kind == FeatureTag::Kind::kCorner || a.v1 == b.v1) &&
                std::memcmp(&a.sharpness, &b.sharpness, sizeof(float)) == 0,
            "tag " + std::to_string(i) + " read back different: " + *written);
  }
  return 0;
}
