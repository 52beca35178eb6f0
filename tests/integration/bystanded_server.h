// A real server with an admin session and a Bystander (bystander.h), as the
// abuse tests of the protocol port (abuse_test.cc) and of the web port
// (web_port_test.cc) start it, and the bound the bystander's latency must
// keep while peers misbehave (docs/PROTOCOL.md §1.1 and §9).
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "integration/bystander.h"

namespace tessera::testing {

// Far above a bystander's normal few milliseconds, far below the stalls of
// seconds the abuse caused before the server was hardened against it.
inline constexpr double kBystanderMedianMs = 150, kBystanderMaxMs = 1500;

// Every edit of `l` came back as a delta and was acknowledged, within the bound.
inline void expectServed(Bystander& bystander, const Expected<Bystander::Latencies>& l,
                         const std::string& during) {
  ASSERT_TRUE(l.isOk()) << during << ": " << l.status().message();
  Status acked = bystander.awaitAcks();
  EXPECT_TRUE(acked.isOk()) << during << ": " << acked.message();
  EXPECT_LT(l->median(), kBystanderMedianMs) << during;
  EXPECT_LT(l->max(), kBystanderMaxMs) << during;
}

struct BystandedServer {
  std::string data;  // the server's data directory
  std::optional<ServerProcess> server;
  std::unique_ptr<client::Session> admin;  // from 127.0.0.8
  std::unique_ptr<Bystander> bystander;    // from 127.0.0.9
};

// Starts the server with `args` in a new temporary directory named after
// `name`, connects the admin and the bystander, and checks that the
// bystander is served before any abuse. Fails the test (ASSERT) otherwise.
inline void startBystanded(BystandedServer& s, const std::string& name,
                           const std::vector<std::string>& args) {
  s.data = makeTempDir(name) + "/data";
  auto server = ServerProcess::start(s.data, args);
  ASSERT_TRUE(server.isOk()) << server.status().message();
  s.server.emplace(std::move(*server));
  auto options = s.server->session("admin", s.server->adminToken());
  options.localAddress = "127.0.0.8";
  auto admin = client::Session::connect(options);
  ASSERT_TRUE(admin.isOk()) << admin.status().message();
  s.admin = std::move(*admin);
  auto bystander = Bystander::start(*s.server, *s.admin);
  ASSERT_TRUE(bystander.isOk()) << bystander.status().message();
  s.bystander = std::move(*bystander);
  expectServed(*s.bystander, s.bystander->run(10), "before the abuse");
}

}  // namespace tessera::testing
