// The views of a document on their own (server/document/document_views.h,
// docs/ARCHITECTURE.md "One edit, end to end", steps 4 and 5, and "Bulk
// work"): one view per subscriber, a delta only to those whose snapshot
// lacks it, unwatched views dropped but for the most recent morph views
// within one subscriber's budget, and a view whose update fails dropped
// with word to its subscribers. No host, no threads: each call's effect is
// there when it returns.
#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/document/document.h"
#include "core/tessellation/document_grid.h"
#include "server/document/document_views.h"
#include "server/document/replies.h"
#include "support/decoding_inbox.h"
#include "support/test_meshes.h"

namespace tessera::server {
namespace {

using Inbox = testing::DecodingInbox;

std::vector<std::string> keysOf(const DocumentViews::Views& views) {
  std::vector<std::string> keys;
  for (const auto& [key, view] : views) keys.push_back(key);
  return keys;
}

class DocumentViewsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto doc = testing::cubeDocument(2);
    ASSERT_TRUE(doc.isOk()) << doc.status().message();
    doc_.emplace(std::move(*doc));
    auto tessellation = Tessellation::build(*doc_, {.baseLevel = 1, .maxLevel = 2});
    ASSERT_TRUE(tessellation.isOk());
    morphTriangles_ = tessellation->numTriangles();
    ASSERT_GT(morphTriangles_, 0);
    // Two morph views fit the budget, three do not.
    views_.emplace(store::DocumentId{7}, 2 * morphTriangles_, 1u << 20);
  }
  // A view at time t of a morph (its tessellation is what the budget counts).
  LodView morphView(double t) {
    LodView view;
    view.morphT = t;
    view.tessellation =
        std::make_unique<Tessellation>(*Tessellation::build(*doc_, {.baseLevel = 1, .maxLevel = 2}));
    return view;
  }
  // `who` moves to view `key` as its host does: it leaves the others, then
  // the view is added if new, then it gets its snapshot at `version`.
  DocumentViews::Views subscribe(const std::shared_ptr<Inbox>& who, const std::string& key, LodView fresh,
                                 uint64_t version = 1) {
    DocumentViews::Views dropped = views_->leaveAllBut(who->sessionId(), key);
    LodView* view = views_->find(key);
    if (!view) view = &views_->add(key, std::move(fresh));
    views_->attach(*view, who, version);
    return dropped;
  }

  std::optional<Document> doc_;
  int64_t morphTriangles_ = 0;
  std::optional<DocumentViews> views_;
  std::shared_ptr<Inbox> ann_ = std::make_shared<Inbox>(1), bob_ = std::make_shared<Inbox>(2);
  const std::shared_ptr<const std::string> frame_ = frameOf(ackFor(40, 7), 1u << 20);
};

TEST_F(DocumentViewsTest, ADeltaGoesOnlyToSubscribersWhoseSnapshotLacksIt) {
  subscribe(ann_, "a", LodView{}, /*version=*/3);
  subscribe(bob_, "a", LodView{}, /*version=*/5);
  FlushBatch batch{4, {}, {{"a", frame_}, {"gone", frame_}}};
  views_->send(batch);
  ASSERT_EQ(ann_->received.size(), 1u);
  EXPECT_EQ(ann_->received[0].ack().client_seq(), 40u);
  EXPECT_TRUE(bob_->received.empty()) << "its snapshot at version 5 holds version 4";
  EXPECT_TRUE(batch.frames.empty());
  views_->send(batch);
  EXPECT_EQ(ann_->received.size(), 1u) << "sending a batch again is a no-op";
}

TEST_F(DocumentViewsTest, ADeltaGoesInEachSubscribersCodec) {
  // Ann decodes Draco, Bob meshopt (docs/REGION_ENCODING.md "meshopt
  // regions"): one view, one frame per codec, keyed "a" and "a|meshopt".
  subscribe(ann_, "a", LodView{}, /*version=*/3);
  views_->attach(*views_->find("a"), bob_, 3, RegionCodec::kMeshopt);
  EXPECT_EQ(heldCodecs(*views_->find("a")),
            (std::vector<RegionCodec>{RegionCodec::kDraco, RegionCodec::kMeshopt}));
  const auto meshoptFrame = frameOf(ackFor(41, 7), 1u << 20);
  FlushBatch batch{4, {}, {{"a", frame_}, {"a|meshopt", meshoptFrame}}};
  views_->send(batch);
  ASSERT_EQ(ann_->received.size(), 1u);
  EXPECT_EQ(ann_->received[0].ack().client_seq(), 40u);
  ASSERT_EQ(bob_->received.size(), 1u);
  EXPECT_EQ(bob_->received[0].ack().client_seq(), 41u);
  // Once Bob leaves, nobody holds meshopt: the flush encodes it no more.
  views_->leave(bob_->sessionId());
  EXPECT_EQ(heldCodecs(*views_->find("a")), std::vector<RegionCodec>{RegionCodec::kDraco});
}

