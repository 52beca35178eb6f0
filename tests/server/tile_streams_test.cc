// The camera moves of view subscribers on their own (server/document/
// tile_streams.h, docs/VIEWS.md "The server"): a turn builds a few tiles,
// a view that needs more goes on in the next turns at once, and those
// continuations are the server's, so a view its client sends meanwhile
// still waits for --view-interval-ms. No host, no threads: the clock is the
// test's argument.
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <numbers>

#include "core/document/document.h"
#include "core/io/mesh_import.h"
#include "core/tessellation/document_grid.h"
#include "server/document/tile_cache.h"
#include "server/document/tile_streams.h"
#include "support/decoding_inbox.h"
#include "support/test_meshes.h"
#include "support/tile_gaps.h"

namespace tessera::server {
namespace {

using Clock = TileStreams::Clock;
using namespace std::chrono_literals;

constexpr int64_t kBudget = 4'000'000;

// A perspective camera at `eye` looking at `target`, one pixel's tolerance.
View lookAt(const Vec3& eye, const Vec3& target, int width, int height) {
  View v;
  v.eye = eye;
  v.forward = target - eye;
  v.up = std::abs(v.forward.normalized()[1]) > 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  v.fovYRadians = 50 * std::numbers::pi / 180;
  v.nearDistance = 1e-4;
  v.width = width;
  v.height = height;
  v.tolerancePixels = 1;
  return v;
}

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
  void subscribe(const View& view) {
    auto target = cache_->select(view, kBudget);
    ASSERT_TRUE(target.isOk()) << target.status().message();
    ASSERT_TRUE(streams_.subscribe(*cache_, viewer_, view, kBudget, *target, {}, 1, false).isOk());
  }
  bool lastDeltaCompletes(uint64_t viewSeq) const {
    for (auto m = viewer_->received.rbegin(); m != viewer_->received.rend(); ++m) {
      if (m->has_delta()) return m->delta().view_complete() && m->delta().view_seq() == viewSeq;
    }
    return false;
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
  subscribe(far());
  ASSERT_FALSE(::testing::Test::HasFatalFailure());
  const Clock::time_point t = Clock::now() + interval_;
  streams_.setPending(viewer_->sessionId(), close(0), 1);
  streams_.applyDue(*cache_, t, interval_, 1);
  ASSERT_GE(stats_.viewContinuations.load(), 1) << "the close view must need more tiles than one turn builds";
  EXPECT_FALSE(lastDeltaCompletes(1));
  int turns = 1;
  while (auto due = streams_.nextDue(interval_)) {
    ASSERT_LE(*due, t) << "a continuation waits for nothing, turn " << turns;
    ASSERT_LT(turns, 10'000) << "the view never completes";
    streams_.applyDue(*cache_, t, interval_, 1);
    ++turns;
  }
  EXPECT_TRUE(lastDeltaCompletes(1)) << "after " << turns << " turns";
  EXPECT_EQ(stats_.viewsApplied.load(), 1) << "continuations are not the client's views";
  EXPECT_EQ(stats_.viewContinuations.load(), turns - 1);
  std::printf("[ measured ] the close view completed in %d turns\n", turns);
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

}  // namespace
}  // namespace tessera::server
