// The web port (docs/WEB_VIEWER.md "Serving it", PROTOCOL.md §1.2): the viewer's
// files over HTTP and the protocol over WebSocket, against the real tessera-server, with an independent
// Beast client (web_client.h). Every refusal is checked for its message,
// and a bystander on the protocol port keeps its latency throughout.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "client/lib/document_view.h"
#include "client/lib/session.h"
#include "core/hierarchy/ids.h"
#include "integration/bystanded_server.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "integration/web_client.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using client::Session;
using testing::Bystander;
using testing::httpExchange;
using testing::httpStatus;
using testing::ServerProcess;
using testing::WebSocketClient;

struct WebServer : testing::BystandedServer {
  uint16_t webPort = 0;
};

void start(WebServer& w, const std::string& name, std::vector<std::string> args = {}) {
  const std::string portFile = testing::makeTempDir(name + "-port") + "/wsport";
  args.insert(args.end(), {"--ws-port", "0", "--ws-port-file", portFile, "--web-root", TESSERA_WEB_DIR});
  testing::startBystanded(w, name, args);
  std::ifstream in(portFile);
  int port = 0;
  ASSERT_TRUE(in >> port && port > 0) << "no web port in " << portFile;
  w.webPort = static_cast<uint16_t>(port);
}

void expectServed(Bystander& bystander, const std::string& during) {
  testing::expectServed(bystander, bystander.run(10), during);
}

std::string get(const std::string& target, const std::string& extraHeaders = "") {
  return "GET " + target + " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n" + extraHeaders + "\r\n";
}

std::string builtFile(const std::string& name) {
  return testing::fileBytes(std::string(TESSERA_WEB_DIR) + "/" + name);
}

std::string upgradeRequest(const std::string& extraHeaders = "") {
  return "GET /ws HTTP/1.1\r\nHost: 127.0.0.1\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
         "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n" +
         extraHeaders + "\r\n";
}

wire::ClientMessage hello(const std::string& token, uint64_t seq = 1) {
  wire::ClientMessage m;
  m.set_client_seq(seq);
  m.mutable_hello()->set_protocol_version(1);
  m.mutable_hello()->set_client_name("web-test");
  m.mutable_hello()->set_token(token);
  return m;
}

wire::ClientMessage withSeq(wire::ClientMessage m, uint64_t seq) {
  m.set_client_seq(seq);
  return m;
}

// The fatal Error a connection ends with, skipping anything before it.
Expected<wire::Error> fatalError(WebSocketClient& ws) {
  for (int i = 0; i < 1000; ++i) {
    TESSERA_ASSIGN_OR_RETURN(wire::ServerMessage m, ws.receive());
    if (m.has_error() && m.error().fatal()) return m.error();
  }
  return ioError("no fatal Error");
}

