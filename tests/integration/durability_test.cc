// Durability (docs/STORE.md "Kill -9 soak"): an edit storm from several
// editors -- signed moves, semi-sharp and infinite creases, undos and redos --
// with the server killed by SIGKILL at a random moment of each cycle and
// restarted. Every acknowledged edit must be there, and the surface must
// equal a replay of the acknowledged history -- plus, at most, commands that
// were in flight when the server died (durable but not yet acknowledged).
//
// In CI it runs 20 cycles. The soak (bench/kill_soak.sh) runs the same test
// with more cycles and editors through these variables:
//   TESSERA_SOAK_CYCLES          kill -9 cycles (default 20)
//   TESSERA_SOAK_EDITORS         concurrent editors, 1 to 8 (default 2; the
//                                check replays up to editors! orderings of
//                                the commands in flight at each kill)
//   TESSERA_SOAK_MIX             percent of moves,creases,undos; the rest are
//                                redos (default 70,15,10)
//   TESSERA_SOAK_STORM_MS        longest storm before the kill (default 180;
//                                each cycle draws 30 ms to this)
//   TESSERA_SOAK_SNAPSHOT_EVERY  the server's --snapshot-every (default 7)
//   TESSERA_SOAK_SEED            the cycle generator's seed (default 20261122)
//   TESSERA_SOAK_MAX_SECONDS     start no cycle after this long; the test
//                                then fails with the cycles it ran (default 0:
//                                no limit)
// and prints one "soak:" line with its figures, also when it fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <mutex>
#include <random>
#include <set>
#include <sstream>
#include <thread>

#include "client/lib/document_view.h"
#include "client/lib/session.h"
#include "core/document/document.h"
#include "core/hierarchy/ids.h"
#include "core/io/mesh_export.h"
#include "core/io/mesh_import.h"
#include "core/tessellation/document_grid.h"
#include "core/tessellation/tessellation.h"
#include "core/util/file_io.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "integration/storm_history.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using client::DocumentView;
using client::Session;
using testing::ServerProcess;
using testing::StormCommand;
using Kind = StormCommand::Kind;

constexpr uint32_t kBase = 1, kMax = 3;
constexpr size_t kMaxHistories = 16;

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

// The level-3 limit surface as the server's ExportDocument writes it: GLB
// with float32 positions and normals, evaluated from scratch from the edit
// list. It tells apart histories whose surfaces the subscriber's quantized
// regions show alike (a coarse move tilting a fine vertex's frame moves the
// fine limit by about 1e-5).
constexpr uint32_t kExportLevel = 3;

wire::ClientMessage exportLimitSurface(uint64_t documentId) {
  wire::ClientMessage m;
  m.mutable_export_document()->set_document_id(documentId);
  m.mutable_export_document()->set_level(kExportLevel);
  m.mutable_export_document()->set_limit(true);
  return m;
}

std::string exportedGlb(const Document& doc, const std::string& path) {
  auto surface = doc.surface(kExportLevel, SurfaceKind::kLimit);
  if (!surface.isOk() || !exportMesh(*surface, path).isOk()) return {};
  auto bytes = readFile(path);
  return bytes.isOk() ? *bytes : std::string();
}

int envInt(const char* name, int fallback) {
  const char* value = std::getenv(name);
  return value != nullptr && *value != '\0' ? std::atoi(value) : fallback;
}

struct StormOptions {
  int cycles = 20;
  int editors = 2;
  int movePercent = 70, creasePercent = 15, undoPercent = 10;  // the rest are redos
  int stormMs = 180;
  int snapshotEvery = 7;
  uint32_t seed = 20261122;
  int maxSeconds = 0;

  static StormOptions fromEnvironment() {
    StormOptions o;
    o.cycles = envInt("TESSERA_SOAK_CYCLES", o.cycles);
    o.editors = envInt("TESSERA_SOAK_EDITORS", o.editors);
    if (const char* mix = std::getenv("TESSERA_SOAK_MIX"); mix != nullptr && *mix != '\0') {
      char comma = 0;
      std::istringstream(mix) >> o.movePercent >> comma >> o.creasePercent >> comma >> o.undoPercent;
    }
    o.stormMs = std::max(30, envInt("TESSERA_SOAK_STORM_MS", o.stormMs));
    o.snapshotEvery = envInt("TESSERA_SOAK_SNAPSHOT_EVERY", o.snapshotEvery);
    o.seed = static_cast<uint32_t>(envInt("TESSERA_SOAK_SEED", static_cast<int>(o.seed)));
    o.maxSeconds = envInt("TESSERA_SOAK_MAX_SECONDS", o.maxSeconds);
    return o;
  }
};

