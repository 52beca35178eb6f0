// Document leases (server/cluster/document_leases.h) against a real
// nats-server: one owner at a time, and a lease held under a node's own
// name by a process before it (a restart under the same name, or a lease
// that expired while NATS had no quorum and that a replica still shows) is
// never an owner that node forwards to.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "cluster/nats_cluster.h"
#include "server/cluster/document_leases.h"

namespace tessera {
namespace {

using cluster::DocumentLeases;
using cluster::NatsLink;
using testing::NatsCluster;
using namespace std::chrono_literals;

std::unique_ptr<NatsLink> linkTo(const NatsCluster& nats) {
  auto link = nats.connect();
  if (!link.isOk()) {
    ADD_FAILURE() << link.status().toString();
    return nullptr;
  }
  return std::move(link).value();
}

std::unique_ptr<DocumentLeases> leasesOf(NatsLink& link, const std::string& node) {
  auto leases = DocumentLeases::open(link, node, 1000ms, 1);
  if (!leases.isOk()) {
    ADD_FAILURE() << leases.status().toString();
    return nullptr;
  }
  return std::move(leases).value();
}

TEST(DocumentLeases, OneOwnerAtATimeAndNeverItselfUnderALeaseFromBefore) {
  auto nats = NatsCluster::start(1);
  ASSERT_TRUE(nats.isOk()) << nats.status().toString();
  auto linkA = linkTo(*nats), linkB = linkTo(*nats), linkRestarted = linkTo(*nats);
  ASSERT_TRUE(linkA && linkB && linkRestarted);
  auto a = leasesOf(*linkA, "node0"), b = leasesOf(*linkB, "node1");
  ASSERT_TRUE(a && b);
  const store::DocumentId doc{1};

  auto taken = a->acquire(doc);
  ASSERT_TRUE(taken.isOk()) << taken.status().toString();
  EXPECT_TRUE(*taken);
  std::string owner;
  auto other = b->acquire(doc, &owner);
  ASSERT_TRUE(other.isOk()) << other.status().toString();
  EXPECT_FALSE(*other);
  EXPECT_EQ(owner, "node0");

  // node0 again, as a new process (its first one stopped renewing): the
  // lease under its name is not its own, and not an owner to forward to.
  auto restarted = leasesOf(*linkRestarted, "node0");
  ASSERT_TRUE(restarted);
  owner.clear();
  auto again = restarted->acquire(doc, &owner);
  ASSERT_FALSE(again.isOk()) << "acquire answered " << *again << " with owner '" << owner << "'";
  EXPECT_EQ(again.status().code(), ErrorCode::kIoError);
  EXPECT_NE(again.status().message().find("held under this node's name (node0)"), std::string::npos)
      << again.status().message();
  EXPECT_TRUE(owner.empty()) << owner;

  // Once the old lease expires (nobody renews it), the new process takes it.
  bool mine = false;
  for (int i = 0; i < 50 && !mine; ++i) {
    std::this_thread::sleep_for(100ms);
    auto retried = restarted->acquire(doc);
    mine = retried.isOk() && *retried;
  }
  EXPECT_TRUE(mine) << "the lease under node0's name did not expire within 5 s";
}

// NATS loses its majority while the bucket's leader survives: that leader
// still expires the key (max age) and then refuses the renewal outright
// ("wrong last sequence: 0"), which alone reads like another writer. Every
// failed renewal must say what is wrong: the quorum. (The cluster quorum
// test got such a notice and no word of the quorum, in CI.)
TEST(DocumentLeases, ALeaseLostWhileNatsHasNoMajorityNamesTheMajority) {
  auto nats = NatsCluster::start(3);
  ASSERT_TRUE(nats.isOk()) << nats.status().toString();
  auto link = linkTo(*nats);
  ASSERT_TRUE(link);
  auto opened = DocumentLeases::open(*link, "node0", 1000ms, 3);
  ASSERT_TRUE(opened.isOk()) << opened.status().toString();
  DocumentLeases& leases = **opened;
  const store::DocumentId doc{1};
  auto taken = leases.acquire(doc);
  ASSERT_TRUE(taken.isOk() && *taken) << (taken.isOk() ? "taken by another node" : taken.status().toString());
  auto leader = nats->leaderOf(NatsLink::bucketStream(DocumentLeases::kBucket));
  ASSERT_TRUE(leader.isOk()) << leader.status().toString();
  for (int server = 0; server < 3; ++server) {
    if (server != *leader) nats->kill9(server);
  }

  std::vector<std::string> failures;
  bool lost = false;
  const auto deadline = std::chrono::steady_clock::now() + 30s;
  while (!lost && std::chrono::steady_clock::now() < deadline) {
    const Status renewed = leases.renew(doc);
    if (!renewed.isOk()) {
      failures.push_back(renewed.message());
      lost = renewed.code() == ErrorCode::kNotFound;
    }
    std::this_thread::sleep_for(250ms);
  }
  ASSERT_FALSE(failures.empty()) << "renewals went on without a majority of the NATS servers";
  for (const std::string& failure : failures) {
    std::printf("renewal without a majority: %s\n", failure.c_str());
    EXPECT_NE(failure.find("majority of the NATS servers"), std::string::npos) << failure;
  }
  EXPECT_EQ(leases.holds(doc), !lost);
}

}  // namespace
}  // namespace tessera