TEST(WebPort, ServesTheViewersFilesAndNothingElse) {
  WebServer w;
  start(w, "tessera-web-files");
  if (::testing::Test::HasFatalFailure()) return;

  // The page, with a query; the bundle; the decoder; the styles; the worker.
  const std::string page = httpExchange(w.webPort, get("/?doc=1"));
  EXPECT_EQ(httpStatus(page), 200) << page.substr(0, 300);
  EXPECT_NE(page.find("Content-Type: text/html; charset=utf-8"), std::string::npos);
  EXPECT_NE(page.find("X-Content-Type-Options: nosniff"), std::string::npos);
  EXPECT_TRUE(page.ends_with(builtFile("index.html"))) << "the body is not the built index.html";
  EXPECT_EQ(httpExchange(w.webPort, get("/index.html")), page);
  const std::string js = httpExchange(w.webPort, get("/viewer.js"));
  EXPECT_EQ(httpStatus(js), 200);
  EXPECT_NE(js.find("Content-Type: text/javascript"), std::string::npos);
  EXPECT_TRUE(js.ends_with(builtFile("viewer.js")));
  const std::string wasm = httpExchange(w.webPort, get("/draco_decoder.wasm"));
  EXPECT_NE(wasm.find("Content-Type: application/wasm"), std::string::npos);
  EXPECT_TRUE(wasm.ends_with(builtFile("draco_decoder.wasm")));
  EXPECT_EQ(httpStatus(httpExchange(w.webPort, get("/viewer.css"))), 200);
  // The worker that decodes region payloads (docs/WEB_VIEWER.md).
  const std::string worker = httpExchange(w.webPort, get("/decode_worker.js"));
  EXPECT_EQ(httpStatus(worker), 200);
  EXPECT_NE(worker.find("Content-Type: text/javascript"), std::string::npos);
  EXPECT_TRUE(worker.ends_with(builtFile("decode_worker.js")));
  // Compressed for a browser that asks; HEAD has the headers only.
  const std::string gz = httpExchange(w.webPort, get("/viewer.js", "Accept-Encoding: gzip, br\r\n"));
  EXPECT_NE(gz.find("Content-Encoding: gzip"), std::string::npos);
  EXPECT_LT(gz.size(), js.size());
  const std::string head =
      httpExchange(w.webPort, "HEAD /viewer.js HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n");
  EXPECT_EQ(httpStatus(head), 200);
  EXPECT_NE(head.find("Content-Length: " + std::to_string(builtFile("viewer.js").size())), std::string::npos)
      << head;
  EXPECT_TRUE(head.ends_with("\r\n\r\n")) << "HEAD sent a body";

  // Path traversal and other names: 404, never a file of the machine.
  for (const std::string target :
       {"/../../../../etc/passwd", "/%2e%2e/%2e%2e/etc/passwd", "/..%2f..%2fetc%2fpasswd",
        "/viewer.js/../../etc/passwd", "//etc/passwd", "/web/", "/index.html/", "/./index.html",
        "/INDEX.HTML", "/node_modules/three/package.json", "/favicon.ico", "/ws/../index.html",
        "/CMakeLists.txt", "/viewer.js%00.html"}) {
    const std::string r = httpExchange(w.webPort, get(target));
    EXPECT_EQ(httpStatus(r), 404) << target << ": " << r.substr(0, 200);
    EXPECT_EQ(r.find("root:"), std::string::npos) << target;
  }
  // Only GET and HEAD; no bodies; bounded headers; garbage is a 400.
  const std::string post =
      httpExchange(w.webPort, "POST / HTTP/1.1\r\nHost: x\r\nContent-Length: 0\r\nConnection: close\r\n\r\n");
  EXPECT_EQ(httpStatus(post), 405) << post;
  EXPECT_NE(post.find("Allow: GET, HEAD"), std::string::npos);
  const std::string body =
      httpExchange(w.webPort, "GET / HTTP/1.1\r\nHost: x\r\nContent-Length: 5\r\n\r\nhello");
  EXPECT_EQ(httpStatus(body), 413) << body;
  const std::string huge =
      httpExchange(w.webPort, get("/", "X-Padding: " + std::string(64 * 1024, 'a') + "\r\n"));
  EXPECT_EQ(httpStatus(huge), 431) << huge.substr(0, 200);
  EXPECT_EQ(httpStatus(httpExchange(w.webPort, "NONSENSE\r\n\r\n")), 400);
  // A WebSocket upgrade anywhere but /ws.
  EXPECT_FALSE(WebSocketClient::connect(w.webPort, "/index.html").isOk());

  expectServed(*w.bystander, "after the HTTP probes");
  EXPECT_TRUE(w.server->running());
}

