// Operations (docs/OPERATIONS.md): the real tessera-server's HTTP endpoint
// read with an HTTP client of the tests' own (http_exchange.h), what it
// refuses and how it bounds its peers, the `health` command, its JSON log
// file and SIGHUP reopen, JSON start-up errors, `token new`, and an online
// backup restored into a new data directory and compared with the original.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <thread>
#include <vector>

#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include "client/lib/session.h"
#include "core/hierarchy/ids.h"
#include "integration/http_exchange.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using client::Session;
using testing::ServerProcess;

struct ProgramRun {
  int exitCode = -1;
  std::string out, err;
};

// Runs the real binary with `args` (no shell metacharacters in them).
ProgramRun runServerBinary(const std::string& args) {
  const std::string dir = testing::makeTempDir("tessera-ops-run");
  const std::string command =
      std::string(TESSERA_SERVER_PATH) + " " + args + " >" + dir + "/out 2>" + dir + "/err";
  const int status = std::system(command.c_str());
  ProgramRun run;
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = testing::fileBytes(dir + "/out");
  run.err = testing::fileBytes(dir + "/err");
  return run;
}

// Every line a JSON object with ts, level and event.
void expectJsonLines(const std::string& text, const std::string& what) {
  std::istringstream in(text);
  std::string line;
  int lines = 0;
  while (std::getline(in, line)) {
    ++lines;
    auto parsed = nlohmann::json::parse(line, nullptr, false);
    ASSERT_FALSE(parsed.is_discarded()) << what << ": not JSON: " << line;
    EXPECT_TRUE(parsed.is_object() && parsed.contains("ts") && parsed.contains("level") &&
                parsed.contains("event"))
        << what << ": " << line;
  }
  EXPECT_GT(lines, 0) << what << " is empty";
}

