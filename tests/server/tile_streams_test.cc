// The camera moves of view subscribers on their own (server/document/
// tile_streams.h, docs/VIEWS.md "The server"): a turn builds a few tiles,
// a view that needs more goes on in the next turns at once, and those
// continuations are the server's, so a view its client sends meanwhile
// still waits for --view-interval-ms. No host, no threads: the clock is the
// test's argument.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <memory>

#include "core/document/document.h"
#include "core/io/mesh_import.h"
#include "core/tessellation/document_grid.h"
#include "server/document/tile_cache.h"
#include "server/document/tile_streams.h"
#include "support/cameras.h"
#include "support/decoding_inbox.h"
#include "support/test_meshes.h"
#include "support/tile_gaps.h"

namespace tessera::server {
namespace {

using Clock = TileStreams::Clock;
using namespace std::chrono_literals;

constexpr int64_t kBudget = 4'000'000;

using testing::lookAt;

class TileStreamsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto mesh = importMesh(testing::cgalMeshPath("hand.off"));
    ASSERT_TRUE(mesh.isOk()) << mesh.status().message();
    auto doc = Document::create(*mesh, {.maxLevel = 4});
    ASSERT_TRUE(doc.isOk()) << doc.status().message();
    doc_ = std::make_unique<Document>(std::move(*doc));
    Vec3 lo = doc_->basePoints()[0], hi = lo;
    for (const Vec3& p : doc_->basePoints()) lo = testing::min(lo, p), hi = testing::max(hi, p);
    centre_ = 0.5 * (lo + hi);
    radius_ = 0.5 * (hi - lo).norm();
    auto grid = documentGrid(*doc_);
    ASSERT_TRUE(grid.isOk()) << grid.status().message();
    grid_ = *grid;
    cache_ = std::make_unique<TileCache>(*doc_, grid_, uint64_t{1} << 30, stats_);
  }
  // The whole hand, far away: a few coarse tiles.
  View far() const { return lookAt(centre_ + Vec3(0, 0, 3 * radius_), centre_, 390, 844); }
  // A desktop camera close to the surface: many fine tiles nobody built.
  View close(double side) const {
    const Vec3 target = doc_->basePoints()[0];
    const Vec3 out = (target - centre_).normalized();
    return lookAt(target + 0.15 * radius_ * (out + Vec3(side, 0, 0)), target, 1920, 1080);
  }
  void subscribe(const View& view, TileStreams& streams) {
    auto target = cache_->select(view, kBudget);
    ASSERT_TRUE(target.isOk()) << target.status().message();
    ASSERT_TRUE(streams.open(*cache_, viewer_, view, kBudget, {}, 1, false).isOk());
    ASSERT_TRUE(streams.start(*cache_, viewer_->sessionId(), *target, 1).isOk());
  }
  void subscribe(const View& view) { subscribe(view, streams_); }
  bool lastDeltaCompletes(uint64_t viewSeq) const {
    for (auto m = viewer_->received.rbegin(); m != viewer_->received.rend(); ++m) {
      if (m->has_delta()) return m->delta().view_complete() && m->delta().view_seq() == viewSeq;
    }
    return false;
  }

  // From the far view to the close one on `streams`: the turns it takes,
  // each due at once after the first, the last completing the view.
  int turnsToClose(TileStreams& streams) {
    subscribe(far(), streams);
    if (::testing::Test::HasFatalFailure()) return 0;
    const Clock::time_point t = Clock::now() + interval_;
    streams.setPending(viewer_->sessionId(), close(0), 1);
    streams.applyDue(*cache_, t, interval_, 1);
    EXPECT_GE(stats_.viewContinuations.load(), 1)
        << "the close view must need more tiles than one turn builds";
    EXPECT_FALSE(lastDeltaCompletes(1));
    int turns = 1;
    while (auto due = streams.nextDue(interval_)) {
      EXPECT_LE(*due, t) << "a continuation waits for nothing, turn " << turns;
      if (turns >= 10'000) {
        ADD_FAILURE() << "the view never completes";
        break;
      }
      streams.applyDue(*cache_, t, interval_, 1);
      ++turns;
    }
    EXPECT_TRUE(lastDeltaCompletes(1)) << "after " << turns << " turns";
    EXPECT_EQ(stats_.viewsApplied.load(), 1) << "continuations are not the client's views";
    EXPECT_EQ(stats_.viewContinuations.load(), turns - 1);
    return turns;
  }

  std::unique_ptr<Document> doc_;
  Vec3 centre_;
  double radius_ = 0;
  QuantizationGrid grid_;
  ServerStats stats_;
  std::unique_ptr<TileCache> cache_;
  TileStreams streams_{1, 1u << 26, stats_};
  std::shared_ptr<testing::DecodingInbox> viewer_ = std::make_shared<testing::DecodingInbox>(1);
  const Clock::duration interval_ = 50ms;
};