// The protocol over WebSocket assembles the same surface as over TCP: a
// browser-like client and a TCP client subscribe with the same profile,
// another TCP client edits, and both views hash equal to each other and
// to the server's hash at every version.
TEST(WebPort, TheProtocolOverWebSocketAssemblesTheSameSurface) {
  WebServer w;
  start(w, "tessera-web-protocol");
  if (::testing::Test::HasFatalFailure()) return;
  auto created =
      w.admin->call(testing::createDocument("ws", testing::fileBytes(testing::sourceTestDataPath("cube.obj")),
                                            testing::fileBytes(testing::sourceTestDataPath("cube.tags")), 4),
                    30);
  ASSERT_TRUE(created.isOk() && created->has_ack())
      << (created.isOk() ? created->DebugString() : created.status().message());
  const uint64_t doc = created->ack().document_id();
  ASSERT_TRUE(w.admin->call(testing::openDocument(doc), 20).isOk());

  auto ws = WebSocketClient::connect(w.webPort, "/ws", "http://127.0.0.1:" + std::to_string(w.webPort));
  ASSERT_TRUE(ws.isOk()) << ws.status().message();
  ASSERT_TRUE((*ws)->send(hello(w.server->adminToken(), 1)).isOk());
  auto ack = (*ws)->receive();
  ASSERT_TRUE(ack.isOk()) << ack.status().message();
  ASSERT_TRUE(ack->has_hello_ack()) << ack->DebugString();
  EXPECT_EQ(ack->hello_ack().role(), wire::ROLE_ADMIN);

  client::DocumentView webView(doc), tcpView(doc);
  auto applyTo = [](client::DocumentView& view) {
    return [&view](const wire::ServerMessage& m) {
      Status s = view.apply(m);
      EXPECT_TRUE(s.isOk()) << s.message();
    };
  };
  ASSERT_TRUE((*ws)->send(withSeq(testing::openDocument(doc), 2)).isOk());
  auto opened = (*ws)->callReply(2, applyTo(webView));
  ASSERT_TRUE(opened.isOk() && opened->has_ack())
      << (opened.isOk() ? opened->DebugString() : opened.status().message());
  ASSERT_TRUE((*ws)->send(withSeq(testing::subscribe(doc, 1, 3), 3)).isOk());
  auto subscribed = (*ws)->callReply(3, applyTo(webView));
  ASSERT_TRUE(subscribed.isOk() && subscribed->has_ack()) << subscribed->DebugString();
  for (int i = 0; i < 100 && !webView.ready(); ++i) {
    auto m = (*ws)->receive();
    ASSERT_TRUE(m.isOk()) << m.status().message();
    applyTo(webView)(*m);
  }
  ASSERT_TRUE(webView.ready());
  EXPECT_TRUE(webView.verifySurface().isOk()) << webView.verifySurface().message();

  auto tcp = Session::connect(w.server->session("tcp-viewer", w.server->adminToken()));
  ASSERT_TRUE(tcp.isOk());
  ASSERT_TRUE((*tcp)->call(testing::openDocument(doc), 20).isOk());
  ASSERT_TRUE((*tcp)->call(testing::subscribe(doc, 1, 3), 20).isOk());
  while (!tcpView.ready() || tcpView.version() < webView.version()) {
    auto m = (*tcp)->receive(20);
    ASSERT_TRUE(m.isOk()) << m.status().message();
    applyTo(tcpView)(*m);
  }
  EXPECT_EQ(webView.surfaceHash(), tcpView.surfaceHash());

  // Three edits from the TCP side; the WebSocket view follows each.
  for (int k = 0; k < 3; ++k) {
    auto moved = w.admin->call(
        testing::moveVertex(doc, VertexId(1, 2).packed(), 0, 0, 0.05 * (k + 1), wire::MOVE_MODE_OFFSET), 20);
    ASSERT_TRUE(moved.isOk() && moved->has_ack())
        << (moved.isOk() ? moved->DebugString() : moved.status().message());
    const uint64_t version = moved->ack().version();
    while (webView.version() < version) {
      auto m = (*ws)->receive();
      ASSERT_TRUE(m.isOk()) << m.status().message();
      applyTo(webView)(*m);
    }
    while (tcpView.version() < version) {
      auto m = (*tcp)->receive(20);
      ASSERT_TRUE(m.isOk()) << m.status().message();
      applyTo(tcpView)(*m);
    }
    EXPECT_TRUE(webView.verifySurface().isOk()) << webView.verifySurface().message();
    EXPECT_EQ(webView.surfaceHash(), tcpView.surfaceHash()) << "version " << version;
  }
  // An edit through the WebSocket reaches the TCP side.
  ASSERT_TRUE(
      (*ws)
          ->send(withSeq(testing::moveVertex(doc, VertexId(0, 1).packed(), 0, 0.1, 0, wire::MOVE_MODE_OFFSET),
                         4))
          .isOk());
  auto moved = (*ws)->callReply(4, applyTo(webView));
  ASSERT_TRUE(moved.isOk() && moved->has_ack()) << moved->DebugString();
  while (tcpView.version() < moved->ack().version()) {
    auto m = (*tcp)->receive(20);
    ASSERT_TRUE(m.isOk()) << m.status().message();
    applyTo(tcpView)(*m);
  }
  EXPECT_TRUE(tcpView.verifySurface().isOk());
}

