// Abuse by unauthenticated and authenticated peers (docs/PROTOCOL.md §1.1, §9), against
// the real server, each case with a bystander on another address and
// document whose edits must keep arriving promptly (bystander.h).
#include <gtest/gtest.h>

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/write.hpp>
#include <chrono>
#include <future>
#include <thread>

#include "client/lib/session.h"
#include "core/hierarchy/ids.h"
#include "integration/bystanded_server.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

namespace asio = boost::asio;
using client::Session;
using testing::BystandedServer;
using testing::Bystander;
using testing::expectServed;
using testing::ServerProcess;
using testing::startBystanded;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

std::string serverLog(const std::string& dataDirectory) {
  return testing::fileBytes(dataDirectory + ".log");
}

Expected<std::unique_ptr<Session>> connectFrom(const ServerProcess& server, const std::string& address,
                                               const std::string& token) {
  auto options = server.session("peer", token);
  options.localAddress = address;
  return Session::connect(options);
}

// Wrong tokens from one address are answered ever more slowly; the right
// token from another address is served at once; the log names the address
// and never the token.
TEST(ServerAbuse, FailedTokensSlowDownPerAddressOnly) {
  BystandedServer s;
  startBystanded(s, "tessera-abuse-auth",
                 {"--auth-failure-delay-ms", "200", "--auth-failure-max-delay-ms", "800"});
  if (::testing::Test::HasFatalFailure()) return;
  auto abuse = std::async(std::launch::async, [&] {
    const auto t0 = Clock::now();
    std::vector<std::string> errors;
    for (int i = 0; i < 6; ++i) {
      auto peer = connectFrom(*s.server, "127.0.0.1", "wrong-token-" + std::to_string(i) + "-0123456789");
      errors.push_back(peer.isOk() ? std::string("accepted") : peer.status().message());
    }
    return std::make_pair(secondsSince(t0), errors);
  });
  expectServed(*s.bystander, s.bystander->run(20), "during the token guessing");
  auto [seconds, errors] = abuse.get();
  for (const std::string& e : errors) EXPECT_NE(e.find("access token is not known"), std::string::npos) << e;
  // Attempts 2..6 wait 200, 400, 800, 800 and 800 ms.
  EXPECT_GE(seconds, 3.0) << "six wrong tokens were answered in " << seconds << " s";

  // Parallel attempts from the same address queue behind each other.
  const auto t0 = Clock::now();
  std::vector<std::future<bool>> parallel;
  for (int i = 0; i < 3; ++i) {
    parallel.push_back(std::async(std::launch::async, [&, i] {
      return !connectFrom(*s.server, "127.0.0.1", "parallel-wrong-" + std::to_string(i) + "-0123456789")
                  .isOk();
    }));
  }
  for (auto& p : parallel) EXPECT_TRUE(p.get());
  EXPECT_GE(secondsSince(t0), 1.6) << "three parallel guesses were not spaced";

  // Another address with the right token: at once.
  const auto t1 = Clock::now();
  auto rightful = connectFrom(*s.server, "127.0.0.2", s.server->adminToken());
  ASSERT_TRUE(rightful.isOk()) << rightful.status().message();
  EXPECT_LT(secondsSince(t1), 0.5);
  // Anonymous peers guess nothing and are not delayed.
  const auto t2 = Clock::now();
  EXPECT_TRUE(connectFrom(*s.server, "127.0.0.1", "").isOk());
  EXPECT_LT(secondsSince(t2), 0.5);

  const std::string log = serverLog(s.data);
  EXPECT_NE(log.find("auth_failed"), std::string::npos);
  EXPECT_NE(log.find("127.0.0.1"), std::string::npos);
  EXPECT_EQ(log.find("wrong-token-"), std::string::npos) << "a token reached the log";
  EXPECT_EQ(log.find("parallel-wrong-"), std::string::npos) << "a token reached the log";
  EXPECT_EQ(s.server->stop(), 0);
}

