// Streaming a morph (docs/PERFORMANCE.md), both ways, against the real server:
//   (a) region deltas at t: every viewer subscribes at t_k
//       (LodProfile.morph_t) and receives the surface at t_k as regions; a
//       frame is encoded once per t and shared by every viewer at that t;
//   (b) the coarse stream: every viewer asks for the control points at t_k
//       (GetMorphControl) and would refine them itself.
// V viewers (default 100) each play F frames (default 24) of t from 0 to 1
// as fast as the server answers, all at once. Printed per mode: bytes per
// frame per viewer, frames per second per viewer (median and slowest) and
// over all viewers, and the wall time. Then the visual difference of (b)
// against (a): at 5 times, every vertex (a) displays against the limit
// position of the same vertex of the document refined from (b)'s control
// mesh alone (finer edits are not in it), max and RMS, relative to the
// bounding-box diagonal.
//
// The document: a CGAL mesh (default fandisk) as key 0, key 1 the same mesh
// bent, and level-2 edits on both keys. A scenario, not a Google Benchmark
// (a load over many connections against the real binary). Bounded: every
// viewer stops after its frames or 300 s.
//
//   build/release/bench/tessera_bench_morph_stream [MESH.off] [VIEWERS] [FRAMES] [KEY1_MESH]
// (KEY1_MESH: key 1 from this mesh, e.g. deploy/samples/morph/mesh_b.obj
// over mesh_a.obj, instead of the bent mesh).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <thread>

#include "client/lib/document_view.h"
#include "client/lib/session.h"
#include "core/document/document.h"
#include "core/io/mesh_import.h"
#include "core/io/mesh_writers.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "integration/server_stat.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using Clock = std::chrono::steady_clock;
using client::DocumentView;
using client::Session;

constexpr uint32_t kBase = 1, kMax = 3;
constexpr double kAngle = 10;
constexpr int kDocumentLevel = 3;