// Each bad WebSocket peer gets its protocol error (or HTTP refusal), and
// the server and a bystander go on.
TEST(WebPort, BadWebSocketPeersAreRefusedByName) {
  WebServer w;
  start(w, "tessera-web-abuse", {"--handshake-timeout", "1", "--connections-per-address", "3"});
  if (::testing::Test::HasFatalFailure()) return;

  {  // A frame larger than the Hello's limit: refused from its prefix
     // (1 MiB announced; the rest is not sent, so that the server has read
     // everything when it closes and the Error is not lost to a reset).
    auto ws = WebSocketClient::connect(w.webPort);
    ASSERT_TRUE(ws.isOk()) << ws.status().message();
    std::string big = std::string("\x00\x10\x00\x00", 4) + std::string(1000, 'x');
    (void)(*ws)->sendBytes(big);
    auto e = fatalError(**ws);
    ASSERT_TRUE(e.isOk()) << e.status().message();
    EXPECT_EQ(e->code(), wire::ERROR_CODE_FRAME_TOO_LARGE) << e->message();
    EXPECT_NE(e->message().find("Hello"), std::string::npos) << e->message();
  }
  {  // Two frames in one message.
    auto ws = WebSocketClient::connect(w.webPort);
    ASSERT_TRUE(ws.isOk());
    auto a = encodeFrame(hello(w.server->adminToken(), 1));
    auto b = encodeFrame(withSeq(testing::ping(), 2));
    ASSERT_TRUE((*ws)->sendBytes(*a + *b).isOk());
    auto e = fatalError(**ws);
    ASSERT_TRUE(e.isOk()) << e.status().message();
    EXPECT_EQ(e->code(), wire::ERROR_CODE_MALFORMED_FRAME);
    EXPECT_NE(e->message().find("more than one frame"), std::string::npos) << e->message();
  }
  {  // A text message.
    auto ws = WebSocketClient::connect(w.webPort);
    ASSERT_TRUE(ws.isOk());
    ASSERT_TRUE((*ws)->sendBytes("{\"hello\":1}", false).isOk());
    auto e = fatalError(**ws);
    ASSERT_TRUE(e.isOk()) << e.status().message();
    EXPECT_EQ(e->code(), wire::ERROR_CODE_MALFORMED_FRAME);
    EXPECT_NE(e->message().find("is text"), std::string::npos) << e->message();
  }
  {  // A frame cut short at the message's end.
    auto ws = WebSocketClient::connect(w.webPort);
    ASSERT_TRUE(ws.isOk());
    auto a = encodeFrame(hello(w.server->adminToken(), 1));
    ASSERT_TRUE((*ws)->sendBytes(a->substr(0, a->size() - 3)).isOk());
    auto e = fatalError(**ws);
    ASSERT_TRUE(e.isOk()) << e.status().message();
    EXPECT_EQ(e->code(), wire::ERROR_CODE_MALFORMED_FRAME);
    EXPECT_NE(e->message().find("ends inside its frame"), std::string::npos) << e->message();
  }
  {  // An upgrade and no Hello: the handshake deadline (1 s here).
    auto ws = WebSocketClient::connect(w.webPort);
    ASSERT_TRUE(ws.isOk());
    auto e = fatalError(**ws);
    ASSERT_TRUE(e.isOk()) << e.status().message();
    EXPECT_EQ(e->code(), wire::ERROR_CODE_TIMEOUT);
    EXPECT_EQ(e->message(), "no Hello in time");
  }
  {  // No token: only ping; a subscribe is refused as unauthenticated.
    auto ws = WebSocketClient::connect(w.webPort);
    ASSERT_TRUE(ws.isOk());
    ASSERT_TRUE((*ws)->send(hello("", 1)).isOk());
    auto ack = (*ws)->receive();
    ASSERT_TRUE(ack.isOk() && ack->has_hello_ack());
    EXPECT_EQ(ack->hello_ack().role(), wire::ROLE_UNSPECIFIED);
    ASSERT_TRUE((*ws)->send(withSeq(testing::subscribe(w.bystander->document(), 1, 2), 2)).isOk());
    auto r = (*ws)->callReply(2, [](const wire::ServerMessage&) {});
    ASSERT_TRUE(r.isOk() && r->has_reject()) << (r.isOk() ? r->DebugString() : r.status().message());
    EXPECT_EQ(r->reject().reason(), wire::REJECT_REASON_NOT_AUTHENTICATED);
  }
  {  // A wrong token.
    auto ws = WebSocketClient::connect(w.webPort);
    ASSERT_TRUE(ws.isOk());
    ASSERT_TRUE((*ws)->send(hello("not-a-token-of-this-server", 1)).isOk());
    auto e = fatalError(**ws);
    ASSERT_TRUE(e.isOk()) << e.status().message();
    EXPECT_EQ(e->code(), wire::ERROR_CODE_AUTH_FAILED);
    EXPECT_EQ(e->message().find("not-a-token"), std::string::npos) << "the token was echoed";
  }
  // A page of another origin may not open a WebSocket; no Origin (not a
  // browser) and the page's own may.
  EXPECT_FALSE(WebSocketClient::connect(w.webPort, "/ws", "https://evil.example").isOk());
  const std::string refused = httpExchange(w.webPort, upgradeRequest("Origin: https://evil.example\r\n"));
  EXPECT_EQ(httpStatus(refused), 403);
  EXPECT_NE(refused.find("origin https://evil.example may not connect"), std::string::npos) << refused;

  // The per-address limit (3 here) counts WebSocket and TCP connections
  // together: the bystander's two are on 127.0.0.9; from 127.0.0.1, two TCP
  // sessions and one WebSocket fill it, and the next upgrade is a 503.
  auto t1 = Session::connect(w.server->session("t1", w.server->adminToken()));
  auto t2 = Session::connect(w.server->session("t2", w.server->adminToken()));
  ASSERT_TRUE(t1.isOk() && t2.isOk());
  auto w1 = WebSocketClient::connect(w.webPort);
  ASSERT_TRUE(w1.isOk());
  ASSERT_TRUE((*w1)->send(hello(w.server->adminToken(), 1)).isOk());
  ASSERT_TRUE((*w1)->receive().isOk());
  EXPECT_FALSE(WebSocketClient::connect(w.webPort).isOk())
      << "a fourth connection from 127.0.0.1 was upgraded";
  const std::string over = httpExchange(w.webPort, upgradeRequest());
  EXPECT_EQ(httpStatus(over), 503) << over;
  EXPECT_NE(over.find("more than 3 connections from 127.0.0.1"), std::string::npos) << over;

  expectServed(*w.bystander, "after the WebSocket abuse");
  // And the web port still serves.
  EXPECT_EQ(httpStatus(httpExchange(w.webPort, get("/"))), 200);
}

}  // namespace
}  // namespace tessera
