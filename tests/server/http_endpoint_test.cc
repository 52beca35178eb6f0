// The operations endpoint (server/ops/http_endpoint.h) in-process, over
// sources the test controls, read with the GET of the health command
// (server/ops/http_get.h); and that GET's errors, each naming its URL.
// The endpoint's refusals and bounds against the real binary are in
// tests/integration/operations_test.cc.
#include "server/ops/http_endpoint.h"

#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <chrono>
#include <mutex>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "server/ops/http_get.h"

namespace tessera::server {
namespace {

constexpr std::chrono::milliseconds kTimeout{10'000};

struct FakeServer {
  ServerStats stats;
  std::mutex mutex;
  std::optional<std::string> unhealthy;

  HttpSources sources() {
    return {&stats, [] { return store::StoreStats{}; }, [] { return int64_t{7}; },
            [this] {
              std::lock_guard lock(mutex);
              return unhealthy;
            }};
  }
  void setUnhealthy(std::optional<std::string> reason) {
    std::lock_guard lock(mutex);
    unhealthy = std::move(reason);
  }
};

std::string urlOf(uint16_t port, const std::string& path) {
  return "http://127.0.0.1:" + std::to_string(port) + path;
}

TEST(HttpEndpoint, ServesHealthAndMetricsUntilDestroyed) {
  FakeServer fake;
  auto endpoint = HttpEndpoint::start("127.0.0.1", 0, fake.sources());
  ASSERT_TRUE(endpoint.isOk()) << endpoint.status().message();
  const uint16_t port = (*endpoint)->port();
  ASSERT_GT(port, 0);

  auto healthy = httpGet(urlOf(port, "/healthz"), kTimeout);
  ASSERT_TRUE(healthy.isOk()) << healthy.status().message();
  EXPECT_EQ(healthy->status, 200);
  EXPECT_EQ(healthy->contentType, "application/json");
  auto json = nlohmann::json::parse(healthy->body, nullptr, false);
  ASSERT_FALSE(json.is_discarded()) << healthy->body;
  EXPECT_EQ(json["status"], "ok");
  EXPECT_TRUE(json["uptime_seconds"].is_number_integer()) << healthy->body;
  EXPECT_FALSE(json.contains("reason"));

  // The reason is the server's own text; whatever it holds, the JSON stays valid.
  fake.setUnhealthy("store: \"data.db\" unreadable\\\n");
  auto unhealthy = httpGet(urlOf(port, "/healthz"), kTimeout);
  ASSERT_TRUE(unhealthy.isOk()) << unhealthy.status().message();
  EXPECT_EQ(unhealthy->status, 503);
  json = nlohmann::json::parse(unhealthy->body, nullptr, false);
  ASSERT_FALSE(json.is_discarded()) << unhealthy->body;
  EXPECT_EQ(json["status"], "unavailable");
  EXPECT_EQ(json["reason"], "store:  data.db  unreadable  ");
  fake.setUnhealthy(std::nullopt);

  fake.stats.edits = 5;
  auto metrics = httpGet(urlOf(port, "/metrics"), kTimeout);
  ASSERT_TRUE(metrics.isOk()) << metrics.status().message();
  EXPECT_EQ(metrics->status, 200);
  EXPECT_EQ(metrics->contentType.rfind("text/plain", 0), 0u) << metrics->contentType;
  EXPECT_NE(metrics->body.find("\ntessera_documents_open 7\n"), std::string::npos) << metrics->body;
  EXPECT_NE(metrics->body.find("\ntessera_edits_total 5\n"), std::string::npos) << metrics->body;

  auto missing = httpGet(urlOf(port, "/metricz"), kTimeout);
  ASSERT_TRUE(missing.isOk()) << missing.status().message();
  EXPECT_EQ(missing->status, 404);

  endpoint->reset();  // stops and joins
  auto gone = httpGet(urlOf(port, "/healthz"), kTimeout);
  ASSERT_FALSE(gone.isOk()) << "answered after the endpoint was destroyed";
  EXPECT_EQ(gone.status().code(), ErrorCode::kIoError) << gone.status().message();
}

TEST(HttpEndpoint, ATakenPortFailsStartUpSayingSo) {
  FakeServer fake;
  auto first = HttpEndpoint::start("127.0.0.1", 0, fake.sources());
  ASSERT_TRUE(first.isOk()) << first.status().message();
  const std::string port = std::to_string((*first)->port());
  auto second = HttpEndpoint::start("127.0.0.1", (*first)->port(), fake.sources());
  ASSERT_FALSE(second.isOk()) << "two endpoints on port " << port;
  EXPECT_NE(second.status().message().find("--http-port"), std::string::npos) << second.status().message();
  EXPECT_NE(second.status().message().find("127.0.0.1:" + port), std::string::npos)
      << second.status().message();
  EXPECT_NE(second.status().message().find("in use"), std::string::npos) << second.status().message();
  // The first one still serves.
  auto healthy = httpGet(urlOf((*first)->port(), "/healthz"), kTimeout);
  ASSERT_TRUE(healthy.isOk()) << healthy.status().message();
  EXPECT_EQ(healthy->status, 200);
}

TEST(HttpGet, AMalformedUrlIsAnInvalidArgumentNamingIt) {
  for (const std::string url : {"ftp://127.0.0.1/healthz", "127.0.0.1:9478/healthz", "http://", "http://:80/",
                                "http://host:port/", "http://[::1/healthz", "https://127.0.0.1/healthz"}) {
    auto reply = httpGet(url, kTimeout);
    ASSERT_FALSE(reply.isOk()) << url;
    EXPECT_EQ(reply.status().code(), ErrorCode::kInvalidArgument) << url << ": " << reply.status().message();
    EXPECT_NE(reply.status().message().find(url), std::string::npos) << reply.status().message();
  }
}

TEST(HttpGet, NothingListeningIsAnIoErrorNamingTheUrl) {
  // A port just bound and released: nothing listens on it.
  boost::asio::io_context io;
  uint16_t port = 0;
  {
    boost::asio::ip::tcp::acceptor released(io, {boost::asio::ip::make_address("127.0.0.1"), 0});
    port = released.local_endpoint().port();
  }
  const std::string url = urlOf(port, "/healthz");
  auto reply = httpGet(url, kTimeout);
  ASSERT_FALSE(reply.isOk());
  EXPECT_EQ(reply.status().code(), ErrorCode::kIoError) << reply.status().message();
  EXPECT_NE(reply.status().message().find(url), std::string::npos) << reply.status().message();
}

TEST(HttpGet, APeerThatNeverAnswersIsATimeoutNamingTheUrl) {
  // Listening, so the kernel completes the connection, but never accepted.
  boost::asio::io_context io;
  boost::asio::ip::tcp::acceptor silent(io, {boost::asio::ip::make_address("127.0.0.1"), 0});
  const std::string url = urlOf(silent.local_endpoint().port(), "/healthz");
  const auto began = std::chrono::steady_clock::now();
  auto reply = httpGet(url, std::chrono::milliseconds(300));
  ASSERT_FALSE(reply.isOk());
  EXPECT_EQ(reply.status().code(), ErrorCode::kTimeout) << reply.status().message();
  EXPECT_NE(reply.status().message().find(url), std::string::npos) << reply.status().message();
  // Generous: the deadline holds, within a wide margin for a loaded machine.
  EXPECT_LT(std::chrono::steady_clock::now() - began, std::chrono::seconds(10));
}

}  // namespace
}  // namespace tessera::server
