// docs/PROTOCOL.md checked against a real tessera-server: the stats list it
// documents, the surface hash recomputed from the document's text alone
// (6.5), the vertex order of exports (7.2, ExportDocument) derived from the
// numbering rules of 3.2, and which error wins for a command's ids (7.2).
// Where the text is the oracle, the test implements it itself rather than
// calling the project's code.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "client/lib/document_view.h"
#include "client/lib/session.h"
#include "core/hierarchy/ids.h"
#include "integration/cube_server.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using client::DocumentView;
using client::Session;
using testing::CubeServer;
using testing::ServerProcess;
using testing::startWithCube;

std::string protocolText() {
  std::ifstream in(std::string(TESSERA_SOURCE_TESTDATA_DIR) + "/../../docs/PROTOCOL.md");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// ---------------------------------------------------------------------------
// Stats: the table after "always in this order" in section 7.3.

std::vector<std::string> documentedStats(const std::string& text) {
  std::vector<std::string> names;
  const size_t at = text.find("always in\nthis order");
  if (at == std::string::npos) return names;
  std::istringstream lines(text.substr(at));
  std::string line;
  bool inTable = false;
  while (std::getline(lines, line)) {
    if (line.rfind("| name |", 0) == 0) {
      inTable = true;
      continue;
    }
    if (!inTable || line.rfind("| ---", 0) == 0) continue;
    if (line.rfind("| `", 0) != 0) break;  // the table ended
    const size_t end = line.find('`', 3);
    names.push_back(line.substr(3, end - 3));
  }
  return names;
}

TEST(ProtocolDocument, StatsListMatchesTheServersReply) {
  CubeServer s;
  startWithCube(s, "tessera-protocol-stats", 3);
  if (::testing::Test::HasFatalFailure()) return;
  const std::vector<std::string> documented = documentedStats(protocolText());
  ASSERT_GT(documented.size(), 10u)
      << "no stats table found after 'always in this order' in docs/PROTOCOL.md";
  wire::ClientMessage stats;
  stats.mutable_stats();
  auto reply = s.admin->call(stats, 10);
  ASSERT_TRUE(reply.isOk() && reply->has_stats_reply());
  std::vector<std::string> served;
  for (const auto& stat : reply->stats_reply().stats()) served.push_back(stat.name());
  EXPECT_EQ(documented, served) << "docs/PROTOCOL.md's StatsReply table and the server's order differ";
}

// ---------------------------------------------------------------------------
// The surface hash, written from the text of 6.5 alone.

uint64_t hashFromTheText(const std::map<uint64_t, RegionMesh>& regions) {
  using Key = std::array<uint64_t, 4>;
  uint64_t sum = 0;
  for (const auto& [id, mesh] : regions) {
    for (const auto& t : mesh.triangles) {
      std::array<Key, 3> keys;
      for (int k = 0; k < 3; ++k) {
        keys[k][0] = mesh.vertexIds.empty() ? 0 : mesh.vertexIds[t[k]];
        for (int c = 0; c < 3; ++c) {
          const float value = static_cast<float>(mesh.positions[t[k]][c]);
          keys[k][1 + c] = value == 0.0f ? 0u : std::bit_cast<uint32_t>(value);
        }
      }
      std::array<std::array<Key, 3>, 3> rotations{
          {{keys[0], keys[1], keys[2]}, {keys[1], keys[2], keys[0]}, {keys[2], keys[0], keys[1]}}};
      const auto& smallest = *std::min_element(rotations.begin(), rotations.end());
      std::vector<uint8_t> bytes;
      for (const Key& key : smallest) {
        for (int i = 0; i < 8; ++i) bytes.push_back(static_cast<uint8_t>(key[0] >> (8 * i)));
        for (int c = 1; c < 4; ++c) {
          for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<uint8_t>(key[c] >> (8 * i)));
        }
      }
      EXPECT_EQ(bytes.size(), 60u);
      uint64_t h = 0xcbf29ce484222325ull;
      for (uint8_t b : bytes) h = (h ^ b) * 0x100000001b3ull;
      sum += h;
    }
  }
  return sum;
}

