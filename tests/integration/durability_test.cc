// Durability (server issue §4): an edit storm from several clients, the
// server killed with SIGKILL at random moments (20 times), restarted each
// time. Every acknowledged edit must be there, and the surface must equal a
// replay of the acknowledged history -- plus, at most, edits that were in
// flight when the server died (durable but not yet acknowledged).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <map>
#include <mutex>
#include <set>
#include <random>
#include <thread>

#include "client/lib/document_view.h"
#include "client/lib/session.h"
#include "core/document/document.h"
#include "core/hierarchy/ids.h"
#include "core/io/mesh_import.h"
#include "core/tessellation/document_grid.h"
#include "core/tessellation/tessellation.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using client::DocumentView;
using client::Session;
using testing::ServerProcess;

struct Move {
  uint64_t vertex;
  Vec3 displacement;
};

constexpr uint32_t kBase = 1, kMax = 3;

// The hash a subscriber with the test's profile would see for `doc`:
// the same tessellation, encoded on the same grid, decoded.
uint64_t expectedHash(Document doc, uint64_t documentId) {
  auto t = Tessellation::build(doc, {.baseLevel = kBase, .maxLevel = kMax, .angleThresholdDegrees = 15});
  auto grid = documentGrid(doc);
  if (!t.isOk() || !grid.isOk()) return 0;
  wire::ServerMessage snapshot;
  snapshot.mutable_snapshot()->set_document_id(documentId);
  for (const auto& [id, mesh] : t->regions()) {
    RegionHeader header;
    header.regionId = id;
    header.documentVersion = 1;
    header.profile = t->profile();
    header.grid = *grid;
    auto bytes = encodeRegion(header, mesh);
    if (!bytes.isOk()) return 0;
    wire::Region* r = snapshot.mutable_snapshot()->add_regions();
    r->set_region_id(id);
    r->set_draco(*bytes);
  }
  DocumentView view(documentId);
  if (!view.apply(snapshot).isOk()) return 0;
  return view.surfaceHash();
}

