// Access and bad input against the real server (docs/PROTOCOL.md §1.1, §4.1): an
// unauthenticated or under-privileged client gets typed refusals, bad
// frames get a fatal error naming the problem, and none of it disturbs
// another client.
#include <gtest/gtest.h>

#include <boost/asio/ip/tcp.hpp>
#include <cmath>

#include "client/lib/session.h"
#include "core/hierarchy/ids.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using client::Session;
using testing::ServerProcess;

wire::RejectReason rejected(const Expected<wire::ServerMessage>& reply) {
  return reply.isOk() && reply->has_reject() ? reply->reject().reason() : wire::REJECT_REASON_UNSPECIFIED;
}

TEST(ServerSecurity, RefusesWhatARoleDoesNotAllowAndBadInput) {
  const std::string dir = testing::makeTempDir("tessera-server-security");
  auto server = ServerProcess::start(dir + "/data", {"--max-frame-bytes", "1048576", "--max-level", "5",
                                                     "--max-mesh-bytes", "4000", "--max-triangles", "5000"});
  ASSERT_TRUE(server.isOk()) << server.status().message();
  auto admin = Session::connect(server->session("admin", server->adminToken()));
  ASSERT_TRUE(admin.isOk());
  const std::string cube = testing::fileBytes(testing::sourceTestDataPath("cube.obj"));
  auto created = (*admin)->call(testing::createDocument("cube", cube, "", 4), 30);
  ASSERT_TRUE(created.isOk() && created->has_ack());
  const uint64_t doc = created->ack().document_id();
  ASSERT_TRUE(
      (*admin)->call(testing::grant(doc, wire::ROLE_VIEWER, "viewer-token-0123456789"), 10)->has_ack());

  // A bystander whose service must not suffer.
  auto bystander = Session::connect(server->session("bystander", "viewer-token-0123456789"));
  ASSERT_TRUE(bystander.isOk());
  ASSERT_TRUE((*bystander)->call(testing::openDocument(doc), 10)->has_ack());

  // Unauthenticated: may ping, nothing else.
  auto anonymous = Session::connect(server->session("anonymous", ""));
  ASSERT_TRUE(anonymous.isOk());
  EXPECT_TRUE((*anonymous)->call(testing::ping(), 10)->has_pong());
  wire::ClientMessage list;
  list.mutable_list_documents();
  EXPECT_EQ(rejected((*anonymous)->call(list, 10)), wire::REJECT_REASON_NOT_AUTHENTICATED);
  EXPECT_EQ(rejected((*anonymous)->call(testing::openDocument(doc), 10)),
            wire::REJECT_REASON_NOT_AUTHENTICATED);

  // A viewer may read but not edit, create or grant; an unknown token sees nothing.
  auto viewer = Session::connect(server->session("viewer", "viewer-token-0123456789"));
  ASSERT_TRUE(viewer.isOk());
  auto listed = (*viewer)->call(list, 10);
  ASSERT_TRUE(listed.isOk() && listed->has_document_list());
  EXPECT_EQ(listed->document_list().documents_size(), 1);
  ASSERT_TRUE((*viewer)->call(testing::openDocument(doc), 10)->has_ack());
  EXPECT_EQ(rejected((*viewer)->call(testing::moveVertex(doc, VertexId(1, 2).packed(), 0, 0, 1), 10)),
            wire::REJECT_REASON_PERMISSION_DENIED);
  EXPECT_EQ(rejected((*viewer)->call(testing::createDocument("x", cube, "", 3), 10)),
            wire::REJECT_REASON_PERMISSION_DENIED);
  EXPECT_EQ(rejected((*viewer)->call(testing::grant(doc, wire::ROLE_ADMIN, "stolen-token-0123456789"), 10)),
            wire::REJECT_REASON_PERMISSION_DENIED);
  // A token no grant names fails the handshake (docs/PROTOCOL.md §4.1).
  auto stranger = Session::connect(server->session("stranger", "unknown-token-0123456789"));
  ASSERT_FALSE(stranger.isOk());
  EXPECT_NE(stranger.status().message().find("the access token is not known to this server"),
            std::string::npos)
      << stranger.status().message();

  // Bad commands from an admin: NaN, unknown ids, levels past the maximum,
  // bad profiles, an oversized and a malformed mesh.
  ASSERT_TRUE((*admin)->call(testing::openDocument(doc), 10)->has_ack());
  EXPECT_EQ(
      rejected((*admin)->call(testing::moveVertex(doc, VertexId(1, 2).packed(), std::nan(""), 0, 1), 10)),
      wire::REJECT_REASON_INVALID_ARGUMENT);
  auto unknown = (*admin)->call(testing::moveVertex(doc, VertexId(1, 999999).packed(), 0, 0, 1), 10);
  EXPECT_EQ(rejected(unknown), wire::REJECT_REASON_NOT_FOUND);
  EXPECT_NE(unknown->reject().message().find("v1:999999"), std::string::npos) << unknown->reject().message();
  auto tooDeep = (*admin)->call(testing::moveVertex(doc, VertexId(9, 1).packed(), 0, 0, 1), 10);
  EXPECT_EQ(rejected(tooDeep), wire::REJECT_REASON_NOT_FOUND);
  EXPECT_NE(tooDeep->reject().message().find("above the maximum level 4"), std::string::npos)
      << tooDeep->reject().message();
  EXPECT_EQ(rejected((*admin)->call(testing::moveVertex(doc, VertexId(1, 2).packed(), 1e6, 0, 1), 10)),
            wire::REJECT_REASON_LIMIT_EXCEEDED);
  EXPECT_EQ(rejected((*admin)->call(testing::subscribe(doc, 3, 2), 10)),
            wire::REJECT_REASON_INVALID_ARGUMENT);
  EXPECT_EQ(rejected((*admin)->call(testing::subscribe(doc, 1, 9), 10)),
            wire::REJECT_REASON_INVALID_ARGUMENT);
  EXPECT_EQ(rejected((*admin)->call(testing::openDocument(777), 10)), wire::REJECT_REASON_NOT_FOUND);
  EXPECT_EQ(rejected((*admin)->call(testing::createDocument("deep", cube, "", 9), 30)),
            wire::REJECT_REASON_INVALID_ARGUMENT);
  EXPECT_EQ(rejected((*admin)->call(testing::createDocument("junk", "v 0 0 0\nf 1 2 3\n", "", 3), 30)),
            wire::REJECT_REASON_INVALID_MESH);
  auto big = (*admin)->call(testing::createDocument("big", std::string(5000, '#') + cube, "", 3), 30);
  EXPECT_EQ(rejected(big), wire::REJECT_REASON_LIMIT_EXCEEDED);
  EXPECT_NE(big->reject().message().find("above the limit of 4000"), std::string::npos)
      << big->reject().message();
  // Level 4 of the cube has 3,072 triangles: within the server's 5,000, over
  // a subscriber's own budget of 1,000.
  EXPECT_EQ(rejected((*admin)->call(testing::subscribe(doc, 4, 4), 30)), wire::REJECT_REASON_UNSPECIFIED);
  wire::ClientMessage tight = testing::subscribe(doc, 4, 4);
  tight.mutable_subscribe()->mutable_profile()->set_triangle_budget(1000);
  auto overBudget = (*admin)->call(tight, 30);
  EXPECT_EQ(rejected(overBudget), wire::REJECT_REASON_LIMIT_EXCEEDED);
  // Refused from the level counts before any work.
  EXPECT_NE(
      overBudget->reject().message().find("base level 4 alone has 3072 triangles, above the budget of 1000"),
      std::string::npos)
      << overBudget->reject().message();
  wire::ClientMessage undo;
  undo.mutable_undo()->set_document_id(doc);
  undo.mutable_undo()->set_edit_id(42);
  EXPECT_EQ(rejected((*admin)->call(undo, 10)), wire::REJECT_REASON_NOT_FOUND);

  // A frame announcing more than the limit: a fatal error naming sizes.
  auto rogue = Session::connect(server->session("rogue", ""));
  ASSERT_TRUE(rogue.isOk());
  ASSERT_TRUE((*rogue)->sendRaw(std::string("\x7f\xff\xff\xff", 4)).isOk());
  auto error = (*rogue)->receive(10);
  ASSERT_TRUE(error.isOk() && error->has_error())
      << (error.isOk() ? error->DebugString() : error.status().message());
  EXPECT_EQ(error->error().code(), wire::ERROR_CODE_FRAME_TOO_LARGE);
  EXPECT_TRUE(error->error().fatal());
  EXPECT_NE(error->error().message().find("1048576"), std::string::npos) << error->error().message();
  EXPECT_FALSE((*rogue)->receive(5).isOk());  // closed

  // Garbage where a payload should be.
  auto garbler = Session::connect(server->session("garbler", ""));
  ASSERT_TRUE(garbler.isOk());
  ASSERT_TRUE((*garbler)->sendRaw(std::string("\x00\x00\x00\x04\xff\xff\xff\xff", 8)).isOk());
  auto garbled = (*garbler)->receive(10);
  ASSERT_TRUE(garbled.isOk() && garbled->has_error());
  EXPECT_EQ(garbled->error().code(), wire::ERROR_CODE_MALFORMED_FRAME);

  // No Hello first.
  auto rude = Session::connect(server->session("rude", ""));
  ASSERT_TRUE(rude.isOk());

  // The bystander still gets service.
  EXPECT_TRUE((*bystander)->call(testing::ping(), 10)->has_pong());
  auto subscribed = (*bystander)->call(testing::subscribe(doc, 1, 3), 30);
  ASSERT_TRUE(subscribed.isOk() && subscribed->has_ack());
  EXPECT_EQ(server->stop(), 0);
}