// Raw TCP peers that never authenticate: a small Hello limit, a deadline
// bytes do not extend, and their own connection limits.
TEST(ServerAbuse, UnauthenticatedPeersHoldNeitherMemoryNorSlots) {
  BystandedServer s;
  startBystanded(s, "tessera-abuse-preauth",
                 {"--handshake-timeout", "1.5", "--unauthenticated-per-address", "3",
                  "--unauthenticated-total", "5", "--hello-max-bytes", "4096"});
  if (::testing::Test::HasFatalFailure()) return;
  asio::io_context io;
  auto rawFrom = [&](const std::string& address) {
    auto socket = std::make_unique<asio::ip::tcp::socket>(io);
    boost::system::error_code ec;
    socket->open(asio::ip::tcp::v4(), ec);
    socket->bind({asio::ip::make_address(address), 0}, ec);
    socket->connect({asio::ip::make_address("127.0.0.1"), s.server->port()}, ec);
    EXPECT_FALSE(ec) << ec.message();
    return socket;
  };
  auto readAll = [](asio::ip::tcp::socket& socket) {
    std::string received;
    char buffer[512];
    boost::system::error_code ec;
    for (;;) {
      const size_t n = socket.read_some(asio::buffer(buffer), ec);
      if (ec) break;
      received.append(buffer, n);
    }
    return received;
  };

  // A Hello announcing more than the Hello limit is refused before any payload.
  {
    auto big = rawFrom("127.0.0.1");
    asio::write(*big, asio::buffer(std::string("\x00\x10\x00\x00", 4) + std::string(1000, 'x')));
    const std::string said = readAll(*big);
    EXPECT_NE(said.find("more than the limit of 4096 bytes for the first frame"), std::string::npos) << said;
  }

  // A byte every 0.3 s (a Hello announcing 256 bytes, then its payload)
  // does not extend the 1.5 s handshake deadline.
  auto trickle = std::async(std::launch::async, [&] {
    auto socket = rawFrom("127.0.0.3");
    const auto t0 = Clock::now();
    const std::string bytes = std::string("\x00\x00\x01\x00", 4) + std::string(256, 'x');
    boost::system::error_code ec;
    for (size_t i = 0; i < 20 && !ec; ++i) {
      asio::write(*socket, asio::buffer(bytes.data() + i, 1), ec);
      std::this_thread::sleep_for(std::chrono::milliseconds(300));
      socket->non_blocking(true);
      char probe[256];
      socket->read_some(asio::buffer(probe), ec);
      socket->non_blocking(false);
      if (ec == asio::error::would_block) ec = {};
      if (!ec) break;  // got something: the error
    }
    return secondsSince(t0);
  });

  // Three silent peers fill 127.0.0.1's unauthenticated slots; a fourth is
  // refused, while an authenticated client from there is still served.
  std::vector<std::unique_ptr<asio::ip::tcp::socket>> silent;
  for (int i = 0; i < 3; ++i) silent.push_back(rawFrom("127.0.0.1"));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  auto fourth = connectFrom(*s.server, "127.0.0.1", "");
  ASSERT_FALSE(fourth.isOk());
  EXPECT_NE(fourth.status().message().find("unauthenticated connections from 127.0.0.1"), std::string::npos)
      << fourth.status().message();
  // In all: 3 here + the trickler; one more from elsewhere reaches 5.
  silent.push_back(rawFrom("127.0.0.4"));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  auto sixth = connectFrom(*s.server, "127.0.0.5", "");
  ASSERT_FALSE(sixth.isOk());
  EXPECT_NE(sixth.status().message().find("unauthenticated connections in all"), std::string::npos)
      << sixth.status().message();
  expectServed(*s.bystander, s.bystander->run(20), "with the unauthenticated slots full");

  const double trickled = trickle.get();
  EXPECT_LT(trickled, 3.0) << "a trickling peer held its slot for " << trickled << " s";
  // The silent peers are closed at their deadline, freeing the slots.
  for (auto& socket : silent) EXPECT_NE(readAll(*socket).find("no Hello in time"), std::string::npos);
  EXPECT_TRUE(connectFrom(*s.server, "127.0.0.1", "").isOk());
  EXPECT_EQ(s.server->stop(), 0);
}

