// A view-dependent subscriber on a node that does not own the document
// (docs/CLUSTER.md, docs/PROTOCOL.md section 16): its Subscribe with a view
// and its SetViews are forwarded to the owner, whose tiles come back through
// its own node; an edit on the owner reaches it as tiles whose hash is the
// owner's.
#include <gtest/gtest.h>

#include <chrono>
#include <random>

#include "client/lib/view_wire.h"
#include "cluster/cluster_run.h"
#include "integration/messages.h"

namespace tessera {
namespace {

using client::DocumentView;
using client::Session;

View cubeView(const Vec3& eye) {
  View v;
  v.eye = eye;
  v.forward = Vec3(0.5, 0.5, 0.5) - eye;
  v.up = Vec3(0, 1, 0);
  v.nearDistance = 1e-3;
  v.width = 390;
  v.height = 844;
  v.tolerancePixels = 1;
  return v;
}

// Reads until the view holds the tiles of SetView `seq` (0: the
// Subscribe's) at `version` or later.
bool untilComplete(Session& s, DocumentView& view, uint64_t seq, uint64_t version, double seconds) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < deadline) {
    auto m = s.receive(0.5);
    if (!m.isOk()) continue;
    if (!view.apply(*m).isOk()) return false;
    if (view.ready() && view.viewComplete() && view.viewSeq() == seq && view.version() >= version)
      return true;
  }
  return false;
}

TEST(ClusterViews, AViewOnAnotherNodeIsForwardedToTheOwnerAndItsTilesComeBack) {
  auto run = testing::ClusterRun::start(2);
  ASSERT_TRUE(run.isOk()) << run.status().message();
  testing::ClusterRun& c = **run;
  auto doc = c.createCube();
  ASSERT_TRUE(doc.isOk()) << doc.status().message();
  // Node 0 opens first and owns the document; the viewer is on node 1.
  auto editor = Session::connect(c.session(0, "editor", testing::kEditorToken));
  ASSERT_TRUE(editor.isOk());
  ASSERT_TRUE((*editor)->call(testing::openDocument(*doc), 30)->has_ack());
  auto viewer = Session::connect(c.session(1, "viewer", testing::kViewerToken));
  ASSERT_TRUE(viewer.isOk());
  ASSERT_TRUE((*viewer)->call(testing::openDocument(*doc), 30)->has_ack());
  DocumentView view(*doc);
  auto subscribed = (*viewer)->call(client::subscribeWithView(*doc, cubeView(Vec3(0.5, 0.5, 4))), 30);
  ASSERT_TRUE(subscribed.isOk() && subscribed->has_ack())
      << (subscribed.isOk() ? subscribed->DebugString() : subscribed.status().message());
  ASSERT_TRUE(untilComplete(**viewer, view, 0, 1, 30)) << "no complete view through node 1";
  EXPECT_TRUE(view.verifySurface().isOk()) << view.verifySurface().message();

  // A move of the camera, forwarded as SetView: the owner's answer names it.
  auto seq = (*viewer)->send(client::setView(*doc, cubeView(Vec3(1.3, 1.2, 1.4))));
  ASSERT_TRUE(seq.isOk());
  ASSERT_TRUE(untilComplete(**viewer, view, *seq, 1, 30)) << "the moved view never completed";
  EXPECT_TRUE(view.verifySurface().isOk()) << view.verifySurface().message();

  // An edit on the owner reaches the view.
  std::mt19937 rng(3);
  auto ack = (*editor)->call(testing::smallMove(*doc, rng), 30);
  ASSERT_TRUE(ack.isOk() && ack->has_ack()) << (ack.isOk() ? ack->DebugString() : ack.status().message());
  ASSERT_TRUE(untilComplete(**viewer, view, *seq, ack->ack().version(), 30))
      << "the edit never reached the view";
  EXPECT_TRUE(view.verifySurface().isOk()) << view.verifySurface().message();
}

}  // namespace
}  // namespace tessera