TEST_F(DocumentViewsTest, ADeltaIsEncodedOncePerCodecSomeoneHolds) {
  LodView fresh;
  fresh.tessellation =
      std::make_unique<Tessellation>(*Tessellation::build(*doc_, {.baseLevel = 1, .maxLevel = 2}));
  subscribe(ann_, "a", std::move(fresh), /*version=*/1);
  LodView& view = *views_->find("a");
  auto grid = documentGrid(*doc_);
  ASSERT_TRUE(grid.isOk());
  ServerStats stats;
  Tessellation::Changes changes;
  for (const auto& [region, mesh] : view.tessellation->regions()) {
    view.layout[region] = 1;
    changes.changed.push_back(region);
  }
  changes.relaid = changes.changed;
  const auto magics = [](const DeltaContent& delta) {
    std::set<std::string> out;
    for (const RegionPayload& r : delta.regions) out.insert(r.bytes->substr(0, 4));
    return out;
  };
  const int64_t n = static_cast<int64_t>(changes.changed.size());
  // Draco alone: nobody holds meshopt, nothing is encoded in it.
  auto deltas = buildDeltas(view, changes, EncodeContext{2, *grid, *doc_, stats}, 7, DeltaContent{});
  ASSERT_EQ(deltas.size(), 1u);
  EXPECT_EQ(deltas[0].first, RegionCodec::kDraco);
  EXPECT_EQ(deltas[0].second.regions.size(), changes.changed.size());
  EXPECT_EQ(magics(deltas[0].second), std::set<std::string>{"TSRG"});
  EXPECT_EQ(stats.regionsEncoded.load(), n);
  // Bob decodes meshopt: each region once more, in meshopt, whatever the
  // number of meshopt subscribers.
  views_->attach(view, bob_, 2, RegionCodec::kMeshopt);
  auto carol = std::make_shared<Inbox>(3);
  views_->attach(view, carol, 2, RegionCodec::kMeshopt);
  deltas = buildDeltas(view, changes, EncodeContext{3, *grid, *doc_, stats}, 7, DeltaContent{});
  ASSERT_EQ(deltas.size(), 2u);
  EXPECT_EQ(deltas[1].first, RegionCodec::kMeshopt);
  EXPECT_EQ(magics(deltas[0].second), std::set<std::string>{"TSRG"});
  EXPECT_EQ(magics(deltas[1].second), std::set<std::string>{"TSRM"});
  EXPECT_EQ(deltas[1].second.surfaceHash, deltas[0].second.surfaceHash);
  EXPECT_EQ(stats.regionsEncoded.load(), 3 * n);
  EXPECT_EQ(view.encoded[1].size(), changes.changed.size());
  // Both leave: the meshopt cache goes at the next flush (it would be stale).
  views_->leave(bob_->sessionId());
  views_->leave(carol->sessionId());
  deltas = buildDeltas(view, changes, EncodeContext{4, *grid, *doc_, stats}, 7, DeltaContent{});
  ASSERT_EQ(deltas.size(), 1u);
  EXPECT_TRUE(view.encoded[1].empty());
  EXPECT_EQ(stats.regionsEncoded.load(), 4 * n);
}

TEST_F(DocumentViewsTest, ASubscriberWatchesOneViewOfADocument) {
  subscribe(ann_, "a", LodView{});
  subscribe(bob_, "b", LodView{});
  EXPECT_EQ(views_->watchedByOthers(1), 1u);
  EXPECT_EQ(views_->watchedByOthers(3), 2u);
  EXPECT_EQ(views_->subscriberCount(), 2u);

  // Ann moves to b: a has nobody left, and goes at once (not a morph view).
  EXPECT_EQ(keysOf(subscribe(ann_, "b", LodView{})), std::vector<std::string>{"a"});
  EXPECT_EQ(views_->size(), 1u);
  EXPECT_EQ(views_->find("a"), nullptr);
  EXPECT_EQ(views_->subscriberCount(), 2u);

  // Bob moves to c: b stays, Ann watches it.
  EXPECT_TRUE(subscribe(bob_, "c", LodView{}).empty());
  EXPECT_EQ(views_->size(), 2u);
}