uint16_t readPortFile(const std::string& path) {
  for (int i = 0; i < 2000; ++i) {
    std::ifstream in(path);
    int port = 0;
    if (in >> port && port > 0) return static_cast<uint16_t>(port);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return 0;
}

// The HTTP port file is written before the server serves, and /healthz
// answers 503 until it does (docs/OPERATIONS.md "Health and metrics"): a
// loaded machine can take a moment. Waits for a 200, at most 10 s.
bool waitServing(uint16_t httpPort) {
  for (int i = 0; i < 100; ++i) {
    auto health = testing::httpGet(httpPort, "/healthz", 10);
    if (health.isOk() && health->status == 200) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return false;
}

// name{labels} value  ->  value, for one metric line of the text format.
std::map<std::string, double> parseMetrics(const std::string& body) {
  std::map<std::string, double> values;
  std::istringstream in(body);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto space = line.rfind(' ');
    values[line.substr(0, space)] = std::stod(line.substr(space + 1));
  }
  return values;
}

void openIn(Session& session, uint64_t doc) {
  auto opened = session.call(testing::openDocument(doc), 30);
  EXPECT_TRUE(opened.isOk() && !opened->has_reject())
      << (opened.isOk() ? opened->DebugString() : opened.status().message());
}

struct Cube {
  std::unique_ptr<Session> admin;
  uint64_t doc = 0;
};

Cube createCube(const ServerProcess& server, const std::string& name) {
  Cube c;
  auto admin = Session::connect(server.session("admin", server.adminToken()));
  EXPECT_TRUE(admin.isOk()) << admin.status().message();
  if (!admin.isOk()) return c;
  c.admin = std::move(*admin);
  auto created =
      c.admin->call(testing::createDocument(name, testing::fileBytes(testing::sourceTestDataPath("cube.obj")),
                                            testing::fileBytes(testing::sourceTestDataPath("cube.tags")), 4),
                    30);
  EXPECT_TRUE(created.isOk() && created->has_ack())
      << (created.isOk() ? created->DebugString() : created.status().message());
  if (created.isOk() && created->has_ack()) c.doc = created->ack().document_id();
  openIn(*c.admin, c.doc);
  return c;
}

void moveOnce(Session& session, uint64_t doc, int i) {
  auto acked =
      session.call(testing::moveVertex(doc, VertexId(2, static_cast<uint64_t>(i % 60)).packed(),
                                       0.001 * (i % 7), -0.002 * (i % 3), 0.0015, wire::MOVE_MODE_OFFSET),
                   20);
  ASSERT_TRUE(acked.isOk() && acked->has_ack())
      << (acked.isOk() ? acked->DebugString() : acked.status().message());
}

std::string exportGlb(Session& session, uint64_t doc) {
  wire::ClientMessage m;
  m.mutable_export_document()->set_document_id(doc);
  m.mutable_export_document()->set_level(3);
  m.mutable_export_document()->set_limit(true);
  auto reply = session.call(m, 30);
  EXPECT_TRUE(reply.isOk() && reply->has_export_result())
      << (reply.isOk() ? reply->DebugString() : reply.status().message());
  return reply.isOk() && reply->has_export_result() ? reply->export_result().glb() : std::string();
}

TEST(Operations, HealthAndPrometheusMetricsOverHttp) {
  const std::string dir = testing::makeTempDir("tessera-ops-http");
  auto server =
      ServerProcess::start(dir + "/data", {"--http-port", "0", "--http-port-file", dir + "/http-port"});
  ASSERT_TRUE(server.isOk()) << server.status().message();
  const uint16_t httpPort = readPortFile(dir + "/http-port");
  ASSERT_GT(httpPort, 0);
  ASSERT_TRUE(waitServing(httpPort)) << "the server did not start serving";
  auto get = [&](const std::string& target) { return testing::httpGet(httpPort, target, 10); };

  auto health = get("/healthz");
  ASSERT_TRUE(health.isOk()) << health.status().message();
  EXPECT_EQ(health->status, 200);
  auto healthJson = nlohmann::json::parse(health->body, nullptr, false);
  ASSERT_FALSE(healthJson.is_discarded()) << health->body;
  EXPECT_EQ(healthJson["status"], "ok");

  auto before = get("/metrics");
  ASSERT_TRUE(before.isOk()) << before.status().message();
  EXPECT_EQ(before->status, 200);
  EXPECT_NE(before->contentType.find("text/plain"), std::string::npos);
  const auto m0 = parseMetrics(before->body);
  EXPECT_EQ(m0.at("tessera_edits_total"), 0);
  // SQLite fsyncs each write before its acknowledgement, and says so.
  EXPECT_NE(before->body.find("tessera_store_durability_info{backend=\"sqlite\",engine_version=\""),
            std::string::npos)
      << before->body;
  EXPECT_NE(before->body.find("write_sync=\"each-write\"} 1"), std::string::npos) << before->body;

  Cube cube = createCube(*server, "metrics");
  ASSERT_NE(cube.doc, 0u);
  constexpr int kEdits = 12;
  for (int i = 0; i < kEdits; ++i) moveOnce(*cube.admin, cube.doc, i);

  auto after = get("/metrics");
  ASSERT_TRUE(after.isOk()) << after.status().message();
  const auto m = parseMetrics(after->body);
  EXPECT_EQ(m.at("tessera_edits_total"), kEdits);
  EXPECT_EQ(m.at("tessera_connections"), 1);  // the admin session
  EXPECT_GE(m.at("tessera_documents_open"), 1);
  EXPECT_GT(m.at("tessera_edits_per_second"), 0);
  // Every acked edit has an ack latency; every batch a commit time.
  EXPECT_EQ(m.at("tessera_edit_ack_seconds_count"), kEdits);
  EXPECT_GE(m.at("tessera_store_commit_seconds_count"), 1);
  EXPECT_GE(m.at("tessera_store_entries_committed_total"), kEdits);
  for (const char* h : {"tessera_edit_ack_seconds", "tessera_store_commit_seconds",
                        "tessera_tessellate_seconds", "tessera_region_encode_seconds"}) {
    // Buckets are cumulative, end at +Inf with the count, and the sum is a time.
    int buckets = 0;
    for (const auto& entry : m) buckets += entry.first.rfind(std::string(h) + "_bucket{", 0) == 0 ? 1 : 0;
    EXPECT_EQ(buckets, 18) << h;
    std::vector<double> cumulative;
    for (const char* le : {"5e-05", "0.0001", "0.00025", "0.0005", "0.001", "0.0025", "0.005", "0.01",
                           "0.025", "0.05", "0.1", "0.25", "0.5", "1", "2.5", "5", "10", "+Inf"}) {
      auto it = m.find(std::string(h) + "_bucket{le=\"" + le + "\"}");
      ASSERT_NE(it, m.end()) << h << " le=" << le << "\n" << after->body;
      cumulative.push_back(it->second);
    }
    for (size_t i = 1; i < cumulative.size(); ++i) EXPECT_LE(cumulative[i - 1], cumulative[i]) << h;
    EXPECT_EQ(cumulative.back(), m.at(std::string(h) + "_count")) << h;
    EXPECT_GE(m.at(std::string(h) + "_sum"), 0) << h;
  }

  // A refused command counts as a refusal.
  auto refused = cube.admin->call(testing::moveVertex(cube.doc, VertexId(9, 0).packed(), 0, 0, 0), 10);
  ASSERT_TRUE(refused.isOk() && refused->has_reject()) << (refused.isOk() ? refused->DebugString() : "");
  auto refusals = get("/metrics");
  ASSERT_TRUE(refusals.isOk()) << refusals.status().message();
  EXPECT_EQ(parseMetrics(refusals->body).at("tessera_refusals_total"), m.at("tessera_refusals_total") + 1);

  auto missing = get("/admin");
  ASSERT_TRUE(missing.isOk()) << missing.status().message();
  EXPECT_EQ(missing->status, 404);
  // Loopback by default, and said so in the log.
  EXPECT_NE(
      testing::fileBytes(dir + "/data.log").find("\"event\":\"http_listening\",\"address\":\"127.0.0.1\""),
      std::string::npos);

  EXPECT_EQ(server->stop(), 0);
  auto gone = get("/healthz");
  EXPECT_FALSE(gone.isOk()) << "the endpoint still answers after the server stopped";
}

// What the endpoint refuses (docs/OPERATIONS.md, "Health and metrics"):
// methods but GET and HEAD, paths but its two, requests larger than 8 KiB
// of headers or with a body, and garbage; each refusal closes the
// connection, and the endpoint goes on serving.
TEST(Operations, HttpEndpointAnswersSmallGetsOnly) {
  const std::string dir = testing::makeTempDir("tessera-ops-http-edges");
  auto server =
      ServerProcess::start(dir + "/data", {"--http-port", "0", "--http-port-file", dir + "/http-port"});
  ASSERT_TRUE(server.isOk()) << server.status().message();
  const uint16_t httpPort = readPortFile(dir + "/http-port");
  ASSERT_GT(httpPort, 0);
  ASSERT_TRUE(waitServing(httpPort)) << "the server did not start serving";
  using testing::httpExchange;
  using testing::httpStatus;

  for (const std::string method : {"POST", "PUT", "DELETE"}) {
    const std::string answer = httpExchange(
        httpPort, method + " /healthz HTTP/1.1\r\nHost: x\r\nContent-Length: 0\r\nConnection: close\r\n\r\n");
    EXPECT_EQ(httpStatus(answer), 405) << method << ": " << answer;
    EXPECT_NE(answer.find("Allow: GET, HEAD"), std::string::npos) << answer;
  }
  auto unknown = testing::httpGet(httpPort, "/nope");
  ASSERT_TRUE(unknown.isOk()) << unknown.status().message();
  EXPECT_EQ(unknown->status, 404);
  EXPECT_NE(unknown->body.find("/healthz"), std::string::npos) << unknown->body;
  // The query is not part of the path; HEAD has the headers only.
  auto query = testing::httpGet(httpPort, "/healthz?from=probe");
  ASSERT_TRUE(query.isOk()) << query.status().message();
  EXPECT_EQ(query->status, 200);
  const std::string head =
      httpExchange(httpPort, "HEAD /healthz HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n");
  EXPECT_EQ(httpStatus(head), 200) << head;
  EXPECT_TRUE(head.ends_with("\r\n\r\n")) << "HEAD sent a body: " << head;
  // Two requests on one kept-alive connection, sent at once: two answers.
  const std::string two = httpExchange(httpPort,
                                       "GET /healthz HTTP/1.1\r\nHost: x\r\n\r\n"
                                       "GET /metrics HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n");
  EXPECT_EQ(httpStatus(two), 200) << two.substr(0, 300);
  EXPECT_NE(two.find("HTTP/1.1 200", 1), std::string::npos) << "no second answer: " << two.substr(0, 300);
  EXPECT_NE(two.find("tessera_edits_total"), std::string::npos);

  struct Refused {
    std::string what, request;
    int status;
  };
  for (const Refused& refused : std::vector<Refused>{
           {"headers over 8 KiB",
            "GET /healthz HTTP/1.1\r\nHost: x\r\nX-Padding: " + std::string(64 * 1024, 'a') + "\r\n\r\n",
            431},
           {"a body", "GET /healthz HTTP/1.1\r\nHost: x\r\nContent-Length: 5\r\n\r\nhello", 413},
           {"a chunked body",
            "GET /healthz HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: chunked\r\n\r\n5\r\nhello\r\n0\r\n\r\n",
            413},
           {"garbage", "NONSENSE\r\n\r\n", 400}}) {
    // No "Connection: close" in these requests: the endpoint closes by itself.
    const std::string answer = httpExchange(httpPort, refused.request);
    EXPECT_EQ(httpStatus(answer), refused.status) << refused.what << ": " << answer.substr(0, 300);
    EXPECT_NE(answer.find("Connection: close"), std::string::npos)
        << refused.what << ": " << answer.substr(0, 300);
  }

  auto health = testing::httpGet(httpPort, "/healthz");
  ASSERT_TRUE(health.isOk()) << health.status().message();
  EXPECT_EQ(health->status, 200) << "after the refusals";
}

// Peers that send half a request and wait hold nothing but their own
// connection: a probe on another is answered at once, and the endpoint
// closes each of them when its 5 s are up (docs/OPERATIONS.md, "Health and
// metrics").
TEST(Operations, SlowHttpClientsDoNotHoldTheEndpoint) {
  const std::string dir = testing::makeTempDir("tessera-ops-http-slow");
  auto server =
      ServerProcess::start(dir + "/data", {"--http-port", "0", "--http-port-file", dir + "/http-port"});
  ASSERT_TRUE(server.isOk()) << server.status().message();
  const uint16_t httpPort = readPortFile(dir + "/http-port");
  ASSERT_GT(httpPort, 0);
  ASSERT_TRUE(waitServing(httpPort)) << "the server did not start serving";

  namespace asio = boost::asio;
  constexpr int kSlow = 6;  // more than the endpoint's two threads, fewer than its 32 connections
  asio::io_context io;
  std::vector<asio::ip::tcp::socket> slow;
  for (int i = 0; i < kSlow; ++i) {
    slow.emplace_back(io);
    boost::system::error_code ec;
    slow.back().connect({asio::ip::make_address("127.0.0.1"), httpPort}, ec);
    ASSERT_FALSE(ec) << ec.message();
    // A request line and one header, but never the blank line that ends them.
    asio::write(slow.back(), asio::buffer(std::string("GET /healthz HTTP/1.1\r\nHost: x\r\n")), ec);
    ASSERT_FALSE(ec) << ec.message();
  }

  auto health = testing::httpGet(httpPort, "/healthz", 10);
  ASSERT_TRUE(health.isOk()) << health.status().message();
  EXPECT_EQ(health->status, 200);
  // Answered while the slow ones were still waiting (a probe takes
  // milliseconds, their time runs for 5 s): nothing was sent to them yet and
  // they are open.
  for (auto& socket : slow) {
    char byte = 0;
    const ssize_t n = ::recv(socket.native_handle(), &byte, 1, MSG_PEEK | MSG_DONTWAIT);
    EXPECT_TRUE(n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK))
        << "a slow connection was answered or closed before the probe was: recv " << n;
  }

  // Each is closed by the endpoint without an answer; 30 s bounds the wait.
  for (auto& socket : slow) {
    testing::setReceiveTimeout(socket, 30);
    char buffer[256];
    boost::system::error_code ec;
    const size_t n = socket.read_some(asio::buffer(buffer), ec);
    EXPECT_TRUE(ec == asio::error::eof || ec == asio::error::connection_reset)
        << "a slow connection is still open after 30 s: " << ec.message() << ", " << std::string(buffer, n);
  }
  auto again = testing::httpGet(httpPort, "/healthz", 10);
  ASSERT_TRUE(again.isOk()) << again.status().message();
  EXPECT_EQ(again->status, 200);
}