// Checks every decoded id of `view` against the birth level that 3.2's
// counts give its index (the cube: 8, 18, 12); returns the ids per level.
std::map<int, size_t> expectBirthLevels(const DocumentView& view, int maxLevel) {
  std::vector<uint64_t> vertices{8};
  uint64_t e = 18, f = 12;
  for (int l = 1; l <= maxLevel; ++l) {
    vertices.push_back(vertices.back() + e);
    e = 2 * e + 3 * f;
    f = 4 * f;
  }
  std::map<int, size_t> perLevel;
  for (const auto& [id, mesh] : view.regions()) {
    for (uint64_t packed : mesh.vertexIds) {
      const int level = static_cast<int>(packed >> 58);
      const uint64_t index = packed & ((uint64_t{1} << 58) - 1);
      int birth = 0;
      while (birth < maxLevel && vertices[birth] <= index) ++birth;
      EXPECT_EQ(level, birth) << "index " << index;
      ++perLevel[level];
    }
  }
  return perLevel;
}

// Reads until the view is ready at `version` or later; keeps the last
// snapshot's and delta's announced hashes.
void readUntil(Session& s, DocumentView& view, uint64_t version) {
  for (int i = 0; i < 400 && !(view.ready() && view.version() >= version); ++i) {
    auto m = s.receive(10);
    ASSERT_TRUE(m.isOk()) << m.status().message();
    Status applied = view.apply(*m);
    ASSERT_TRUE(applied.isOk()) << applied.message();
  }
  ASSERT_TRUE(view.ready());
  ASSERT_EQ(view.version(), version);
}

TEST(ProtocolDocument, SurfaceHashIsRecomputedFromTheText) {
  CubeServer s;
  startWithCube(s, "tessera-protocol-hash", 5);
  if (::testing::Test::HasFatalFailure()) return;
  // A viewer with ids and a display-only one (ids hashed as 0).
  auto viewer = Session::connect(s.process->session("viewer", s.process->adminToken()));
  auto watcher = Session::connect(s.process->session("watcher", s.process->adminToken()));
  ASSERT_TRUE(viewer.isOk() && watcher.isOk());
  DocumentView withIds(s.doc), displayOnly(s.doc);
  for (auto [session, omitIds] : {std::pair{viewer->get(), false}, std::pair{watcher->get(), true}}) {
    ASSERT_TRUE(session->call(testing::openDocument(s.doc), 10)->has_ack());
    auto sub = testing::subscribe(s.doc, 2, 5, 10);
    sub.mutable_subscribe()->mutable_profile()->set_omit_vertex_ids(omitIds);
    auto subscribed = session->call(sub, 30);
    ASSERT_TRUE(subscribed.isOk() && subscribed->has_ack()) << subscribed->DebugString();
  }
  readUntil(**viewer, withIds, 1);
  readUntil(**watcher, displayOnly, 1);
  // Ids as lattice points (depth 3 below level-2 regions) at their birth level.
  const auto perLevel = expectBirthLevels(withIds, 5);
  EXPECT_GT(perLevel.size(), 3u) << "ids of more than three levels";

  const uint64_t before = hashFromTheText(withIds.regions());
  EXPECT_NE(before, 0u);
  EXPECT_EQ(withIds.surfaceHash(), before);           // the client library's
  EXPECT_EQ(withIds.announcedSurfaceHash(), before);  // the server's, in the snapshot
  EXPECT_TRUE(withIds.verifySurface().isOk());
  const uint64_t plainBefore = hashFromTheText(displayOnly.regions());
  EXPECT_EQ(displayOnly.announcedSurfaceHash(), plainBefore);
  EXPECT_NE(plainBefore, before);  // the ids count

  // An edit: the delta's hash is the state after it, and it changed.
  auto moved = s.admin->call(testing::moveVertex(s.doc, VertexId(2, 0).packed(), 0.1, 0.05, 1.2), 10);
  ASSERT_TRUE(moved.isOk() && moved->has_ack()) << moved->DebugString();
  readUntil(**viewer, withIds, 2);
  readUntil(**watcher, displayOnly, 2);
  const uint64_t after = hashFromTheText(withIds.regions());
  EXPECT_NE(after, before);
  EXPECT_EQ(withIds.surfaceHash(), after);
  EXPECT_EQ(withIds.announcedSurfaceHash(), after);  // the server's, in the delta
  EXPECT_EQ(displayOnly.announcedSurfaceHash(), hashFromTheText(displayOnly.regions()));
  EXPECT_NE(hashFromTheText(displayOnly.regions()), plainBefore);

  // A late subscriber's snapshot at the same version has the same hash.
  auto late = Session::connect(s.process->session("late", s.process->adminToken()));
  ASSERT_TRUE(late.isOk());
  ASSERT_TRUE((*late)->call(testing::openDocument(s.doc), 10)->has_ack());
  ASSERT_TRUE((*late)->call(testing::subscribe(s.doc, 2, 5, 10), 30)->has_ack());
  DocumentView joined(s.doc);
  readUntil(**late, joined, 2);
  EXPECT_EQ(hashFromTheText(joined.regions()), after);
  EXPECT_EQ(joined.announcedSurfaceHash(), after);
}

