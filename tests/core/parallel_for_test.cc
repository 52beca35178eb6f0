// Work spread over cores (core/util/parallel_for.h): every item runs once,
// whatever the threads; and the steps that use it give bit-identical
// results on one thread and on several (a tessellation built and updated
// region by region, docs/ARCHITECTURE.md "One edit, end to end").
#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <random>
#include <set>
#include <thread>
#include <vector>

#include "core/document/document.h"
#include "core/io/mesh_import.h"
#include "core/tessellation/tessellation.h"
#include "core/util/parallel_for.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

TEST(ParallelFor, EveryItemRunsOnceWhateverTheThreads) {
  for (unsigned threads : {0u, 1u, 2u, 3u, 8u}) {
    for (size_t n : {size_t{0}, size_t{1}, size_t{2}, size_t{7}, size_t{1000}}) {
      std::vector<std::atomic<int>> runs(n);
      std::mutex mutex;
      std::set<std::thread::id> ids;
      parallelFor(n, threads, [&](size_t i) {
        runs[i].fetch_add(1);
        std::lock_guard lock(mutex);
        ids.insert(std::this_thread::get_id());
      });
      for (size_t i = 0; i < n; ++i) ASSERT_EQ(runs[i].load(), 1) << "item " << i << " of " << n;
      EXPECT_LE(ids.size(), std::max<size_t>(1, std::min<size_t>(n, threads)))
          << n << " items on " << threads << " threads";
      if (threads <= 1 && n > 0) {
        EXPECT_EQ(*ids.begin(), std::this_thread::get_id()) << "on the caller";
      }
    }
  }
}

// The helpers are shared: calls from several threads at once, and calls
// nested in an item, each finish with every item run once (a call works on
// with the threads it has, and never waits for a helper busy elsewhere).
TEST(ParallelFor, CallsFromSeveralThreadsAndNestedCallsAllFinish) {
  constexpr int kCallers = 4, kCalls = 200;
  std::atomic<int64_t> total{0};
  std::vector<std::jthread> callers;
  for (int c = 0; c < kCallers; ++c) {
    callers.emplace_back([&] {
      for (int k = 0; k < kCalls; ++k) {
        parallelFor(6, 3, [&](size_t i) {
          parallelFor(4, 2, [&](size_t j) { total.fetch_add(static_cast<int64_t>(10 * i + j)); });
        });
      }
    });
  }
  callers.clear();  // joined
  // Per outer call: sum over i < 6, j < 4 of 10 i + j = 4 * 10 * 15 + 6 * 6.
  EXPECT_EQ(total.load(), int64_t{kCallers} * kCalls * (4 * 10 * 15 + 6 * 6));
}

TEST(ParallelFor, WorkThreadsAreTheHardwaresUnlessChosen) {
  const unsigned hardware = workThreads();
  EXPECT_GE(hardware, 1u);
  EXPECT_LE(hardware, 4u);
  setWorkThreads(3);
  EXPECT_EQ(workThreads(), 3u);
  setWorkThreads(0);
  EXPECT_EQ(workThreads(), hardware);
}

void expectSameRegions(const Tessellation& a, const Tessellation& b, const std::string& what) {
  ASSERT_EQ(a.regions().size(), b.regions().size()) << what;
  for (const auto& [id, mesh] : a.regions()) {
    auto other = b.regions().find(id);
    ASSERT_NE(other, b.regions().end()) << what << ": region " << id;
    EXPECT_EQ(mesh.positions, other->second.positions) << what << ": region " << id;
    EXPECT_EQ(mesh.normals, other->second.normals) << what << ": region " << id;
    EXPECT_EQ(mesh.vertexIds, other->second.vertexIds) << what << ": region " << id;
    EXPECT_EQ(mesh.triangles, other->second.triangles) << what << ": region " << id;
  }
}

// Two documents, one tessellated on one thread and one on four, take the
// same random edits: every region stays bit-identical, and so do the
// changes each update reports.
TEST(ParallelFor, ATessellationOnFourThreadsEqualsOneOnOneThroughEdits) {
  auto mesh = importMesh(testing::cgalMeshPath("fandisk.off"));
  ASSERT_TRUE(mesh.isOk());
  auto one = Document::create(*mesh, {.maxLevel = 3});
  auto four = Document::create(*mesh, {.maxLevel = 3});
  ASSERT_TRUE(one.isOk() && four.isOk());
  const LodProfile profile{.baseLevel = 1, .maxLevel = 3, .angleThresholdDegrees = 10};
  setWorkThreads(1);
  auto t1 = Tessellation::build(*one, profile);
  setWorkThreads(4);
  auto t4 = Tessellation::build(*four, profile);
  ASSERT_TRUE(t1.isOk() && t4.isOk());
  expectSameRegions(*t1, *t4, "built");
  std::mt19937 rng(11);
  for (int edit = 0; edit < 12; ++edit) {
    const int level = edit % 3;
    const VertexId v(level,
                     std::uniform_int_distribution<uint64_t>(0, one->counts().vertices(level) - 1)(rng));
    const Vec3 by(0.002 * (edit % 5), -0.001 * edit, 0.003);
    ASSERT_TRUE(one->moveBy(std::span(&v, 1), by).isOk());
    ASSERT_TRUE(four->moveBy(std::span(&v, 1), by).isOk());
    setWorkThreads(1);
    auto c1 = t1->update(*one);
    setWorkThreads(4);
    auto c4 = t4->update(*four);
    ASSERT_TRUE(c1.isOk() && c4.isOk());
    EXPECT_EQ(c1->changed, c4->changed) << "edit " << edit;
    EXPECT_EQ(c1->relaid, c4->relaid) << "edit " << edit;
    EXPECT_FALSE(c4->changed.empty()) << "edit " << edit;
    expectSameRegions(*t1, *t4, "after edit " + std::to_string(edit));
  }
  setWorkThreads(0);
}

}  // namespace
}  // namespace tessera