wire::ClientMessage profile(uint64_t doc, uint32_t base, uint32_t max, double angle) {
  return testing::subscribe(doc, base, max, angle);
}

// Distinct LOD profiles are capped per document and released with their
// last subscriber; subscriptions are capped per session; over-budget
// profiles and exports are refused from an estimate.
TEST(ServerAbuse, ProfilesAreCappedReleasedAndEstimated) {
  BystandedServer s;
  startBystanded(
      s, "tessera-abuse-profiles",
      {"--profiles-per-document", "2", "--subscriptions-per-session", "1", "--max-triangles", "20000"});
  if (::testing::Test::HasFatalFailure()) return;
  const std::string cube = testing::fileBytes(testing::sourceTestDataPath("cube.obj"));
  auto created = s.admin->call(testing::createDocument("target", cube, "", 5), 30);
  ASSERT_TRUE(created.isOk() && created->has_ack());
  const uint64_t doc = created->ack().document_id();
  auto created2 = s.admin->call(testing::createDocument("other", cube, "", 3), 30);
  ASSERT_TRUE(created2.isOk() && created2->has_ack());
  const uint64_t other = created2->ack().document_id();

  auto a = connectFrom(*s.server, "127.0.0.1", s.server->adminToken());
  auto b = connectFrom(*s.server, "127.0.0.1", s.server->adminToken());
  auto c = connectFrom(*s.server, "127.0.0.1", s.server->adminToken());
  ASSERT_TRUE(a.isOk() && b.isOk() && c.isOk());
  for (Session* x : {a->get(), b->get(), c->get()})
    ASSERT_TRUE(x->call(testing::openDocument(doc), 20)->has_ack());

  // One session churning through many profiles holds one view at a time:
  // each replaced profile is dropped, so the cap of 2 is never reached.
  for (int i = 0; i < 12; ++i) {
    auto r = (*a)->call(profile(doc, 1, 3, 5 + i), 30);
    ASSERT_TRUE(r.isOk() && r->has_ack())
        << "profile " << i << ": " << (r.isOk() ? r->DebugString() : r.status().message());
  }
  // Two distinct profiles held: a third is refused while they are watched,
  // and the refused session keeps the profile it had (c shares b's).
  ASSERT_TRUE((*b)->call(profile(doc, 1, 3, 40), 30)->has_ack());
  ASSERT_TRUE((*c)->call(profile(doc, 1, 3, 40), 30)->has_ack());
  auto third = (*c)->call(profile(doc, 1, 3, 50), 30);
  ASSERT_TRUE(third.isOk() && third->has_reject())
      << (third.isOk() ? third->DebugString() : third.status().message());
  EXPECT_EQ(third->reject().reason(), wire::REJECT_REASON_LIMIT_EXCEEDED);
  EXPECT_NE(third->reject().message().find("--profiles-per-document"), std::string::npos)
      << third->reject().message();
  ASSERT_TRUE(
      (*a)->call(testing::moveVertex(doc, VertexId(1, 3).packed(), 0.01, 0.0, 0.02, wire::MOVE_MODE_OFFSET),
                 30)
          ->has_ack());
  bool delta = false;
  for (auto until = Clock::now() + std::chrono::seconds(10); !delta && Clock::now() < until;) {
    auto m = (*c)->receive(1);
    delta = m.isOk() && m->has_delta() && m->delta().document_id() == doc;
  }
  EXPECT_TRUE(delta) << "the refused subscriber lost the profile it had";
  // b leaves: its profile goes with it, and c's is served.
  (*b)->close();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  auto again = (*c)->call(profile(doc, 1, 3, 50), 30);
  ASSERT_TRUE(again.isOk() && again->has_ack())
      << (again.isOk() ? again->DebugString() : again.status().message());

  // One subscription per session here: a second document is refused.
  ASSERT_TRUE((*c)->call(testing::openDocument(other), 20)->has_ack());
  auto second = (*c)->call(profile(other, 0, 2, 15), 30);
  ASSERT_TRUE(second.isOk() && second->has_reject());
  EXPECT_NE(second->reject().message().find("--subscriptions-per-session"), std::string::npos)
      << second->reject().message();

  // Estimates: base level 5 of the cube alone has 12 * 4^5 = 12,288
  // triangles, within 20,000; a budget of 10,000 is below it. Export at
  // level 5 (12,288) is allowed, at a level past it refused by count.
  wire::ClientMessage tight = profile(doc, 5, 5, 15);
  tight.mutable_subscribe()->mutable_profile()->set_triangle_budget(10000);
  auto refused = (*a)->call(tight, 30);
  ASSERT_TRUE(refused.isOk() && refused->has_reject());
  EXPECT_EQ(refused->reject().reason(), wire::REJECT_REASON_LIMIT_EXCEEDED);
  EXPECT_NE(
      refused->reject().message().find("base level 5 alone has 12288 triangles, above the budget of 10000"),
      std::string::npos)
      << refused->reject().message();
  wire::ClientMessage exportDeep;
  exportDeep.mutable_export_document()->set_document_id(doc);
  exportDeep.mutable_export_document()->set_level(7);
  auto deep = (*a)->call(exportDeep, 30);
  ASSERT_TRUE(deep.isOk() && deep->has_reject());
  EXPECT_EQ(deep->reject().reason(), wire::REJECT_REASON_LIMIT_EXCEEDED);
  EXPECT_NE(deep->reject().message().find("export: level 7 has 196608 triangles, above the limit of 20000"),
            std::string::npos)
      << deep->reject().message();
  expectServed(*s.bystander, s.bystander->run(20), "after the profile churn");
  EXPECT_EQ(s.server->stop(), 0);
}