TEST_F(DocumentViewsTest, AGoneSubscriberWatchesNothing) {
  subscribe(ann_, "a", LodView{});
  subscribe(bob_, "b", LodView{});
  bob_.reset();
  EXPECT_EQ(views_->watchedByOthers(1), 0u);
  EXPECT_EQ(keysOf(views_->dropUnwatched()), std::vector<std::string>{"b"});
}

TEST_F(DocumentViewsTest, LeavingDropsTheViewsNobodyWatches) {
  subscribe(ann_, "a", LodView{});
  subscribe(bob_, "a", LodView{});
  EXPECT_TRUE(views_->leave(1).empty()) << "Bob still watches a";
  EXPECT_EQ(keysOf(views_->leave(2)), std::vector<std::string>{"a"});
  EXPECT_EQ(views_->size(), 0u);
}

TEST_F(DocumentViewsTest, UnwatchedMorphViewsStayMostRecentFirstWithinTheBudget) {
  subscribe(ann_, "t0.1", morphView(0.1));
  EXPECT_TRUE(subscribe(ann_, "t0.2", morphView(0.2)).empty()) << "t0.1 is kept: one view's triangles";
  EXPECT_TRUE(subscribe(ann_, "t0.3", morphView(0.3)).empty()) << "t0.1 and t0.2 fit the budget";
  subscribe(bob_, "t0.9", morphView(0.9));
  EXPECT_EQ(keysOf(views_->leave(1)), std::vector<std::string>{"t0.1"})
      << "three unwatched morph views are over the budget: the least recently used goes";
  EXPECT_EQ(views_->size(), 3u);

  // A key changed: every unwatched morph view is stale, the watched one stays.
  EXPECT_EQ(keysOf(views_->dropRetainedMorphViews()), (std::vector<std::string>{"t0.2", "t0.3"}));
  EXPECT_NE(views_->find("t0.9"), nullptr);
}

TEST_F(DocumentViewsTest, MovingBackToARetainedMorphViewKeepsIt) {
  subscribe(ann_, "t0.1", morphView(0.1));
  subscribe(ann_, "t0.2", morphView(0.2));
  subscribe(ann_, "t0.3", morphView(0.3));  // t0.1 and t0.2 kept, unwatched
  // Ann goes back to t0.1, the least recently used. The view she leaves,
  // t0.3, is now unwatched and the most recent: with t0.2 it fills the
  // budget of unwatched views, so counted with them t0.1 would go. It is
  // about to be watched: it stays, and is not counted.
  EXPECT_TRUE(views_->leaveAllBut(ann_->sessionId(), "t0.1").empty());
  LodView* back = views_->find("t0.1");
  ASSERT_NE(back, nullptr) << "the view a subscriber moves to was dropped under it";
  views_->attach(*back, ann_, 1);
  EXPECT_NE(views_->find("t0.2"), nullptr);
  EXPECT_NE(views_->find("t0.3"), nullptr);
  // Leaving t0.1 now makes three unwatched views: the oldest use goes.
  EXPECT_EQ(keysOf(views_->leave(ann_->sessionId())), std::vector<std::string>{"t0.2"});
}

TEST_F(DocumentViewsTest, AViewWhoseUpdateFailsGoesAndItsSubscribersAreTold) {
  subscribe(ann_, "a", LodView{});
  subscribe(bob_, "b", LodView{});
  std::vector<std::string> updated;
  views_->updateEach([&](const std::string& key, LodView&) {
    updated.push_back(key);
    return key == "b" ? invalidArgument("over its budget") : Status::ok();
  });
  EXPECT_EQ(updated, (std::vector<std::string>{"a", "b"})) << "every view, in key order";
  EXPECT_TRUE(ann_->received.empty());
  ASSERT_EQ(bob_->received.size(), 1u);
  EXPECT_EQ(bob_->received[0].error().code(), wire::ERROR_CODE_INTERNAL);
  EXPECT_EQ(bob_->received[0].error().message(), "LOD profile b dropped: over its budget");
  EXPECT_EQ(views_->find("b"), nullptr);
  EXPECT_NE(views_->find("a"), nullptr);
}

TEST_F(DocumentViewsTest, TakeAllLeavesNoView) {
  subscribe(ann_, "a", LodView{});
  subscribe(bob_, "b", LodView{});
  EXPECT_EQ(keysOf(views_->takeAll()), (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(views_->size(), 0u);
}

}  // namespace
}  // namespace tessera::server
