// What a cluster node's acknowledgement survives, as the node reads it from
// the NATS servers (server/cluster/nats_server_info.h, docs/CLUSTER.md
// "What an acknowledged edit survives"): the INFO line parsed, the version
// rule, and against a real nats-server process: a node reports
// not-each-write in its stats and metrics, and --require-fsync refuses to
// start, naming the version and what to install.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "client/lib/session.h"
#include "cluster/nats_cluster.h"
#include "integration/http_exchange.h"
#include "integration/server_process.h"
#include "server/cluster/nats_server_info.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using cluster::parseNatsInfoLine;
using cluster::supportsPerWriteSync;

TEST(NatsDurability, TheInfoLineAndTheVersionRule) {
  auto info = parseNatsInfoLine(
      R"(INFO {"server_id":"X","version":"2.9.10","jetstream":true,"max_payload":1048576})");
  ASSERT_TRUE(info.isOk()) << info.status().message();
  EXPECT_EQ(info->version, "2.9.10");
  EXPECT_TRUE(info->jetstream);
  EXPECT_FALSE(parseNatsInfoLine("-ERR 'Authorization Violation'").isOk());
  EXPECT_FALSE(parseNatsInfoLine("INFO {not json").isOk());
  EXPECT_NE(parseNatsInfoLine(R"(INFO {"server_id":"X"})").status().message().find("no version"),
            std::string::npos);
  EXPECT_FALSE(supportsPerWriteSync("2.9.10"));
  EXPECT_FALSE(supportsPerWriteSync("2.9.99"));
  EXPECT_TRUE(supportsPerWriteSync("2.10.0"));
  EXPECT_TRUE(supportsPerWriteSync("2.12.1"));
  EXPECT_TRUE(supportsPerWriteSync("3.0.0"));
  EXPECT_FALSE(supportsPerWriteSync("v-two"));
  EXPECT_EQ(cluster::natsDurability({"2.9.10", true}).sync, store::WriteSync::kNotEachWrite);
  EXPECT_EQ(cluster::natsDurability({"2.10.4", true}).sync, store::WriteSync::kConfigured);
  EXPECT_NE(cluster::natsDurability({"2.9.10", true}).statement.find("power loss of a majority"),
            std::string::npos);
}

TEST(NatsDurability, ANodeSaysWhatItsAcknowledgementSurvivesAndRequireFsyncRefusesToStart) {
  // One NATS server is enough to read its version, and keeps this test
  // light beside the suite's three-server clusters.
  auto nats = testing::NatsCluster::start(1);
  ASSERT_TRUE(nats.isOk()) << nats.status().message();
  auto info = cluster::readNatsServerInfo(nats->url(0), std::chrono::milliseconds(5000));
  ASSERT_TRUE(info.isOk()) << info.status().message();
  std::printf("[ measured ] nats-server %s\n", info->version.c_str());
  const std::string dir = testing::makeTempDir("tessera-nats-durability");

  // --require-fsync on servers that cannot sync each write: the node exits
  // at once, and says why and what to install.
  const std::string refusedLog = dir + "/refused.log";
  const std::string command = std::string(TESSERA_SERVER_PATH) + " --port 0 --data " + dir +
                              "/refused --cluster " + nats->urls() +
                              " --cluster-replicas 1 --require-fsync > " + refusedLog + " 2>&1";
  const int status = std::system(command.c_str());
  EXPECT_NE(status, 0);
  std::ifstream in(refusedLog);
  const std::string said((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!supportsPerWriteSync(info->version)) {
    EXPECT_NE(said.find("--require-fsync: "), std::string::npos) << said;
    EXPECT_NE(said.find("nats-server " + info->version + " has no sync_interval"), std::string::npos) << said;
    EXPECT_NE(said.find("Install nats-server 2.10 or later"), std::string::npos) << said;
  }

  // Without it the node runs, and its stats and metrics carry the guarantee.
  auto node = testing::ServerProcess::start(
      dir + "/node", {"--cluster", nats->urls(), "--cluster-replicas", "1", "--node-name", "durability-node",
                      "--http-port", "0", "--http-port-file", dir + "/http-port"});
  ASSERT_TRUE(node.isOk()) << node.status().message();
  auto session = client::Session::connect(node->session("admin", node->adminToken()));
  ASSERT_TRUE(session.isOk()) << session.status().message();
  wire::ClientMessage ask;
  ask.mutable_stats();
  auto stats = (*session)->call(ask, 20);
  ASSERT_TRUE(stats.isOk() && stats->has_stats_reply());
  double syncs = -2;
  for (const auto& s : stats->stats_reply().stats())
    if (s.name() == "acknowledgement_syncs_each_write") syncs = s.value();
  EXPECT_EQ(syncs, supportsPerWriteSync(info->version) ? -1.0 : 0.0);
  std::ifstream portIn(dir + "/http-port");
  int httpPort = 0;
  portIn >> httpPort;
  auto metrics = testing::httpGet(static_cast<uint16_t>(httpPort), "/metrics", 10);
  ASSERT_TRUE(metrics.isOk()) << metrics.status().message();
  EXPECT_NE(
      metrics->body.find("tessera_store_durability_info{backend=\"nats\",engine_version=\"" + info->version +
                         "\",write_sync=\"" +
                         (supportsPerWriteSync(info->version) ? "configured" : "not-each-write") + "\"} 1"),
      std::string::npos)
      << metrics->body;
  (*session)->close();
  EXPECT_EQ(node->stop(), 0);
}

}  // namespace
}  // namespace tessera