// ---------------------------------------------------------------------------
// The level of a decoded id (6.2): the vertex's birth level, whether the ids
// travel as lattice points (flag 4) or as 8 bytes (flag 0, lattice depth
// above 7, here with --max-level 12).

TEST(ProtocolDocument, DecodedIdsArriveAtTheirBirthLevel) {
  const std::string dir = testing::makeTempDir("tessera-protocol-birth");
  auto process = ServerProcess::start(dir + "/data", {"--max-level", "12"});
  ASSERT_TRUE(process.isOk()) << process.status().message();
  auto admin = Session::connect(process->session("admin", process->adminToken()));
  ASSERT_TRUE(admin.isOk());
  auto created = (*admin)->call(
      testing::createDocument("cube", testing::fileBytes(testing::sourceTestDataPath("cube.obj")), "", 10),
      30);
  ASSERT_TRUE(created.isOk() && created->has_ack())
      << (created.isOk() ? created->DebugString() : created.status().message());
  const uint64_t doc = created->ack().document_id();
  ASSERT_TRUE((*admin)->call(testing::openDocument(doc), 10)->has_ack());
  // A coarse profile reaching level 10: its leaf regions at level 2 lie 8
  // levels above the profile's deepest, too deep for lattice points.
  ASSERT_TRUE((*admin)->call(testing::subscribe(doc, 0, 10, 40), 60)->has_ack());
  DocumentView view(doc);
  std::map<uint16_t, int> flags;  // header flags (offset 6) -> regions
  for (int i = 0; i < 400 && !view.ready(); ++i) {
    auto m = (*admin)->receive(20);
    ASSERT_TRUE(m.isOk()) << m.status().message();
    if (m->has_snapshot()) {
      for (const auto& r : m->snapshot().regions()) {
        ASSERT_GE(r.draco().size(), 8u);
        ++flags[static_cast<uint16_t>(static_cast<uint8_t>(r.draco()[6]) |
                                      (static_cast<uint8_t>(r.draco()[7]) << 8))];
      }
    }
    ASSERT_TRUE(view.apply(*m).isOk());
  }
  ASSERT_TRUE(view.ready());
  EXPECT_GT(flags[0], 0) << "no region with 8-byte ids";
  const auto perLevel = expectBirthLevels(view, 10);
  // Vertices of one leaf level, yet their ids name three levels.
  EXPECT_GT(perLevel.count(0) + perLevel.count(1) + perLevel.count(2), 2u);
  std::printf(
      "[ measured ] %d regions with 8-byte ids, %d with lattice ids; ids at levels 0/1/2: %zu/%zu/%zu\n",
      flags[0], flags[4], perLevel.count(0) ? perLevel.at(0) : 0, perLevel.count(1) ? perLevel.at(1) : 0,
      perLevel.count(2) ? perLevel.at(2) : 0);
}

// ---------------------------------------------------------------------------
// Export order: the numbering of 3.2, applied by the test to the level-0
// export, predicts every triangle of the level-1 and level-2 exports.

struct Glb {
  std::vector<std::array<float, 3>> positions, normals;
  std::vector<std::array<uint64_t, 3>> triangles;
};