TEST_F(TileStreamsTest, AViewThatNeedsManyNewTilesGoesOnAtOnceTurnByTurnUntilComplete) {
  std::printf("[ measured ] the close view completed in %d turns\n", turnsToClose(streams_));
}

// While an edit waits, a turn builds one refinement's tiles and no more
// (selectTilesForEach's stopBuilding): more turns, the same end.
TEST_F(TileStreamsTest, WhileAnEditWaitsATurnBuildsOneRefinement) {
  const int quietTurns = turnsToClose(streams_);
  // Again from no tiles, an edit waiting throughout.
  cache_ = std::make_unique<TileCache>(*doc_, grid_, uint64_t{1} << 30, stats_);
  viewer_ = std::make_shared<testing::DecodingInbox>(2);
  stats_.viewContinuations = 0;
  stats_.viewsApplied = 0;
  int asked = 0;
  TileStreams streams(1, 1u << 26, stats_, [&] { return ++asked, true; });
  const int turns = turnsToClose(streams);
  std::printf("[ measured ] %d turns while an edit waits, %d without\n", turns, quietTurns);
  EXPECT_GT(turns, quietTurns);
  EXPECT_GE(asked, turns - 1) << "every turn that stopped asked";
}

TEST_F(TileStreamsTest, AViewSentDuringAContinuationWaitsForItsInterval) {
  subscribe(far());
  ASSERT_FALSE(::testing::Test::HasFatalFailure());
  const Clock::time_point t = Clock::now() + interval_;
  streams_.setPending(viewer_->sessionId(), close(0), 1);
  streams_.applyDue(*cache_, t, interval_, 1);
  ASSERT_GE(stats_.viewContinuations.load(), 1) << "the close view must need more tiles than one turn builds";
  ASSERT_EQ(stats_.viewsApplied.load(), 1);

  // The client moves again 1 ms later, while its view goes on: the new
  // view replaces the continuation, and is due one interval after the
  // last view the client sent was applied, not at once.
  streams_.setPending(viewer_->sessionId(), close(0.5), 2);
  auto due = streams_.nextDue(interval_);
  ASSERT_TRUE(due.has_value());
  EXPECT_EQ(*due, t + interval_);
  streams_.applyDue(*cache_, t + 1ms, interval_, 1);
  EXPECT_EQ(stats_.viewsApplied.load(), 1) << "a second view applied 1 ms after the first";
  streams_.applyDue(*cache_, t + interval_, interval_, 1);
  EXPECT_EQ(stats_.viewsApplied.load(), 2) << "the view waited its interval and is applied";
}

TEST_F(TileStreamsTest, SettlingMeasuresOneTileWhileAnEditWaitsAndGoesOnAfterIt) {
  bool editWaits = true;
  TileStreams streams(1, 1u << 26, stats_, [&] { return editWaits; });
  subscribe(far(), streams);
  ASSERT_FALSE(::testing::Test::HasFatalFailure());
  const VertexId moved[] = {VertexId(0, 0)};
  ASSERT_TRUE(doc_->moveBy(moved, radius_ * Vec3(0.01, -0.02, 0.015)).isOk());
  const std::vector<TileKey> reached = cache_->invalidate(doc_->lastUpdate().limits);
  streams.afterEdit(*cache_, reached, 1, 2, 0, 0);
  ASSERT_TRUE(streams.unsettled()) << "the far view's walk read a tile the edit reached";
  auto measured = [&] {
    return std::count_if(reached.begin(), reached.end(),
                         [&](const TileKey& k) { return cache_->hasBounds(k); });
  };
  const size_t sent = viewer_->received.size();
  int stops = 0;
  for (auto before = measured(); !streams.settle(*cache_, 2); before = measured()) {
    ++stops;
    ASSERT_LT(stops, 1000);
    EXPECT_EQ(measured(), before + 1) << "one tile per turn while an edit waits";
    EXPECT_EQ(viewer_->received.size(), sent) << "nothing decided before every tile is measured";
  }
  EXPECT_GE(stops, 1) << "the far view read more than one reached tile: settling should have stopped";
  std::printf("[ measured ] settling stopped %d times, one tile measured each\n", stops);
  EXPECT_FALSE(streams.unsettled());
  ASSERT_GT(viewer_->received.size(), sent);
  EXPECT_TRUE(lastDeltaCompletes(0)) << "the view is complete at the new version";

  // With no edit waiting, settling a second edit takes one turn.
  editWaits = false;
  ASSERT_TRUE(doc_->moveBy(moved, radius_ * Vec3(-0.01, 0.02, -0.015)).isOk());
  const std::vector<TileKey> again = cache_->invalidate(doc_->lastUpdate().limits);
  streams.afterEdit(*cache_, again, 2, 3, 0, 0);
  ASSERT_TRUE(streams.unsettled());
  EXPECT_TRUE(streams.settle(*cache_, 3));
  EXPECT_FALSE(streams.unsettled());
}

}  // namespace
}  // namespace tessera::server
