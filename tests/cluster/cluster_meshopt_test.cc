// meshopt regions across the cluster (docs/REGION_ENCODING.md "meshopt
// regions", docs/CLUSTER.md "Any node serves any client"): a LOD profile
// subscription with codec meshopt on a node that does not own the document
// is forwarded to the owner, which encodes each region once per version,
// profile and codec; the relay merges only identical frames, so a meshopt
// and a Draco subscriber on the same node each get their own codec, in the
// snapshot and in the delta of an edit, and decode the same surface.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <random>
#include <string>

#include "cluster/cluster_run.h"
#include "core/tessellation/region_codec.h"
#include "integration/messages.h"
#include "integration/server_stat.h"

namespace tessera {
namespace {

using client::DocumentView;
using client::Session;
using testing::ClusterRun;

struct CodecViewer {
  std::unique_ptr<Session> session;
  std::unique_ptr<DocumentView> view;
  RegionCodec expected = RegionCodec::kDraco;
  size_t snapshotRegions = 0, deltaRegions = 0;
  size_t snapshotOther = 0, deltaOther = 0;  // regions not in `expected`, or not decoding
};

// Opens the document on `node` and subscribes at the cluster tests' profile
// with `codec` (PROTOCOL.md 7.2, Subscribe.codec).
CodecViewer subscribeOn(ClusterRun& c, int node, uint64_t doc, wire::RegionCodec codec,
                        RegionCodec expected) {
  CodecViewer v;
  v.expected = expected;
  auto s = Session::connect(c.session(node, "viewer@" + c.nodeName(node), testing::kViewerToken));
  EXPECT_TRUE(s.isOk()) << s.status().message();
  if (!s.isOk()) return v;
  auto opened = (*s)->call(testing::openDocument(doc), 30);
  EXPECT_TRUE(opened.isOk() && opened->has_ack());
  auto sub = testing::subscribe(doc, testing::kClusterBase, testing::kClusterMax, testing::kClusterAngle);
  sub.mutable_subscribe()->set_codec(codec);
  auto subscribed = (*s)->call(sub, 30);
  EXPECT_TRUE(subscribed.isOk() && subscribed->has_ack())
      << (subscribed.isOk() ? subscribed->DebugString() : subscribed.status().message());
  v.session = std::move(*s);
  v.view = std::make_unique<DocumentView>(doc);
  return v;
}

// Reads until the view holds `version`, decoding every region received to
// see which codec it came in (decodeRegion reads either, header.codec says
// which). A gap fails: a resubscription could hide a codec mix-up.
bool readUntil(CodecViewer& v, uint64_t version, double seconds) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  auto count = [&](const google::protobuf::RepeatedPtrField<wire::Region>& regions, size_t& n,
                   size_t& other) {
    for (const wire::Region& r : regions) {
      ++n;
      auto decoded = decodeRegion(r.draco());
      if (!decoded.isOk() || decoded->first.codec != v.expected) ++other;
    }
  };
  while (std::chrono::steady_clock::now() < deadline) {
    if (v.view->ready() && v.view->version() >= version) return true;
    auto m = v.session->receive(0.5);
    if (!m.isOk()) {
      if (client::isReceiveTimeout(m.status())) continue;
      return false;
    }
    if (m->has_snapshot()) count(m->snapshot().regions(), v.snapshotRegions, v.snapshotOther);
    if (m->has_delta()) count(m->delta().regions(), v.deltaRegions, v.deltaOther);
    if (!v.view->apply(*m).isOk() || v.view->gaps() > 0) return false;
  }
  return v.view->ready() && v.view->version() >= version;
}

TEST(ClusterMeshopt, AMeshoptSubscriberOnANonOwnerNodeGetsMeshoptSnapshotAndDelta) {
  auto run = ClusterRun::start(2);
  ASSERT_TRUE(run.isOk()) << run.status().message();
  ClusterRun& c = **run;
  auto doc = c.createCube();
  ASSERT_TRUE(doc.isOk()) << doc.status().message();
  // The editor on node 0 opens first: node 0 owns the document.
  auto editor = Session::connect(c.session(0, "editor", testing::kEditorToken));
  ASSERT_TRUE(editor.isOk()) << editor.status().message();
  ASSERT_TRUE((*editor)->call(testing::openDocument(*doc), 30)->has_ack());

  // Both subscribers on node 1, which forwards to the owner.
  CodecViewer meshopt = subscribeOn(c, 1, *doc, wire::REGION_CODEC_MESHOPT, RegionCodec::kMeshopt);
  CodecViewer draco = subscribeOn(c, 1, *doc, wire::REGION_CODEC_DRACO, RegionCodec::kDraco);
  ASSERT_TRUE(meshopt.session && draco.session);
  for (int node = 0; node < 2; ++node) {
    auto admin = Session::connect(c.session(node, "admin", c.nodes[static_cast<size_t>(node)]->adminToken()));
    ASSERT_TRUE(admin.isOk());
    ASSERT_EQ(testing::serverStat(**admin, "documents_owned"), node == 0 ? 1 : 0) << c.nodeName(node);
  }

  ASSERT_TRUE(readUntil(meshopt, 1, 20)) << "no meshopt snapshot through node 1";
  ASSERT_TRUE(readUntil(draco, 1, 20)) << "no Draco snapshot through node 1";
  EXPECT_GT(meshopt.snapshotRegions, 0u);
  EXPECT_EQ(meshopt.snapshotRegions, draco.snapshotRegions);
  EXPECT_EQ(meshopt.snapshotOther, 0u) << "regions of another codec in the meshopt subscriber's snapshot";
  EXPECT_EQ(draco.snapshotOther, 0u) << "regions of another codec in the Draco subscriber's snapshot";
  const uint64_t before = draco.view->surfaceHash();
  EXPECT_EQ(meshopt.view->surfaceHash(), before);

  // An edit by the other client, on the owner: a delta to both.
  std::mt19937 rng(5);
  auto ack = (*editor)->call(testing::smallMove(*doc, rng, 0.02), 30);
  ASSERT_TRUE(ack.isOk() && ack->has_ack()) << (ack.isOk() ? ack->DebugString() : ack.status().message());
  const uint64_t version = ack->ack().version();
  ASSERT_TRUE(readUntil(meshopt, version, 20)) << "the edit never reached the meshopt subscriber";
  ASSERT_TRUE(readUntil(draco, version, 20)) << "the edit never reached the Draco subscriber";
  EXPECT_GT(meshopt.deltaRegions, 0u) << "the edit's delta brought no region";
  EXPECT_EQ(meshopt.deltaRegions, draco.deltaRegions);
  EXPECT_EQ(meshopt.deltaOther, 0u) << "regions of another codec in the meshopt subscriber's delta";
  EXPECT_EQ(draco.deltaOther, 0u) << "regions of another codec in the Draco subscriber's delta";

  // The decoded surfaces agree with each other, with the server's announced
  // hash and with the journal in JetStream replayed here (PROTOCOL 6.5).
  auto journal = testing::journalState(c.nats, *doc);
  ASSERT_TRUE(journal.isOk()) << journal.status().message();
  EXPECT_EQ(journal->version, version);
  EXPECT_NE(draco.view->surfaceHash(), before);
  EXPECT_EQ(meshopt.view->surfaceHash(), draco.view->surfaceHash());
  EXPECT_EQ(meshopt.view->surfaceHash(), journal->surfaceHash);
  EXPECT_TRUE(meshopt.view->verifySurface().isOk()) << meshopt.view->verifySurface().message();
  EXPECT_TRUE(draco.view->verifySurface().isOk()) << draco.view->verifySurface().message();
  std::printf(
      "node 1, document owned by node 0, codec meshopt: %zu regions in the snapshot, %zu in the "
      "delta, %zu not meshopt; surface hash %016llx for both codecs\n",
      meshopt.snapshotRegions, meshopt.deltaRegions, meshopt.snapshotOther + meshopt.deltaOther,
      static_cast<unsigned long long>(meshopt.view->surfaceHash()));
}

}  // namespace
}  // namespace tessera