// What the run saw. Printed as one line when the test ends, passed or
// failed, so that the soak script reports figures either way.
struct Tally {
  int cycles = 0, cyclesPlanned = 0;
  std::map<Kind, int> acknowledged, refused;
  std::map<std::string, int> refusalReasons;
  int movesRefusedOtherwise = 0;  // for a reason other than the per-connection rate limit
  int editorCycles = 0,
      editorCyclesOpened = 0;  // editors started, and those that opened the document before the kill
  int inFlight = 0, inFlightRecovered = 0;
  int losses = 0;  // acknowledged versions missing after a restart, or 1 for a surface no replay explains
  size_t maxHistories = 1;
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();

  static int sum(const std::map<Kind, int>& m) {
    int n = 0;
    for (const auto& [kind, count] : m) n += count;
    return n;
  }
  ~Tally() {
    std::string reasons;
    for (const auto& [reason, count] : refusalReasons) reasons += " " + reason + "=" + std::to_string(count);
    std::printf(
        "soak: %d/%d cycles; editors opened the document in %d of %d editor-cycles; acknowledged %d (moves "
        "%d, creases "
        "%d, undos %d, redos %d); refused %d (moves %d)%s; in flight at the kill %d, recovered %d; losses "
        "%d; "
        "candidate histories at most %zu; %.1f s\n",
        cycles, cyclesPlanned, editorCyclesOpened, editorCycles, sum(acknowledged), acknowledged[Kind::kMove],
        acknowledged[Kind::kCrease], acknowledged[Kind::kUndo], acknowledged[Kind::kRedo], sum(refused),
        refused[Kind::kMove], reasons.c_str(), inFlight, inFlightRecovered, losses, maxHistories,
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    std::fflush(stdout);
  }
};

struct Acknowledged {
  StormCommand command;
  uint64_t editId = 0;  // as the Ack carried it
};

// One editor's cycle: commands until the server dies (or 2,000). Undos
// and redos name this editor's own edits acknowledged in this cycle: so
// every one the server acknowledges is valid in every candidate history,
// and no edit changes after its cycle (settledStateKey relies on it).
void editorStorm(const ServerProcess& server, const std::string& token, uint64_t docId,
                 const StormOptions& options, const LevelCounts& counts, uint32_t seed, int index,
                 std::mutex& mutex, std::map<uint64_t, Acknowledged>& acked,
                 std::vector<StormCommand>& inFlight, Tally& tally) {
  auto session = Session::connect(server.session("editor" + std::to_string(index), token));
  if (!session.isOk() || !(*session)->call(testing::openDocument(docId), 10).isOk()) return;  // killed first
  {
    std::lock_guard lock(mutex);
    ++tally.editorCyclesOpened;
  }
  std::mt19937 local(seed);
  std::vector<uint64_t> active, undone;
  for (int i = 0; i < 2000; ++i) {
    const int roll = static_cast<int>(local() % 100);
    StormCommand command;
    if (roll < options.movePercent + options.creasePercent) {
      command = roll < options.movePercent ? testing::randomSignedMove(local, counts, index, options.editors)
                                           : testing::randomCrease(local, counts, index, options.editors);
    } else if (roll < options.movePercent + options.creasePercent + options.undoPercent && !active.empty()) {
      command.kind = Kind::kUndo;
      command.target = active[local() % active.size()];
    } else if (!undone.empty()) {
      command.kind = Kind::kRedo;
      command.target = undone[local() % undone.size()];
    } else {
      command = testing::randomSignedMove(local, counts, index, options.editors);
    }
    auto reply = (*session)->call(command.message(docId), 5);
    std::lock_guard lock(mutex);
    if (!reply.isOk()) {
      inFlight.push_back(command);  // the server died with it unanswered
      return;
    }
    if (reply->has_ack()) {
      acked[reply->ack().version()] = {command, reply->ack().edit_id()};
      ++tally.acknowledged[command.kind];
      if (command.kind == Kind::kUndo) {
        std::erase(active, command.target);
        undone.push_back(command.target);
      } else if (command.kind == Kind::kRedo) {
        std::erase(undone, command.target);
        active.push_back(command.target);
      } else {
        active.push_back(reply->ack().edit_id());
      }
    } else {
      ++tally.refused[command.kind];
      ++tally.refusalReasons[reply->has_reject() ? wire::RejectReason_Name(reply->reject().reason())
                                                 : "other reply"];
      const bool rateLimited =
          reply->has_reject() && reply->reject().reason() == wire::REJECT_REASON_RATE_LIMITED;
      if (command.kind == Kind::kMove && !rateLimited) ++tally.movesRefusedOtherwise;
    }
  }
}

TEST(ServerDurability, AcknowledgedEditsSurviveKillNine) {
  const StormOptions options = StormOptions::fromEnvironment();
  // Each editor moves its own share of the 8 base vertices (storm_history.h).
  ASSERT_TRUE(options.editors >= 1 && options.editors <= 8) << "TESSERA_SOAK_EDITORS must be 1..8";
  Tally tally;
  tally.cyclesPlanned = options.cycles;
  const std::string dir = testing::makeTempDir("tessera-server-kill");
  const std::string data = dir + "/data";
  const std::string cubePath = testing::sourceTestDataPath("cube.obj");
  // Frequent snapshots: recovery reads a snapshot plus the journal after it.
  const std::vector<std::string> serverArgs = {"--snapshot-every", std::to_string(options.snapshotEvery)};
  std::optional<ServerProcess> server;
  {
    auto started = ServerProcess::start(data, serverArgs);
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

  // Local replicas of the acknowledged history. In-flight commands that
  // were recovered may land in any order, and the checker sees the surface
  // only through the subscriber's quantized regions and the float32 export.
  // Every history those cannot tell apart is kept, once per
  // settledStateKey (same-level moves of different vertices commute exactly,
  // and in-flight creases or undos may change nothing, which would otherwise
  // double the set at every such cycle), and later cycles prune them; one
  // must survive every cycle.
  auto mesh = importMesh(cubePath);
  ASSERT_TRUE(mesh.isOk());
  auto created0 = Document::create(*mesh, {.maxLevel = 4});
  ASSERT_TRUE(created0.isOk());
  const LevelCounts counts = created0->counts();
  std::vector<Document> replicas{std::move(*created0)};
  uint64_t replicaVersion = 1;

  std::mt19937 rng(options.seed);
  auto outOfTime = [&] {
    return options.maxSeconds > 0 &&
           std::chrono::steady_clock::now() - tally.start > std::chrono::seconds(options.maxSeconds);
  };
  for (int cycle = 0; cycle < options.cycles && !outOfTime(); ++cycle) {
    SCOPED_TRACE("cycle " + std::to_string(cycle));
    std::mutex mutex;
    std::map<uint64_t, Acknowledged> acked;  // version -> command
    std::vector<StormCommand> inFlight;
    std::vector<std::thread> editors;
    tally.editorCycles += options.editors;
    for (int e = 0; e < options.editors; ++e) {
      editors.emplace_back(editorStorm, std::cref(*server), std::cref(token), docId, std::cref(options),
                           std::cref(counts), static_cast<uint32_t>(rng()), e, std::ref(mutex),
                           std::ref(acked), std::ref(inFlight), std::ref(tally));
    }
    std::this_thread::sleep_for(
        std::chrono::milliseconds(30 + rng() % static_cast<uint32_t>(options.stormMs - 29)));
    server->kill9();
    for (auto& t : editors) t.join();
    tally.inFlight += static_cast<int>(inFlight.size());

    auto restarted = ServerProcess::start(data, serverArgs);
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
    auto exported = (*viewer)->call(exportLimitSurface(docId), 30);
    ASSERT_TRUE(exported.isOk() && exported->has_export_result());
    ASSERT_EQ(exported->export_result().version(), view.version());
    const std::string& serverGlb = exported->export_result().glb();
    ASSERT_FALSE(serverGlb.empty());
    (*viewer)->close();

    // Every acknowledged version is present...
    const uint64_t recovered = view.version();
    const uint64_t lastAcked = acked.empty() ? replicaVersion : acked.rbegin()->first;
    if (recovered < lastAcked) {
      tally.losses += static_cast<int>(std::distance(acked.upper_bound(recovered), acked.end()));
    }
    ASSERT_GE(recovered, lastAcked) << "an acknowledged edit was lost";
    // ...and versions 1..recovered are the acknowledged commands plus, in
    // the gaps, in-flight ones (at most one per editor).
    std::vector<uint64_t> gaps;
    for (uint64_t v = replicaVersion + 1; v <= recovered; ++v) {
      if (!acked.count(v)) gaps.push_back(v);
    }
    ASSERT_LE(gaps.size(), inFlight.size()) << "versions the clients never sent";
    tally.inFlightRecovered += static_cast<int>(gaps.size());
    // Each history so far, continued by each assignment of in-flight
    // commands to the gaps. An acknowledged command must apply and make the
    // edit id its Ack named (an in-flight edit recovered or not shifts the
    // ids after it).
    std::vector<int> order(inFlight.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    std::vector<Document> survivors;
    std::set<std::string> seen;
    for (const Document& replica : replicas) {
      std::set<std::vector<int>> tried;  // orders that differ only past the gaps are one assignment
      std::sort(order.begin(), order.end());
      do {
        if (!tried.insert(std::vector<int>(order.begin(), order.begin() + static_cast<long>(gaps.size())))
                 .second) {
          continue;
        }
        Document candidate = replica;
        bool ok = true;
        size_t gap = 0;
        for (uint64_t v = replicaVersion + 1; v <= recovered && ok; ++v) {
          auto a = acked.find(v);
          if (a != acked.end()) {
            auto id = a->second.command.applyTo(candidate);
            ok = id.isOk() && *id == a->second.editId;
          } else {
            ok = inFlight[order[gap++]].applyTo(candidate).isOk();
          }
        }
        if (!ok || !seen.insert(testing::settledStateKey(candidate)).second) continue;
        if (exportedGlb(candidate, dir + "/candidate.glb") == serverGlb &&
            expectedHash(candidate, docId) == view.surfaceHash()) {
          survivors.push_back(std::move(candidate));
        }
      } while (std::next_permutation(order.begin(), order.end()));
    }
    if (survivors.empty()) ++tally.losses;
    ASSERT_FALSE(survivors.empty())
        << "the recovered surface is no replay of the acknowledged history (version " << recovered << ", "
        << acked.size() << " acked, " << inFlight.size() << " in flight, " << replicas.size()
        << " candidate histories)";
    // A bound on the check's work: each history is replayed for every
    // assignment of the next cycle's in-flight commands (up to 4! = 24 with
    // 4 editors). Soaks of 100 to 300 cycles kept at most 2 (docs/STORE.md);
    // more than this many would mean the observation no longer tells
    // histories apart.
    ASSERT_LE(survivors.size(), kMaxHistories) << "too many histories match the recovered surface";
    tally.maxHistories = std::max(tally.maxHistories, survivors.size());
    replicas = std::move(survivors);
    replicaVersion = recovered;
    ++tally.cycles;
  }
  EXPECT_EQ(tally.cycles, options.cycles) << "stopped by TESSERA_SOAK_MAX_SECONDS";
  // With signed offsets of at most 0.01 per axis no move leaves the
  // document's grid (five times the cube's extent); the unsigned generator
  // this replaces had 86 % of its moves refused, and so recovered only moves
  // with non-negative components.
  // (The soak's longer storms may meet the server's 200 commands per second
  // per connection; those refusals say nothing about the moves.)
  const int judgedMoves = tally.acknowledged[Kind::kMove] + tally.movesRefusedOtherwise;
  EXPECT_GE(tally.acknowledged[Kind::kMove] * 20, judgedMoves * 19)
      << "more than 5 % of the moves were refused";
  EXPECT_GE(tally.acknowledged[Kind::kMove], 5 * options.cycles);
  if (options.creasePercent > 0) {
    EXPECT_GT(tally.acknowledged[Kind::kCrease], 0);
  }
  if (options.undoPercent > 0) {
    EXPECT_GT(tally.acknowledged[Kind::kUndo], 0);
  }
  EXPECT_EQ(server->stop(), 0);
}

}  // namespace
}  // namespace tessera