Glb exportGlb(Session& s, uint64_t doc, uint32_t level, bool limit) {
  wire::ClientMessage m;
  m.mutable_export_document()->set_document_id(doc);
  m.mutable_export_document()->set_level(level);
  m.mutable_export_document()->set_limit(limit);
  auto reply = s.call(m, 60);
  EXPECT_TRUE(reply.isOk() && reply->has_export_result())
      << (reply.isOk() ? reply->DebugString() : reply.status().message());
  Glb out;
  if (!reply.isOk() || !reply->has_export_result()) return out;
  const std::string& bytes = reply->export_result().glb();
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  EXPECT_TRUE(loader.LoadBinaryFromMemory(&model, &err, &warn,
                                          reinterpret_cast<const unsigned char*>(bytes.data()),
                                          static_cast<unsigned>(bytes.size())))
      << err;
  const tinygltf::Primitive& p = model.meshes.at(0).primitives.at(0);
  auto floats = [&](int accessorIndex) {
    const tinygltf::Accessor& a = model.accessors.at(accessorIndex);
    const tinygltf::BufferView& v = model.bufferViews.at(a.bufferView);
    std::vector<std::array<float, 3>> values(a.count);
    std::memcpy(values.data(), model.buffers.at(v.buffer).data.data() + v.byteOffset + a.byteOffset,
                a.count * 12);
    return values;
  };
  out.positions = floats(p.attributes.at("POSITION"));
  out.normals = floats(p.attributes.at("NORMAL"));
  const tinygltf::Accessor& ia = model.accessors.at(p.indices);
  const tinygltf::BufferView& iv = model.bufferViews.at(ia.bufferView);
  const unsigned char* data = model.buffers.at(iv.buffer).data.data() + iv.byteOffset + ia.byteOffset;
  for (size_t i = 0; i + 2 < ia.count; i += 3) {
    std::array<uint64_t, 3> t;
    for (int k = 0; k < 3; ++k) {
      if (ia.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
        uint16_t x;
        std::memcpy(&x, data + 2 * (i + k), 2);
        t[k] = x;
      } else {
        uint32_t x;
        std::memcpy(&x, data + 4 * (i + k), 4);
        t[k] = x;
      }
    }
    out.triangles.push_back(t);
  }
  return out;
}

// One level's topology as 3.2 defines it.
struct Topology {
  uint64_t vertices = 0;
  std::vector<std::array<uint64_t, 3>> faces;      // corners
  std::vector<std::array<uint64_t, 3>> faceEdges;  // edge j joins corners j and j+1
  std::vector<std::array<uint64_t, 2>> edges;      // from its first end to its second
};

// Level 0: edges by the scan of the base triangles.
Topology baseTopology(uint64_t vertices, const std::vector<std::array<uint64_t, 3>>& faces) {
  Topology t{vertices, faces, {}, {}};
  std::map<std::pair<uint64_t, uint64_t>, uint64_t> known;  // unordered ends -> edge
  for (const auto& f : faces) {
    std::array<uint64_t, 3> fe;
    for (int j = 0; j < 3; ++j) {
      const uint64_t a = f[j], b = f[(j + 1) % 3];
      auto [it, fresh] = known.try_emplace({std::min(a, b), std::max(a, b)}, t.edges.size());
      if (fresh) t.edges.push_back({a, b});
      fe[j] = it->second;
    }
    t.faceEdges.push_back(fe);
  }
  return t;
}

// Level l + 1 from level l, by the rules and the children table of 3.2.
Topology refine(const Topology& p) {
  const uint64_t V = p.vertices, E = p.edges.size();
  Topology c;
  c.vertices = V + E;
  c.edges.resize(2 * E + 3 * p.faces.size());
  for (uint64_t e = 0; e < E; ++e) {
    c.edges[2 * e] = {p.edges[e][0], V + e};
    c.edges[2 * e + 1] = {V + e, p.edges[e][1]};
  }
  for (uint64_t f = 0; f < p.faces.size(); ++f) {
    const auto& v = p.faces[f];
    const auto& e = p.faceEdges[f];
    const uint64_t m0 = V + e[0], m1 = V + e[1], m2 = V + e[2];
    const uint64_t i0 = 2 * E + 3 * f, i1 = i0 + 1, i2 = i0 + 2;
    c.edges[i0] = {m0, m2};
    c.edges[i1] = {m1, m0};
    c.edges[i2] = {m2, m1};
    auto half = [&](int j, uint64_t corner) { return p.edges[e[j]][0] == corner ? 2 * e[j] : 2 * e[j] + 1; };
    c.faces.push_back({v[0], m0, m2});
    c.faceEdges.push_back({half(0, v[0]), i0, half(2, v[0])});
    c.faces.push_back({m0, v[1], m1});
    c.faceEdges.push_back({half(0, v[1]), half(1, v[1]), i1});
    c.faces.push_back({m2, m1, v[2]});
    c.faceEdges.push_back({i2, half(1, v[2]), half(2, v[2])});
    c.faces.push_back({m1, m2, m0});
    c.faceEdges.push_back({i2, i0, i1});
  }
  return c;
}