// At most 32 connections at once: one more gets a 503 naming the limit,
// and the endpoint serves again once they are gone.
TEST(Operations, HttpConnectionsAreBounded) {
  const std::string dir = testing::makeTempDir("tessera-ops-http-bound");
  auto server =
      ServerProcess::start(dir + "/data", {"--http-port", "0", "--http-port-file", dir + "/http-port"});
  ASSERT_TRUE(server.isOk()) << server.status().message();
  const uint16_t httpPort = readPortFile(dir + "/http-port");
  ASSERT_GT(httpPort, 0);

  namespace asio = boost::asio;
  constexpr int kLimit = 32;
  asio::io_context io;
  std::vector<asio::ip::tcp::socket> idle;
  for (int i = 0; i < kLimit; ++i) {
    idle.emplace_back(io);
    boost::system::error_code ec;
    idle.back().connect({asio::ip::make_address("127.0.0.1"), httpPort}, ec);
    ASSERT_FALSE(ec) << ec.message();
  }
  // Accepted after the others (the listen queue is first in, first out).
  const std::string over = testing::httpExchange(httpPort, "GET /healthz HTTP/1.1\r\nHost: x\r\n\r\n");
  EXPECT_EQ(testing::httpStatus(over), 503) << over;
  EXPECT_NE(over.find("more than 32 connections"), std::string::npos) << over;
  EXPECT_NE(testing::fileBytes(dir + "/data.log").find("\"event\":\"connection_refused\""),
            std::string::npos);

  for (auto& socket : idle) socket.close();
  // The endpoint frees their places as it sees them close: within 10 s.
  int status = 0;
  for (int i = 0; i < 100 && status != 200; ++i) {
    auto health = testing::httpGet(httpPort, "/healthz", 10);
    status = health.isOk() ? health->status : 0;
    if (status != 200) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  EXPECT_EQ(status, 200) << "the endpoint still refuses after its connections closed";
}

// `tessera-server health` (docs/OPERATIONS.md, "Health and metrics"): exit
// 0 and the JSON on stdout when healthy; exit 1 with a JSON error naming the
// URL when nothing answers, whether nothing listens or a peer takes the
// connection and never answers.
TEST(Operations, HealthCommandAsksTheEndpoint) {
  const std::string dir = testing::makeTempDir("tessera-ops-health");
  auto server =
      ServerProcess::start(dir + "/data", {"--http-port", "0", "--http-port-file", dir + "/http-port"});
  ASSERT_TRUE(server.isOk()) << server.status().message();
  const uint16_t httpPort = readPortFile(dir + "/http-port");
  ASSERT_GT(httpPort, 0);
  ASSERT_TRUE(waitServing(httpPort)) << "the server did not start serving";

  const std::string url = "http://127.0.0.1:" + std::to_string(httpPort) + "/healthz";
  ProgramRun healthy = runServerBinary("health --url " + url);
  EXPECT_EQ(healthy.exitCode, 0) << healthy.err;
  auto json = nlohmann::json::parse(healthy.out, nullptr, false);
  ASSERT_FALSE(json.is_discarded()) << healthy.out;
  EXPECT_EQ(json["status"], "ok");
  // The URL from --http-port (and --http-listen's default, loopback).
  ProgramRun fromPort = runServerBinary("--http-port " + std::to_string(httpPort) + " health");
  EXPECT_EQ(fromPort.exitCode, 0) << fromPort.err;
  EXPECT_NE(fromPort.out.find("\"status\":\"ok\""), std::string::npos) << fromPort.out;

  ProgramRun refused = runServerBinary("health --url http://127.0.0.1:1/healthz");
  EXPECT_EQ(refused.exitCode, 1);
  expectJsonLines(refused.err, "health against a closed port");
  EXPECT_NE(refused.err.find("http://127.0.0.1:1/healthz"), std::string::npos) << refused.err;

  // A port whose connections are never accepted, let alone answered.
  namespace asio = boost::asio;
  asio::io_context io;
  asio::ip::tcp::acceptor silent(io, {asio::ip::make_address("127.0.0.1"), 0});
  const std::string silentUrl =
      "http://127.0.0.1:" + std::to_string(silent.local_endpoint().port()) + "/healthz";
  ProgramRun mute = runServerBinary("health --url " + silentUrl);
  EXPECT_EQ(mute.exitCode, 1);
  expectJsonLines(mute.err, "health against a silent port");
  EXPECT_NE(mute.err.find(silentUrl), std::string::npos) << mute.err;
  EXPECT_NE(mute.err.find("no answer within"), std::string::npos) << mute.err;

  ProgramRun notHttp = runServerBinary("health --url ftp://127.0.0.1/healthz");
  EXPECT_EQ(notHttp.exitCode, 1);
  EXPECT_NE(notHttp.err.find("--url"), std::string::npos) << notHttp.err;
  EXPECT_NE(notHttp.err.find("ftp://127.0.0.1/healthz"), std::string::npos) << notHttp.err;
}

TEST(Operations, NoHttpEndpointUnlessAsked) {
  const std::string dir = testing::makeTempDir("tessera-ops-nohttp");
  auto server = ServerProcess::start(dir + "/data");
  ASSERT_TRUE(server.isOk()) << server.status().message();
  EXPECT_EQ(testing::fileBytes(dir + "/data.log").find("http_listening"), std::string::npos);
}

TEST(Operations, LogFileIsJsonAndReopensOnSighup) {
  const std::string dir = testing::makeTempDir("tessera-ops-log");
  const std::string log = dir + "/server.json";
  auto server = ServerProcess::start(dir + "/data", {"--log-file", log});
  ASSERT_TRUE(server.isOk()) << server.status().message();
  Cube cube = createCube(*server, "logged");
  ASSERT_NE(cube.doc, 0u);
  // logrotate's way: move the file, then SIGHUP.
  std::filesystem::rename(log, log + ".1");
  ASSERT_EQ(::kill(server->pid(), SIGHUP), 0);
  for (int i = 0; i < 500 && !std::filesystem::exists(log); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_TRUE(std::filesystem::exists(log)) << "no new log file after SIGHUP";
  moveOnce(*cube.admin, cube.doc, 1);
  cube.admin.reset();
  EXPECT_EQ(server->stop(), 0);

  const std::string rotated = testing::fileBytes(log + ".1"), fresh = testing::fileBytes(log);
  expectJsonLines(rotated, "the rotated log");
  expectJsonLines(fresh, "the reopened log");
  EXPECT_NE(rotated.find("\"event\":\"listening\""), std::string::npos);
  EXPECT_NE(fresh.find("\"event\":\"log_reopened\""), std::string::npos);
  EXPECT_NE(fresh.find("\"event\":\"stopped\""), std::string::npos) << "later lines went elsewhere";
  EXPECT_EQ(fresh.find("\"event\":\"listening\""), std::string::npos);
  // Nothing but the process's own start-up notes reaches stderr.
  EXPECT_EQ(testing::fileBytes(dir + "/data.log").find("\"event\":\"stopped\""), std::string::npos);
}

TEST(Operations, StartupAndUsageErrorsAreJsonNamingTheCause) {
  const std::string dir = testing::makeTempDir("tessera-ops-startup");
  ProgramRun badPort = runServerBinary("--port=abc");
  EXPECT_EQ(badPort.exitCode, 2);
  expectJsonLines(badPort.err, "usage error");
  EXPECT_NE(badPort.err.find("--port"), std::string::npos) << badPort.err;

  std::ofstream(dir + "/bad.conf") << "port = 0\nmax-levle = 3\n";
  ProgramRun badConfig = runServerBinary("--config " + dir + "/bad.conf");
  EXPECT_EQ(badConfig.exitCode, 2);
  expectJsonLines(badConfig.err, "config error");
  EXPECT_NE(badConfig.err.find("max-levle"), std::string::npos) << badConfig.err;
  EXPECT_NE(badConfig.err.find(dir + "/bad.conf"), std::string::npos) << badConfig.err;

  auto server = ServerProcess::start(dir + "/data");
  ASSERT_TRUE(server.isOk()) << server.status().message();
  ProgramRun second = runServerBinary("--data " + dir + "/data --port 0");
  EXPECT_EQ(second.exitCode, 1);
  expectJsonLines(second.err, "start-up failure");
  EXPECT_NE(second.err.find("startup_failed"), std::string::npos) << second.err;
  EXPECT_NE(second.err.find("in use"), std::string::npos) << second.err;

  ProgramRun version = runServerBinary("--version");
  EXPECT_EQ(version.exitCode, 0);
  EXPECT_EQ(version.out, "tessera-server 0.1.0\n");
  ProgramRun help = runServerBinary("backup --help");
  EXPECT_EQ(help.exitCode, 0);
  EXPECT_NE(help.out.find("--to"), std::string::npos) << help.out;
  EXPECT_EQ(help.out.find("--max-level"), std::string::npos) << "backup's help lists the serving options:\n"
                                                             << help.out;
}

TEST(Operations, ConfigFileSetsOptionsAndTheCommandLineWins) {
  const std::string dir = testing::makeTempDir("tessera-ops-config");
  std::ofstream(dir + "/server.conf")
      << "# a comment\nhttp-port = 0\nhttp-port-file = \"" << dir << "/http-port\"\nmax-level = 1\n";
  auto server = ServerProcess::start(dir + "/data", {"--config", dir + "/server.conf", "--max-level", "2"});
  ASSERT_TRUE(server.isOk()) << server.status().message();
  EXPECT_GT(readPortFile(dir + "/http-port"), 0) << "the config file's http-port was not applied";
  auto admin = Session::connect(server->session("admin", server->adminToken()));
  ASSERT_TRUE(admin.isOk());
  const std::string cube = testing::fileBytes(testing::sourceTestDataPath("cube.obj"));
  auto two = (*admin)->call(testing::createDocument("two", cube, "", 2), 30);
  ASSERT_TRUE(two.isOk());
  EXPECT_TRUE(two->has_ack()) << "--max-level 2 on the command line must override the file's 1: "
                              << two->DebugString();
  auto three = (*admin)->call(testing::createDocument("three", cube, "", 3), 30);
  ASSERT_TRUE(three.isOk());
  EXPECT_TRUE(three->has_reject()) << three->DebugString();
}

TEST(Operations, TokenNewStoresAWorkingTokenWhileTheServerRuns) {
  const std::string dir = testing::makeTempDir("tessera-ops-token");
  auto server = ServerProcess::start(dir + "/data");
  ASSERT_TRUE(server.isOk()) << server.status().message();
  Cube cube = createCube(*server, "tokens");
  ASSERT_NE(cube.doc, 0u);

  ProgramRun viewer = runServerBinary("token new --role viewer --document " + std::to_string(cube.doc) +
                                      " --data " + dir + "/data");
  ASSERT_EQ(viewer.exitCode, 0) << viewer.err;
  const std::string token = viewer.out.substr(0, viewer.out.find('\n'));
  EXPECT_TRUE(std::regex_match(token, std::regex("[0-9a-f]{64}"))) << token;
  EXPECT_EQ(viewer.err.find(token), std::string::npos) << "the token was logged";
  ProgramRun another = runServerBinary("token new --data " + dir + "/data");
  ASSERT_EQ(another.exitCode, 0) << another.err;
  EXPECT_NE(another.out, viewer.out);

  auto session = Session::connect(server->session("viewer", token));
  ASSERT_TRUE(session.isOk()) << session.status().message();
  openIn(**session, cube.doc);
  auto subscribed = (*session)->call(testing::subscribe(cube.doc, 0, 2), 20);
  ASSERT_TRUE(subscribed.isOk() && subscribed->has_ack())
      << (subscribed.isOk() ? subscribed->DebugString() : "");
  auto snapshot = (*session)->receive(20);
  ASSERT_TRUE(snapshot.isOk()) << snapshot.status().message();
  EXPECT_TRUE(snapshot->has_snapshot()) << snapshot->DebugString();
  auto edit = (*session)->call(testing::moveVertex(cube.doc, VertexId(0, 0).packed(), 0, 0, 1), 20);
  ASSERT_TRUE(edit.isOk());
  EXPECT_TRUE(edit->has_reject()) << "a viewer token may not edit: " << edit->DebugString();

  ProgramRun unknownDocument = runServerBinary("token new --document 999 --data " + dir + "/data");
  EXPECT_NE(unknownDocument.exitCode, 0);
  EXPECT_NE(unknownDocument.err.find("999"), std::string::npos) << unknownDocument.err;
  ProgramRun badRole = runServerBinary("token new --role owner --data " + dir + "/data");
  EXPECT_EQ(badRole.exitCode, 2);
  EXPECT_NE(badRole.err.find("--role"), std::string::npos) << badRole.err;
}

// An online backup taken while another document is being edited, restored
// into a fresh data directory: the restored server serves the backed-up
// document exactly as it was (same version, same exported surface, byte for
// byte) and nothing the original did after the backup.
TEST(Operations, OnlineBackupRestoresTheDocumentsAsTheyWere) {
  const std::string dir = testing::makeTempDir("tessera-ops-backup");
  auto server = ServerProcess::start(dir + "/data", {"--commands-per-second", "100000"});
  ASSERT_TRUE(server.isOk()) << server.status().message();
  Cube kept = createCube(*server, "kept");
  Cube busy = createCube(*server, "busy");
  ASSERT_NE(kept.doc, 0u);
  ASSERT_NE(busy.doc, 0u);
  for (int i = 0; i < 20; ++i) moveOnce(*kept.admin, kept.doc, i);
  const std::string glbAtBackup = exportGlb(*kept.admin, kept.doc);
  ASSERT_FALSE(glbAtBackup.empty());

  // The busy document keeps being edited while the backup runs.
  std::atomic<bool> stop{false};
  std::atomic<int> busyEdits{0};
  std::thread editor([&] {
    for (int i = 0; i < 400 && !stop; ++i) {
      moveOnce(*busy.admin, busy.doc, i);
      ++busyEdits;
    }
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  ProgramRun backup = runServerBinary("backup --data " + dir + "/data --to " + dir + "/backup.db");
  stop = true;
  editor.join();
  ASSERT_EQ(backup.exitCode, 0) << backup.err;
  EXPECT_GT(busyEdits.load(), 0);
  ProgramRun again = runServerBinary("backup --data " + dir + "/data --to " + dir + "/backup.db");
  EXPECT_NE(again.exitCode, 0) << "a backup overwrote an existing file";

  // After the backup: more edits the restored store must not have.
  for (int i = 20; i < 25; ++i) moveOnce(*kept.admin, kept.doc, i);
  ProgramRun whileRunning = runServerBinary("restore --data " + dir + "/data --from " + dir + "/backup.db");
  EXPECT_EQ(whileRunning.exitCode, 1);
  EXPECT_NE(whileRunning.err.find("in use"), std::string::npos) << whileRunning.err;
  kept.admin.reset();
  busy.admin.reset();
  EXPECT_EQ(server->stop(), 0);

  std::ofstream(dir + "/junk.db") << "not a database at all, just text that is long enough to be a header...";
  ProgramRun junk = runServerBinary("restore --data " + dir + "/restored --from " + dir + "/junk.db");
  EXPECT_EQ(junk.exitCode, 1);
  EXPECT_NE(junk.err.find("junk.db"), std::string::npos) << junk.err;

  ProgramRun restore = runServerBinary("restore --data " + dir + "/restored --from " + dir + "/backup.db");
  ASSERT_EQ(restore.exitCode, 0) << restore.err;
  std::filesystem::copy_file(dir + "/data.admin", dir + "/restored.admin");
  auto restored = ServerProcess::start(dir + "/restored");
  ASSERT_TRUE(restored.isOk()) << restored.status().message();
  auto admin = Session::connect(restored->session("admin", restored->adminToken()));
  ASSERT_TRUE(admin.isOk()) << admin.status().message();
  wire::ClientMessage list;
  list.mutable_list_documents();
  auto documents = (*admin)->call(list, 20);
  ASSERT_TRUE(documents.isOk() && documents->has_document_list());
  std::map<uint64_t, uint64_t> versions;
  for (const auto& d : documents->document_list().documents()) versions[d.document_id()] = d.version();
  ASSERT_EQ(versions.size(), 2u);
  EXPECT_EQ(versions[kept.doc], 21u);  // creation is version 1, then the 20 edits before the backup
  EXPECT_LE(versions[busy.doc], static_cast<uint64_t>(busyEdits.load()));
  openIn(**admin, kept.doc);
  openIn(**admin, busy.doc);
  EXPECT_EQ(exportGlb(**admin, kept.doc), glbAtBackup) << "the restored document's surface differs";
  // The busy document opens and serves from whatever version it was at.
  EXPECT_FALSE(exportGlb(**admin, busy.doc).empty());
}

// The systemd notify protocol (Type=notify, WatchdogSec=): a datagram socket
// stands in for systemd, named by NOTIFY_SOCKET in the server's environment.
TEST(Operations, NotifiesSystemdReadyWatchdogAndStopping) {
  const std::string dir = testing::makeTempDir("tessera-ops-notify");
  const std::string socketPath = dir + "/notify.sock";
  const int fd = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  ASSERT_GE(fd, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  ASSERT_LT(socketPath.size(), sizeof(address.sun_path));
  std::strcpy(address.sun_path, socketPath.c_str());
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)), 0);
  timeval timeout{.tv_sec = 0, .tv_usec = 200'000};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof(timeout));

  ::setenv("NOTIFY_SOCKET", socketPath.c_str(), 1);
  ::setenv("WATCHDOG_USEC", "200000", 1);  // pings every 100 ms
  auto server = ServerProcess::start(dir + "/data");
  ::unsetenv("NOTIFY_SOCKET");
  ::unsetenv("WATCHDOG_USEC");
  ASSERT_TRUE(server.isOk()) << server.status().message();

  std::vector<std::string> messages;
  auto collect = [&](double seconds) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    char buffer[512];
    while (std::chrono::steady_clock::now() < until) {
      const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
      if (n > 0) messages.emplace_back(buffer, static_cast<size_t>(n));
    }
  };
  collect(1.5);
  ASSERT_FALSE(messages.empty()) << "nothing on NOTIFY_SOCKET";
  EXPECT_EQ(messages.front().rfind("READY=1", 0), 0u) << messages.front();
  const auto pings = std::count(messages.begin(), messages.end(), std::string("WATCHDOG=1"));
  EXPECT_GE(pings, 3) << "watchdog pings in 1.5 s with WATCHDOG_USEC=200000";
  messages.clear();
  std::thread stopper([&] { EXPECT_EQ(server->stop(), 0); });
  collect(1.5);
  stopper.join();
  EXPECT_NE(std::find(messages.begin(), messages.end(), std::string("STOPPING=1")), messages.end());
  ::close(fd);
}

}  // namespace
}  // namespace tessera
