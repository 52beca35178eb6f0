// The reference for `tessera refine`'s whole-process speed (docs/PERFORMANCE.md "File in to file out"): a
// small OpenSubdiv-based tool that does what `tessera refine IN --level N -o
// OUT` does, written plainly -- the kind of tool a user would write instead.
// It is a benchmark helper, not product code, and links OpenSubdiv only.
//
//   tessera_bench_osd_refine IN.off|IN.obj LEVEL OUT.obj|.ply|.off|.stl|.glb
//
// Reads a triangle mesh (OFF, or OBJ with 'v' and 'f' lines) with fscanf,
// refines it LEVEL times with Far::TopologyRefiner (Loop, edge-only boundary)
// and PrimvarRefiner::Interpolate in double precision, computes area-weighted
// vertex normals (as Tessera's control surface does), and writes the same
// content as Tessera: OBJ and OFF with fprintf("%.17g") (full double
// precision, as Tessera's shortest round-trip text), binary PLY, binary STL
// and GLB with float32 and fwrite.
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

using namespace OpenSubdiv;

namespace {

struct Point {
  double x = 0, y = 0, z = 0;
  void Clear(void* = nullptr) { x = y = z = 0; }
  void AddWithWeight(const Point& p, float w) { x += w * p.x, y += w * p.y, z += w * p.z; }
};

[[noreturn]] void die(const char* what, const char* path) {
  std::fprintf(stderr, "osd_refine: %s: %s\n", path, what);
  std::exit(1);
}

void readMesh(const char* path, std::vector<Point>& points, std::vector<int>& indices) {
  std::FILE* in = std::fopen(path, "r");
  if (!in) die("cannot open", path);
  const std::string name = path;
  if (name.size() > 4 && name.compare(name.size() - 4, 4, ".off") == 0) {
    int v = 0, f = 0, e = 0;
    if (std::fscanf(in, " OFF %d %d %d", &v, &f, &e) != 3) die("bad OFF header", path);
    points.resize(v);
    for (Point& p : points) {
      if (std::fscanf(in, "%lf %lf %lf", &p.x, &p.y, &p.z) != 3) die("bad vertex", path);
    }
    for (int i = 0; i < f; ++i) {
      int n = 0, a = 0, b = 0, c = 0;
      if (std::fscanf(in, "%d %d %d %d", &n, &a, &b, &c) != 4 || n != 3) die("bad triangle", path);
      indices.insert(indices.end(), {a, b, c});
    }
  } else {
    char line[512];
    while (std::fgets(line, sizeof line, in)) {
      Point p;
      int a = 0, b = 0, c = 0;
      if (std::sscanf(line, "v %lf %lf %lf", &p.x, &p.y, &p.z) == 3)
        points.push_back(p);
      else if (std::sscanf(line, "f %d %d %d", &a, &b, &c) == 3)
        indices.insert(indices.end(), {a - 1, b - 1, c - 1});
    }
  }
  std::fclose(in);
}

struct Surface {
  std::vector<Point> points, normals;
  std::vector<std::array<int, 3>> triangles;
};

Surface refine(const std::vector<Point>& base, const std::vector<int>& indices, int level) {
  const int faces = static_cast<int>(indices.size() / 3);
  std::vector<int> arity(faces, 3);
  Far::TopologyDescriptor descriptor;
  descriptor.numVertices = static_cast<int>(base.size());
  descriptor.numFaces = faces;
  descriptor.numVertsPerFace = arity.data();
  descriptor.vertIndicesPerFace = indices.data();
  Sdc::Options sdc;
  sdc.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
  using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
  Far::TopologyRefiner* refiner = Factory::Create(descriptor, Factory::Options(Sdc::SCHEME_LOOP, sdc));
  if (!refiner) die("OpenSubdiv refused the topology", "input");
  refiner->RefineUniform(Far::TopologyRefiner::UniformOptions(level));

  std::vector<Point> current = base;
  Far::PrimvarRefiner primvar(*refiner);
  for (int l = 1; l <= level; ++l) {
    std::vector<Point> next(refiner->GetLevel(l).GetNumVertices());
    Point* destination = next.data();
    primvar.Interpolate(l, current.data(), destination);
    current.swap(next);
  }
  Surface s;
  s.points = std::move(current);
  const Far::TopologyLevel& last = refiner->GetLevel(level);
  s.triangles.resize(last.GetNumFaces());
  for (int f = 0; f < last.GetNumFaces(); ++f) {
    const Far::ConstIndexArray v = last.GetFaceVertices(f);
    s.triangles[f] = {v[0], v[1], v[2]};
  }
  delete refiner;
  // Area-weighted vertex normals.
  s.normals.assign(s.points.size(), Point());
  for (const auto& t : s.triangles) {
    const Point &a = s.points[t[0]], &b = s.points[t[1]], &c = s.points[t[2]];
    const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z, vx = c.x - a.x, vy = c.y - a.y,
                 vz = c.z - a.z;
    const Point n{uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
    for (int v : t) s.normals[v].AddWithWeight(n, 1.0f);
  }
  for (Point& n : s.normals) {
    const double length = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    if (length > 0) n = {n.x / length, n.y / length, n.z / length};
  }
  return s;
}

void putFloats(std::FILE* out, const Point& p) {
  const float xyz[3] = {float(p.x), float(p.y), float(p.z)};
  std::fwrite(xyz, sizeof xyz, 1, out);
}

void writeObj(std::FILE* out, const Surface& s) {
  std::fprintf(out, "# osd_refine\n");
  for (const Point& p : s.points) std::fprintf(out, "v %.17g %.17g %.17g\n", p.x, p.y, p.z);
  for (const Point& n : s.normals) std::fprintf(out, "vn %.17g %.17g %.17g\n", n.x, n.y, n.z);
  for (const auto& t : s.triangles) {
    std::fprintf(out, "f %d//%d %d//%d %d//%d\n", t[0] + 1, t[0] + 1, t[1] + 1, t[1] + 1, t[2] + 1, t[2] + 1);
  }
}

void writeOff(std::FILE* out, const Surface& s) {
  std::fprintf(out, "OFF\n%zu %zu 0\n", s.points.size(), s.triangles.size());
  for (const Point& p : s.points) std::fprintf(out, "%.17g %.17g %.17g\n", p.x, p.y, p.z);
  for (const auto& t : s.triangles) std::fprintf(out, "3 %d %d %d\n", t[0], t[1], t[2]);
}

void writePly(std::FILE* out, const Surface& s) {
  std::fprintf(
      out,
      "ply\nformat binary_little_endian 1.0\nelement vertex %zu\nproperty float x\nproperty float y\n"
      "property float z\nproperty float nx\nproperty float ny\nproperty float nz\nelement face %zu\n"
      "property list uchar int vertex_indices\nend_header\n",
      s.points.size(), s.triangles.size());
  for (size_t i = 0; i < s.points.size(); ++i) putFloats(out, s.points[i]), putFloats(out, s.normals[i]);
  for (const auto& t : s.triangles) {
    const unsigned char three = 3;
    std::fwrite(&three, 1, 1, out);
    std::fwrite(t.data(), sizeof(int), 3, out);
  }
}

void writeStl(std::FILE* out, const Surface& s) {
  char header[80] = "osd_refine";
  std::fwrite(header, 80, 1, out);
  const uint32_t count = static_cast<uint32_t>(s.triangles.size());
  std::fwrite(&count, 4, 1, out);
  for (const auto& t : s.triangles) {
    const Point &a = s.points[t[0]], &b = s.points[t[1]], &c = s.points[t[2]];
    const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z, vx = c.x - a.x, vy = c.y - a.y,
                 vz = c.z - a.z;
    Point n{uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
    const double length = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    if (length > 0) n = {n.x / length, n.y / length, n.z / length};
    putFloats(out, n), putFloats(out, a), putFloats(out, b), putFloats(out, c);
    const uint16_t attributes = 0;
    std::fwrite(&attributes, 2, 1, out);
  }
}

void writeGlb(std::FILE* out, const Surface& s) {
  const size_t n = s.points.size(), indexCount = s.triangles.size() * 3;
  float lo[3] = {1e38f, 1e38f, 1e38f}, hi[3] = {-1e38f, -1e38f, -1e38f};
  for (const Point& p : s.points) {
    const float xyz[3] = {float(p.x), float(p.y), float(p.z)};
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], xyz[k]), hi[k] = std::max(hi[k], xyz[k]);
  }
  const size_t vertexBytes = n * 12, indexBytes = indexCount * 4, binBytes = 2 * vertexBytes + indexBytes;
  char json[2048];
  int length = std::snprintf(
      json, sizeof json,
      "{\"asset\":{\"version\":\"2.0\",\"generator\":\"osd_refine\"},\"buffers\":[{\"byteLength\":%zu}],"
      "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":%zu,\"target\":34962},"
      "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"target\":34962},"
      "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,\"target\":34963}],"
      "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":%zu,\"type\":\"VEC3\","
      "\"min\":[%.9g,%.9g,%.9g],\"max\":[%.9g,%.9g,%.9g]},"
      "{\"bufferView\":1,\"componentType\":5126,\"count\":%zu,\"type\":\"VEC3\"},"
      "{\"bufferView\":2,\"componentType\":5125,\"count\":%zu,\"type\":\"SCALAR\"}],"
      "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1},\"indices\":2,\"mode\":4}]}"
      "],"
      "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],\"scene\":0}",
      binBytes, vertexBytes, vertexBytes, vertexBytes, 2 * vertexBytes, indexBytes, n, lo[0], lo[1], lo[2],
      hi[0], hi[1], hi[2], n, indexCount);
  while (length % 4) json[length++] = ' ';
  const uint32_t header[3] = {0x46546C67, 2, static_cast<uint32_t>(12 + 8 + length + 8 + binBytes)};
  const uint32_t jsonChunk[2] = {static_cast<uint32_t>(length), 0x4E4F534A};
  const uint32_t binChunk[2] = {static_cast<uint32_t>(binBytes), 0x004E4942};
  std::fwrite(header, sizeof header, 1, out);
  std::fwrite(jsonChunk, sizeof jsonChunk, 1, out);
  std::fwrite(json, length, 1, out);
  std::fwrite(binChunk, sizeof binChunk, 1, out);
  for (const Point& p : s.points) putFloats(out, p);
  for (const Point& q : s.normals) putFloats(out, q);
  for (const auto& t : s.triangles) std::fwrite(t.data(), sizeof(int), 3, out);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: %s IN.off|IN.obj LEVEL OUT.obj|.ply|.off|.stl|.glb\n", argv[0]);
    return 2;
  }
  std::vector<Point> points;
  std::vector<int> indices;
  readMesh(argv[1], points, indices);
  const Surface surface = refine(points, indices, std::atoi(argv[2]));
  const std::string output = argv[3];
  const std::string ext = output.substr(output.find_last_of('.') + 1);
  std::FILE* out = std::fopen(argv[3], "wb");
  if (!out) die("cannot open for writing", argv[3]);
  if (ext == "obj")
    writeObj(out, surface);
  else if (ext == "off")
    writeOff(out, surface);
  else if (ext == "ply")
    writePly(out, surface);
  else if (ext == "stl")
    writeStl(out, surface);
  else if (ext == "glb")
    writeGlb(out, surface);
  else
    die("unknown output extension", argv[3]);
  if (std::fclose(out) != 0) die("write failed", argv[3]);
  std::printf("wrote %s: %zu vertices, %zu triangles (level %s)\n", argv[3], surface.points.size(),
              surface.triangles.size(), argv[2]);
  return 0;
}