// The split copies of a limit export: every index from `vertices` on has the
// bit-identical position of an earlier vertex; maps each to it.
// `otherNormal` counts the copies whose normal is not their vertex's.
std::vector<std::array<uint64_t, 3>> withoutCopies(const Glb& glb, uint64_t vertices, size_t& copies,
                                                   size_t& otherNormal) {
  std::map<std::array<uint32_t, 3>, uint64_t> at;
  auto bits = [](const std::array<float, 3>& p) {
    return std::array<uint32_t, 3>{std::bit_cast<uint32_t>(p[0]), std::bit_cast<uint32_t>(p[1]),
                                   std::bit_cast<uint32_t>(p[2])};
  };
  for (uint64_t k = 0; k < vertices && k < glb.positions.size(); ++k) {
    EXPECT_TRUE(at.emplace(bits(glb.positions[k]), k).second) << "two vertices at one position: " << k;
  }
  std::vector<uint64_t> original(glb.positions.size());
  uint64_t previous = 0;
  copies = otherNormal = 0;
  for (uint64_t i = 0; i < glb.positions.size(); ++i) {
    if (i < vertices) {
      original[i] = i;
      continue;
    }
    auto it = at.find(bits(glb.positions[i]));
    EXPECT_NE(it, at.end()) << "vertex " << i << " (past V = " << vertices << ") copies no vertex";
    if (it == at.end()) continue;
    original[i] = it->second;
    EXPECT_GE(it->second, previous) << "copies are not in the order of their vertices";
    previous = it->second;
    // A side of a semi-sharp feature that decays has the same normal as
    // the vertex: the limit surface is smooth there (docs/LIMITS.md).
    if (glb.normals[i] != glb.normals[it->second]) ++otherNormal;
    ++copies;
  }
  std::vector<std::array<uint64_t, 3>> out;
  for (const auto& t : glb.triangles) out.push_back({original[t[0]], original[t[1]], original[t[2]]});
  return out;
}

TEST(ProtocolDocument, ExportVertexOrderFollowsTheNumbering) {
  CubeServer s;
  startWithCube(s, "tessera-protocol-export", 3);
  if (::testing::Test::HasFatalFailure()) return;
  // Some edits, so that positions are not those of a plain cube.
  ASSERT_TRUE(s.admin
                  ->call(testing::moveVertex(s.doc, VertexId(1, 9).packed(), 0.05, 0.02, -0.03,
                                             wire::MOVE_MODE_OFFSET),
                         10)
                  ->has_ack());

  const Glb base = exportGlb(*s.admin, s.doc, 0, false);
  ASSERT_EQ(base.positions.size(), 8u);
  ASSERT_EQ(base.triangles.size(), 12u);
  std::vector<Topology> levels{baseTopology(8, base.triangles)};
  ASSERT_EQ(levels[0].edges.size(), 18u);
  for (int l = 1; l <= 2; ++l) levels.push_back(refine(levels.back()));
  // The counts of 3.2.
  EXPECT_EQ(levels[1].vertices, 26u);
  EXPECT_EQ(levels[1].edges.size(), 72u);
  EXPECT_EQ(levels[2].vertices, 98u);
  EXPECT_EQ(levels[2].faces.size(), 192u);

  std::vector<Glb> limit(3);
  for (uint32_t l = 1; l <= 2; ++l) {
    const Glb control = exportGlb(*s.admin, s.doc, l, false);
    EXPECT_EQ(control.positions.size(), levels[l].vertices) << "a control export has no copies";
    EXPECT_EQ(control.triangles, levels[l].faces) << "level " << l << ": triangles of the control export";

    limit[l] = exportGlb(*s.admin, s.doc, l, true);
    size_t copies = 0, otherNormal = 0;
    const auto mapped = withoutCopies(limit[l], levels[l].vertices, copies, otherNormal);
    EXPECT_EQ(mapped, levels[l].faces) << "level " << l << ": triangles of the limit export";
    EXPECT_GT(copies, 0u) << "the creased cube has crease and corner vertices";
    // The infinitely sharp top rim and corner keep a crease in the limit:
    // their further sides have normals of their own.
    EXPECT_GT(otherNormal, 0u) << "no copy has a normal of its own side";
    std::printf(
        "[ measured ] level %u: %llu vertices, %zu split copies (%zu with another normal), %zu triangles\n",
        l, static_cast<unsigned long long>(levels[l].vertices), copies, otherNormal,
        limit[l].triangles.size());
  }
  // Vertices keep their index: vertex k of level 1 has the same limit at
  // level 2, the same point evaluated from another level. Exact only where
  // no semi-sharp crease is still decaying (3.2), so on the smooth cube.
  auto smooth = s.admin->call(
      testing::createDocument("smooth", testing::fileBytes(testing::sourceTestDataPath("cube.obj")), "", 3),
      30);
  ASSERT_TRUE(smooth.isOk() && smooth->has_ack());
  const uint64_t smoothDoc = smooth->ack().document_id();
  ASSERT_TRUE(s.admin->call(testing::openDocument(smoothDoc), 10)->has_ack());
  const Glb one = exportGlb(*s.admin, smoothDoc, 1, true), two = exportGlb(*s.admin, smoothDoc, 2, true);
  ASSERT_EQ(one.positions.size(), levels[1].vertices);
  ASSERT_EQ(two.positions.size(), levels[2].vertices);
  for (uint64_t k = 0; k < levels[1].vertices; ++k) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(one.positions[k][c], two.positions[k][c], 1e-6) << "vertex " << k;
  }
}