// Selections are checked, and presence carries changes only: a large
// selection is sent once, not again with every later join and leave.
TEST(ServerAbuse, SelectionsAreCheckedAndPresenceSendsChanges) {
  BystandedServer s;
  startBystanded(s, "tessera-abuse-presence", {"--selection-max-ids", "600"});
  if (::testing::Test::HasFatalFailure()) return;
  const std::string cube = testing::fileBytes(testing::sourceTestDataPath("cube.obj"));
  auto created = s.admin->call(testing::createDocument("shared", cube, "", 5), 30);
  ASSERT_TRUE(created.isOk() && created->has_ack());
  const uint64_t doc = created->ack().document_id();
  auto selector = connectFrom(*s.server, "127.0.0.1", s.server->adminToken());
  auto watcher = connectFrom(*s.server, "127.0.0.1", s.server->adminToken());
  ASSERT_TRUE(selector.isOk() && watcher.isOk());
  ASSERT_TRUE((*selector)->call(testing::openDocument(doc), 20)->has_ack());
  ASSERT_TRUE((*watcher)->call(testing::openDocument(doc), 20)->has_ack());

  auto select = [&](const std::vector<uint64_t>& ids) {
    wire::ClientMessage m;
    m.mutable_select()->set_document_id(doc);
    for (uint64_t id : ids) m.mutable_select()->mutable_selection()->add_vertex_ids(id);
    return m;
  };
  // Unknown ids and too many ids: a Reject naming the problem.
  auto unknown = (*selector)->call(select({VertexId(1, 2).packed(), VertexId(2, 999999).packed()}), 20);
  ASSERT_TRUE(unknown.isOk() && unknown->has_reject())
      << (unknown.isOk() ? unknown->DebugString() : unknown.status().message());
  EXPECT_EQ(unknown->reject().reason(), wire::REJECT_REASON_NOT_FOUND);
  EXPECT_NE(unknown->reject().message().find("v2:999999"), std::string::npos) << unknown->reject().message();
  std::vector<uint64_t> many;
  for (uint64_t i = 0; i < 601; ++i) many.push_back(VertexId(4, i).packed());
  auto tooMany = (*selector)->call(select(many), 20);
  ASSERT_TRUE(tooMany.isOk() && tooMany->has_reject());
  EXPECT_NE(tooMany->reject().message().find("601 ids, above the limit of 600"), std::string::npos)
      << tooMany->reject().message();

  // A valid selection of 600 ids (about 4 KB on the wire).
  many.pop_back();
  ASSERT_TRUE((*selector)->send(select(many)).isOk());
  size_t selectionBytes = 0;
  for (int i = 0; i < 50 && selectionBytes == 0; ++i) {
    auto m = (*watcher)->receive(10);
    ASSERT_TRUE(m.isOk()) << m.status().message();
    if (!m->has_presence()) continue;
    for (const auto& p : m->presence().participants()) {
      if (p.selection().vertex_ids_size() == 600) selectionBytes = m->ByteSizeLong();
    }
  }
  ASSERT_GT(selectionBytes, 2000u);

  // Ten open/close cycles by another viewer: the watcher hears of each, but
  // the 600-id selection is not sent again.
  size_t cycleBytes = 0;
  for (int i = 0; i < 10; ++i) {
    auto visitor = connectFrom(*s.server, "127.0.0.1", s.server->adminToken());
    ASSERT_TRUE(visitor.isOk());
    ASSERT_TRUE((*visitor)->call(testing::openDocument(doc), 20)->has_ack());
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    (*visitor)->close();
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
  }
  int joins = 0, leaves = 0;
  for (;;) {
    auto m = (*watcher)->receive(0.5);
    if (!m.isOk()) break;
    if (!m->has_presence()) continue;
    cycleBytes += m->ByteSizeLong();
    EXPECT_FALSE(m->presence().full());
    joins += m->presence().participants_size();
    leaves += m->presence().left_session_ids_size();
  }
  // Every leave is told; a join is told unless its visitor left within the
  // same 100 ms broadcast window.
  EXPECT_EQ(leaves, 10);
  EXPECT_GE(joins, 1);
  EXPECT_LE(joins, 10);
  EXPECT_LT(cycleBytes, selectionBytes) << "the cycles resent the selection";
  expectServed(*s.bystander, s.bystander->run(20), "after the presence churn");
  EXPECT_EQ(s.server->stop(), 0);
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

// A mesh file whose bad line holds bytes that are not UTF-8: the importer's
// error quotes them, and the Reject carrying it must still parse (proto3
// strings are UTF-8), with the bytes written as \xNN. Before the fix the
// client could not parse the reply and lost its stream. Both ways a mesh
// reaches the importer: CreateDocument and AddMorphKey.
TEST(ServerAbuse, MeshErrorsQuotingBinaryBytesReachTheClient) {
  BystandedServer s;
  startBystanded(s, "tessera-abuse-utf8", {});
  if (::testing::Test::HasFatalFailure()) return;
  const std::string bad = std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nbogus\xFF\xFE line\n");
  auto refused = s.admin->call(testing::createDocument("binary", bad, "", 3), 30);
  ASSERT_TRUE(refused.isOk()) << "the reply did not parse: " << refused.status().message();
  ASSERT_TRUE(refused->has_reject()) << refused->DebugString();
  EXPECT_NE(refused->reject().message().find("\\xFF\\xFE"), std::string::npos) << refused->reject().message();

  auto created =
      s.admin->call(testing::createDocument("tri", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "", 3), 30);
  ASSERT_TRUE(created.isOk() && created->has_ack()) << created->DebugString();
  const uint64_t doc = created->ack().document_id();
  ASSERT_TRUE(s.admin->call(testing::openDocument(doc), 10).isOk());
  wire::ClientMessage add;
  add.mutable_add_morph_key()->set_document_id(doc);
  add.mutable_add_morph_key()->set_mesh(bad);
  add.mutable_add_morph_key()->set_mesh_format(wire::MESH_FORMAT_OBJ);
  auto keyRefused = s.admin->call(add, 30);
  ASSERT_TRUE(keyRefused.isOk()) << "the reply did not parse: " << keyRefused.status().message();
  ASSERT_TRUE(keyRefused->has_reject()) << keyRefused->DebugString();
  EXPECT_NE(keyRefused->reject().message().find("\\xFF\\xFE"), std::string::npos)
      << keyRefused->reject().message();
  // The session goes on, and so does the bystander.
  auto pong = s.admin->call(testing::ping(), 10);
  ASSERT_TRUE(pong.isOk() && pong->has_pong());
  expectServed(*s.bystander, s.bystander->run(10), "after the binary meshes");
}

}  // namespace
}  // namespace tessera