TEST(ServerDurability, AcknowledgedEditsSurviveKillNine) {
  const std::string dir = testing::makeTempDir("tessera-server-kill");
  const std::string data = dir + "/data";
  const std::string cubePath = testing::sourceTestDataPath("cube.obj");
  std::optional<ServerProcess> server;
  {
    auto started = ServerProcess::start(data, {"--snapshot-every", "7"});
    ASSERT_TRUE(started.isOk()) << started.status().message();
    server.emplace(std::move(*started));
  }
  auto admin = Session::connect(server->session("admin", server->adminToken()));
  ASSERT_TRUE(admin.isOk());
  auto created = (*admin)->call(testing::createDocument("cube", testing::fileBytes(cubePath), "", 4), 30);
  ASSERT_TRUE(created.isOk() && created->has_ack());
  const uint64_t docId = created->ack().document_id();
  const std::string token = "editor-token-0123456789";
  ASSERT_TRUE((*admin)->call(testing::grant(docId, wire::ROLE_EDITOR, token), 10)->has_ack());
  (*admin)->close();

  // Local replicas of the acknowledged history. The checker sees the
  // surface only through quantized positions, and two in-flight edits that
  // were both recovered may land in either order with surfaces that quantize
  // alike (a coarse move tilts a fine vertex's frame by a hair). Every
  // history the observation cannot tell apart is kept, and later rounds
  // prune them; one must survive every round.
  auto mesh = importMesh(cubePath);
  ASSERT_TRUE(mesh.isOk());
  auto created0 = Document::create(*mesh, {.maxLevel = 4});
  ASSERT_TRUE(created0.isOk());
  std::vector<Document> replicas{std::move(*created0)};
  uint64_t replicaVersion = 1;

  std::mt19937 rng(20261122);
  int totalAcked = 0, roundsWithInFlight = 0;
  size_t maxHistories = 1;
  for (int round = 0; round < 20; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    std::mutex mutex;
    std::map<uint64_t, Move> acked;  // version -> move
    std::vector<Move> inFlight;
    std::vector<std::thread> editors;
    for (int e = 0; e < 2; ++e) {
      editors.emplace_back([&, e, seed = rng()] {
        auto session = Session::connect(server->session("editor" + std::to_string(e), token));
        if (!session.isOk() || !(*session)->call(testing::openDocument(docId), 10).isOk()) return;
        std::mt19937 local(seed);
        for (int i = 0; i < 500; ++i) {
          const int level = static_cast<int>(local() % 3);
          const Move move{VertexId(level, local() % (level == 0 ? 8 : level == 1 ? 26 : 98)).packed(),
                          Vec3(((local() % 21) - 10) * 1e-3, ((local() % 21) - 10) * 1e-3, ((local() % 21) - 10) * 1e-3)};
          auto reply = (*session)->call(testing::moveVertex(docId, move.vertex, move.displacement[0], move.displacement[1],
                                                            move.displacement[2], wire::MOVE_MODE_OFFSET),
                                        5);
          std::lock_guard lock(mutex);
          if (!reply.isOk()) {
            inFlight.push_back(move);  // the server died with it unanswered
            return;
          }
          if (reply->has_ack()) acked[reply->ack().version()] = move;
        }
      });
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(30 + rng() % 150));
    server->kill9();
    for (auto& t : editors) t.join();
    totalAcked += static_cast<int>(acked.size());

    // Frequent snapshots: recovery reads a snapshot plus the journal after it.
    auto restarted = ServerProcess::start(data, {"--snapshot-every", "7"});
    ASSERT_TRUE(restarted.isOk()) << restarted.status().message();
    server.emplace(std::move(*restarted));
    auto viewer = Session::connect(server->session("checker", token));
    ASSERT_TRUE(viewer.isOk());
    ASSERT_TRUE((*viewer)->call(testing::openDocument(docId), 10)->has_ack());
    ASSERT_TRUE((*viewer)->call(testing::subscribe(docId, kBase, kMax), 30)->has_ack());
    DocumentView view(docId);
    for (int i = 0; i < 100 && !view.ready(); ++i) {
      auto m = (*viewer)->receive(10);
      ASSERT_TRUE(m.isOk());
      ASSERT_TRUE(view.apply(*m).isOk());
    }
    ASSERT_TRUE(view.ready());
    (*viewer)->close();

    // Every acknowledged version is present...
    const uint64_t recovered = view.version();
    const uint64_t lastAcked = acked.empty() ? replicaVersion : acked.rbegin()->first;
    ASSERT_GE(recovered, lastAcked) << "an acknowledged edit was lost";
    // ...and versions 1..recovered are the acknowledged edits plus, in the
    // gaps, in-flight ones (at most one per editor).
    std::vector<uint64_t> gaps;
    for (uint64_t v = replicaVersion + 1; v <= recovered; ++v) {
      if (!acked.count(v)) gaps.push_back(v);
    }
    ASSERT_LE(gaps.size(), inFlight.size()) << "versions the clients never sent";
    roundsWithInFlight += gaps.empty() ? 0 : 1;
    // Each history so far, continued by each assignment of in-flight moves
    // to the gaps.
    std::vector<int> order(inFlight.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    std::vector<Document> survivors;
    for (const Document& replica : replicas) {
      std::set<std::vector<int>> tried;  // orders that differ only past the gaps are one assignment
      std::sort(order.begin(), order.end());
      do {
        if (!tried.insert(std::vector<int>(order.begin(), order.begin() + static_cast<long>(gaps.size()))).second) {
          continue;
        }
        Document candidate = replica;
        bool ok = true;
        size_t gap = 0;
        for (uint64_t v = replicaVersion + 1; v <= recovered && ok; ++v) {
          const Move& m = acked.count(v) ? acked[v] : inFlight[order[gap++]];
          const VertexId id = VertexId::fromPacked(m.vertex);
          ok = candidate.moveBy(std::span(&id, 1), m.displacement).isOk();
        }
        if (ok && expectedHash(candidate, docId) == view.surfaceHash()) survivors.push_back(std::move(candidate));
      } while (std::next_permutation(order.begin(), order.end()));
    }
    ASSERT_FALSE(survivors.empty()) << "the recovered surface is no replay of the acknowledged history (version "
                                    << recovered << ", " << acked.size() << " acked, " << inFlight.size()
                                    << " in flight, " << replicas.size() << " candidate histories)";
    maxHistories = std::max(maxHistories, survivors.size());
    replicas = std::move(survivors);
    replicaVersion = recovered;
  }
  std::printf(
      "20 kills: %d edits acknowledged, all recovered; %d rounds recovered an unacknowledged in-flight edit; at most %zu "
      "histories matched at once\n",
      totalAcked, roundsWithInFlight, maxHistories);
  EXPECT_GT(totalAcked, 20);
  EXPECT_EQ(server->stop(), 0);
}

}  // namespace
}  // namespace tessera