// ---------------------------------------------------------------------------
// Which error wins (7.2): a missing id over how the ids relate.

wire::RejectReason rejectOf(Session& s, wire::ClientMessage m) {
  auto reply = s.call(std::move(m), 10);
  EXPECT_TRUE(reply.isOk() && reply->has_reject())
      << (reply.isOk() ? reply->DebugString() : reply.status().message());
  return reply.isOk() && reply->has_reject() ? reply->reject().reason() : wire::REJECT_REASON_UNSPECIFIED;
}

TEST(ProtocolDocument, AMissingIdWinsOverHowTheIdsRelate) {
  CubeServer s;
  startWithCube(s, "tessera-protocol-precedence", 3);
  if (::testing::Test::HasFatalFailure()) return;
  const LevelCounts counts(8, 18, 12, 3);
  const uint64_t a = VertexId(1, 5).packed(), b = VertexId(2, 7).packed();
  const uint64_t missing = VertexId(1, counts.vertices(1)).packed();
  auto move = [&](std::vector<uint64_t> ids) {
    wire::ClientMessage m = testing::moveVertex(s.doc, ids[0], 0, 0, 0.01, wire::MOVE_MODE_OFFSET);
    for (size_t i = 1; i < ids.size(); ++i) m.mutable_move_vertex()->add_vertex_ids(ids[i]);
    return m;
  };
  EXPECT_EQ(rejectOf(*s.admin, move({a, b, missing})), wire::REJECT_REASON_NOT_FOUND);
  EXPECT_EQ(rejectOf(*s.admin, move({missing, b})), wire::REJECT_REASON_NOT_FOUND);
  EXPECT_EQ(rejectOf(*s.admin, move({a, a, missing})), wire::REJECT_REASON_NOT_FOUND);
  EXPECT_EQ(rejectOf(*s.admin, move({a, b})), wire::REJECT_REASON_INVALID_ARGUMENT);
  EXPECT_EQ(rejectOf(*s.admin, move({a, a})), wire::REJECT_REASON_INVALID_ARGUMENT);

  auto crease = [&](uint64_t x, uint64_t y, size_t count = 2) {
    wire::ClientMessage m;
    auto* e = m.mutable_set_edge_sharpness();
    e->set_document_id(s.doc);
    e->set_edge_id(~uint64_t{0});
    e->set_sharpness(2);
    e->add_end_vertex_ids(x);
    if (count > 1) e->add_end_vertex_ids(y);
    return m;
  };
  EXPECT_EQ(rejectOf(*s.admin, crease(a, VertexId(2, counts.vertices(2)).packed())),
            wire::REJECT_REASON_NOT_FOUND);
  EXPECT_EQ(rejectOf(*s.admin, crease(missing, b)), wire::REJECT_REASON_NOT_FOUND);
  EXPECT_EQ(rejectOf(*s.admin, crease(a, b)), wire::REJECT_REASON_INVALID_ARGUMENT);
  // The form of the message comes first: one end vertex, even a missing one.
  EXPECT_EQ(rejectOf(*s.admin, crease(missing, 0, 1)), wire::REJECT_REASON_INVALID_ARGUMENT);
}

}  // namespace
}  // namespace tessera