TEST(ServerSecurity, LimitsConnectionsPerAddressAndCommandRate) {
  const std::string dir = testing::makeTempDir("tessera-server-limits");
  auto server =
      ServerProcess::start(dir + "/data", {"--connections-per-address", "3", "--commands-per-second", "5"});
  ASSERT_TRUE(server.isOk()) << server.status().message();
  std::vector<std::unique_ptr<Session>> sessions;
  for (int i = 0; i < 3; ++i) {
    auto s = Session::connect(server->session("client", server->adminToken()));
    ASSERT_TRUE(s.isOk()) << s.status().message();
    sessions.push_back(std::move(*s));
  }
  auto fourth = Session::connect(server->session("fourth", ""));
  ASSERT_FALSE(fourth.isOk());
  EXPECT_NE(fourth.status().message().find("connections from 127.0.0.1"), std::string::npos)
      << fourth.status().message();

  wire::ClientMessage list;
  list.mutable_list_documents();
  int limited = 0;
  for (int i = 0; i < 20; ++i)
    limited += rejected(sessions[0]->call(list, 10)) == wire::REJECT_REASON_RATE_LIMITED;
  EXPECT_GE(limited, 10);
  EXPECT_EQ(server->stop(), 0);
}

}  // namespace
}  // namespace tessera