double seconds(Clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

// Key 1: the mesh bent about its box's long axis (not affine, so every
// region moves differently).
std::vector<Vec3> bent(const std::vector<Vec3>& points) {
  Vec3 lo = points[0], hi = points[0];
  for (const Vec3& p : points) {
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  }
  const double length = hi[0] - lo[0], height = hi[1] - lo[1];
  std::vector<Vec3> out;
  for (const Vec3& p : points) {
    const double u = (p[0] - lo[0]) / length - 0.5;
    out.push_back(Vec3(p[0], p[1] + 0.6 * height * u * u, p[2] + 0.1 * height * std::sin(3 * u)));
  }
  return out;
}

std::string objOf(const BaseMesh& mesh, const std::vector<Vec3>& points) {
  std::ostringstream out;
  out.precision(17);
  for (const Vec3& p : points) out << "v " << p[0] << " " << p[1] << " " << p[2] << "\n";
  const TriMesh& m = mesh.mesh();
  for (auto f : m.faces()) {
    out << "f";
    for (auto v : m.fv_range(f)) out << " " << v.idx() + 1;
    out << "\n";
  }
  return out.str();
}

wire::ClientMessage subscribeAt(uint64_t doc, double t) {
  wire::ClientMessage m = testing::subscribe(doc, kBase, kMax, kAngle);
  m.mutable_subscribe()->mutable_profile()->set_morph_t(t);
  return m;
}

wire::ClientMessage controlAt(uint64_t doc, double t, bool topology) {
  wire::ClientMessage m;
  m.mutable_get_morph_control()->set_document_id(doc);
  m.mutable_get_morph_control()->set_t(t);
  m.mutable_get_morph_control()->set_with_topology(topology);
  return m;
}

struct PlayResult {
  int frames = 0;
  uint64_t bytes = 0;
  double seconds = 0;
  std::string error;
};

// One viewer playing `frames` frames in mode (a) or (b); bytes are the
// payloads of the frame messages (snapshots, or MorphControl).
PlayResult play(const testing::ServerProcess& server, const std::string& token, uint64_t doc, int frames,
                bool coarse, int offset) {
  PlayResult r;
  auto s = Session::connect(server.session("viewer", token));
  if (!s.isOk()) return {.error = s.status().message()};
  if (!(*s)->call(testing::openDocument(doc), 30).isOk()) return {.error = "open failed"};
  const auto start = Clock::now(), deadline = start + std::chrono::seconds(300);
  for (int k = 0; k < frames && Clock::now() < deadline; ++k) {
    // Viewers start at different frames, as real ones would.
    const double t = static_cast<double>((k + offset) % frames) / (frames - 1);
    if (coarse) {
      auto reply = (*s)->call(controlAt(doc, t, false), 60);
      if (!reply.isOk() || !reply->has_morph_control())
        return {.error = "no morph control at t " + std::to_string(t)};
      r.bytes += reply->ByteSizeLong();
    } else {
      auto ack = (*s)->call(subscribeAt(doc, t), 60);
      if (!ack.isOk() || !ack->has_ack())
        return {.error = "subscribe at t " + std::to_string(t) + " refused"};
      for (bool last = false; !last;) {
        auto m = (*s)->receive(60);
        if (!m.isOk()) return {.error = m.status().message()};
        if (!m->has_snapshot()) continue;
        r.bytes += m->ByteSizeLong();
        last = m->snapshot().remaining_parts() == 0;
      }
    }
    ++r.frames;
  }
  r.seconds = seconds(Clock::now() - start);
  return r;
}

void report(const char* mode, std::vector<PlayResult>& results, double wall) {
  std::vector<double> fps;
  uint64_t bytes = 0;
  int frames = 0;
  for (const PlayResult& r : results) {
    if (!r.error.empty()) std::printf("  viewer error: %s\n", r.error.c_str());
    fps.push_back(r.seconds > 0 ? r.frames / r.seconds : 0);
    bytes += r.bytes;
    frames += r.frames;
  }
  std::sort(fps.begin(), fps.end());
  std::printf(
      "%-24s %10.0f B/frame  %6.2f fps/viewer (median)  %6.2f (slowest)  %8.1f frames/s in all  %6.1f s "
      "wall\n",
      mode, frames ? static_cast<double>(bytes) / frames : 0.0, fps[fps.size() / 2], fps.front(),
      frames / wall, wall);
}

int run(const std::string& meshPath, int viewers, int frames, const std::string& key1Path) {
  auto mesh = importMesh(meshPath);
  if (!mesh.isOk()) {
    std::fprintf(stderr, "%s\n", mesh.status().message().c_str());
    return 2;
  }
  std::vector<Vec3> points0 = mesh->positions(), points1 = bent(points0);
  if (!key1Path.empty()) {
    auto key1 = importMesh(key1Path);
    if (!key1.isOk()) {
      std::fprintf(stderr, "%s\n", key1.status().message().c_str());
      return 2;
    }
    points1 = key1->positions();
  }
  const std::string dir = testing::makeTempDir("tessera-bench-morph");
  // Enough connections and profiles for every viewer at its own t.
  auto server = testing::ServerProcess::start(
      dir + "/data", {"--connections-per-address", std::to_string(viewers + 16), "--profiles-per-document",
                      std::to_string(frames + 4), "--commands-per-second", "100000"});
  if (!server.isOk()) {
    std::fprintf(stderr, "server: %s\n", server.status().message().c_str());
    return 2;
  }
  auto admin = Session::connect(server->session("admin", server->adminToken()));
  if (!admin.isOk()) return 2;
  auto created =
      (*admin)->call(testing::createDocument("morph", objOf(*mesh, points0), "", kDocumentLevel), 120);
  if (!created.isOk() || !created->has_ack()) {
    std::fprintf(stderr, "create: %s\n",
                 created.isOk() ? created->DebugString().c_str() : created.status().message().c_str());
    return 2;
  }
  const uint64_t doc = created->ack().document_id();
  if (!(*admin)->call(testing::openDocument(doc), 30).isOk()) return 2;
  wire::ClientMessage add;
  add.mutable_add_morph_key()->set_document_id(doc);
  add.mutable_add_morph_key()->set_mesh(objOf(*mesh, points1));
  add.mutable_add_morph_key()->set_mesh_format(wire::MESH_FORMAT_OBJ);
  auto added = (*admin)->call(add, 120);
  if (!added.isOk() || !added->has_ack()) {
    std::fprintf(stderr, "add key: %s\n",
                 added.isOk() ? added->DebugString().c_str() : added.status().message().c_str());
    return 2;
  }
  // Level-2 detail on both keys: what the coarse stream leaves out.
  int edits = 0;
  for (uint32_t key = 0; key < 2; ++key) {
    for (uint64_t v = 0; v < 40; ++v) {
      const uint64_t index = (v * 7919 + key * 104729) % static_cast<uint64_t>(mesh->numVertices());
      auto m = testing::moveVertex(doc, VertexId(2, index).packed(), 0.004 * (key + 1), -0.003, 0.002,
                                   wire::MOVE_MODE_OFFSET);
      m.mutable_move_vertex()->set_key(key);
      auto r = (*admin)->call(m, 30);
      edits += r.isOk() && r->has_ack() ? 1 : 0;
    }
  }
  if (!(*admin)->call(testing::grant(doc, wire::ROLE_VIEWER, "morph-viewer-token-0123456789"), 30).isOk())
    return 2;
  std::printf(
      "document: %s, %d base triangles, key 1 %s, %d level-2 edits on the two keys; profile base %u max %u "
      "angle %g; %d viewers x %d frames\n",
      meshPath.c_str(), mesh->numFaces(), key1Path.empty() ? "bent" : key1Path.c_str(), edits, kBase, kMax,
      kAngle, viewers, frames);

  for (bool coarse : {false, true}) {
    const double encodedBefore = testing::serverStat(**admin, "regions_encoded");
    std::vector<PlayResult> results(viewers);
    std::vector<std::thread> threads;
    const auto start = Clock::now();
    for (int i = 0; i < viewers; ++i) {
      threads.emplace_back([&, i] {
        results[i] = play(*server, "morph-viewer-token-0123456789", doc, frames, coarse, i % frames);
      });
    }
    for (auto& t : threads) t.join();
    report(coarse ? "(b) control points at t" : "(a) regions at t", results, seconds(Clock::now() - start));
    std::printf("%-24s %10.0f regions encoded by the server\n", "",
                testing::serverStat(**admin, "regions_encoded") - encodedBefore);
  }

  // The visual difference of (b) against (a).
  auto viewer = Session::connect(server->session("probe", "morph-viewer-token-0123456789"));
  if (!viewer.isOk()) return 2;
  if (!(*viewer)->call(testing::openDocument(doc), 30).isOk()) return 2;
  for (double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    if (!(*viewer)->call(subscribeAt(doc, t), 60).isOk()) return 2;
    DocumentView shown(doc);
    while (!shown.ready()) {
      auto m = (*viewer)->receive(60);
      if (!m.isOk() || !shown.apply(*m).isOk()) return 2;
    }
    auto control = (*viewer)->call(controlAt(doc, t, true), 60);
    if (!control.isOk() || !control->has_morph_control()) return 2;
    const wire::MorphControl& c = control->morph_control();
    BaseTopology topology;
    topology.numVertices = c.points_size() / 3;
    for (int i = 0; i + 2 < c.triangles_size(); i += 3) {
      topology.triangles.push_back({static_cast<int>(c.triangles(i)), static_cast<int>(c.triangles(i + 1)),
                                    static_cast<int>(c.triangles(i + 2))});
    }
    for (int i = 0; i < c.crease_sharpness_size(); ++i) {
      topology.creases.push_back({static_cast<int>(c.crease_vertices(2 * i)),
                                  static_cast<int>(c.crease_vertices(2 * i + 1)), c.crease_sharpness(i)});
    }
    topology.vertexSharpness.assign(c.vertex_sharpness().begin(), c.vertex_sharpness().end());
    std::vector<Vec3> points;
    for (int i = 0; i + 2 < c.points_size(); i += 3)
      points.push_back(Vec3(c.points(i), c.points(i + 1), c.points(i + 2)));
    // What a viewer of (b) computes per frame: the limit surface at the
    // profile's max level from the control mesh.
    const auto refineStart = Clock::now();
    auto coarse = Document::create(std::move(topology), std::move(points), {.maxLevel = kDocumentLevel});
    if (!coarse.isOk()) {
      std::fprintf(stderr, "coarse document: %s\n", coarse.status().message().c_str());
      return 2;
    }
    auto limit = coarse->surface(static_cast<int>(kMax), SurfaceKind::kLimit);
    if (!limit.isOk()) return 2;
    const double refineMs = 1e3 * seconds(Clock::now() - refineStart);
    Vec3 lo = limit->positions[0], hi = limit->positions[0];
    for (const Vec3& p : limit->positions) {
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
    }
    const double diagonal = (hi - lo).norm();
    double worst = 0, squares = 0;
    int64_t count = 0;
    for (const auto& [id, region] : shown.regions()) {
      for (size_t i = 0; i < region.positions.size(); ++i) {
        const VertexId v = VertexId::fromPacked(region.vertexIds[i]);
        const double d = (region.positions[i] - limit->positions[v.index()]).norm();
        worst = std::max(worst, d);
        squares += d * d;
        ++count;
      }
    }
    std::printf(
        "t = %.2f: (b) against (a) over %lld displayed vertices: max %.3e, RMS %.3e of the diagonal %.4g; "
        "(b) refined to level %u on the client in %.0f ms (%zu triangles)\n",
        t, static_cast<long long>(count), worst / diagonal, std::sqrt(squares / count) / diagonal, diagonal,
        kMax, refineMs, limit->triangles.size());
  }
  server->stop();
  return 0;
}

}  // namespace
}  // namespace tessera

int main(int argc, char** argv) {
  const std::string mesh = argc > 1 ? argv[1] : tessera::testing::cgalMeshPath("fandisk.off");
  const int viewers = argc > 2 ? std::atoi(argv[2]) : 100;
  const int frames = argc > 3 ? std::atoi(argv[3]) : 24;
  return tessera::run(mesh, std::max(1, viewers), std::max(2, frames), argc > 4 ? argv[4] : "");
}