namespace tessera {
namespace {

// Timeouts (§2): a connection that never says hello, and one that falls
// silent, are told why and closed.
TEST(ServerSecurity, TimesOutSilentConnections) {
  const std::string dir = testing::makeTempDir("tessera-server-timeouts");
  auto server = ServerProcess::start(dir + "/data", {"--handshake-timeout", "0.3", "--idle-timeout", "0.6"});
  ASSERT_TRUE(server.isOk()) << server.status().message();
  // Raw TCP: connect and say nothing.
  boost::asio::io_context io;
  boost::asio::ip::tcp::socket mute(io);
  boost::system::error_code ec;
  mute.connect({boost::asio::ip::make_address("127.0.0.1"), server->port()}, ec);
  ASSERT_FALSE(ec) << ec.message();
  std::string received;
  char buffer[512];
  for (;;) {
    const size_t n = mute.read_some(boost::asio::buffer(buffer), ec);
    if (ec) break;
    received.append(buffer, n);
  }
  EXPECT_NE(received.find("no Hello in time"), std::string::npos);

  auto quiet = Session::connect(server->session("quiet", ""));
  ASSERT_TRUE(quiet.isOk());
  auto error = (*quiet)->receive(10);
  ASSERT_TRUE(error.isOk() && error->has_error())
      << (error.isOk() ? error->DebugString() : error.status().message());
  EXPECT_EQ(error->error().code(), wire::ERROR_CODE_TIMEOUT);
  EXPECT_EQ(error->error().message(), "idle timeout");
  EXPECT_EQ(server->stop(), 0);
}

}  // namespace
}  // namespace tessera
