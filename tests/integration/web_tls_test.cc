// The web port with TLS on (PROTOCOL.md §1.2): the same
// certificate serves https:// for the page and wss:// for the protocol, and
// a plain-HTTP request gets nothing. The client verifies the certificate
// and speaks the protocol over wss with Boost.Beast.
#include <gtest/gtest.h>

#include <boost/asio/ssl.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/ssl.hpp>
#include <boost/beast/websocket.hpp>
#include <boost/beast/websocket/ssl.hpp>
#include <fstream>

#include "integration/certificates.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "integration/web_client.h"
#include "protocol/framing.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
using testing::ServerProcess;

TEST(WebPortTls, ServesHttpsAndWssWithTheServersCertificate) {
  const std::string dir = testing::makeTempDir("tessera-web-tls");
  ASSERT_TRUE(testing::makeCertificate(dir, "server"));
  const std::string portFile = dir + "/ws.port";
  auto server = ServerProcess::start(
      dir + "/data", {"--tls-cert", dir + "/server.pem", "--tls-key", dir + "/server.key", "--ws-port", "0",
                      "--ws-port-file", portFile, "--web-root", TESSERA_WEB_DIR});
  ASSERT_TRUE(server.isOk()) << server.status().message();
  int port = 0;
  std::ifstream(portFile) >> port;
  ASSERT_GT(port, 0);
  const asio::ip::tcp::endpoint endpoint(asio::ip::make_address("127.0.0.1"), static_cast<uint16_t>(port));

  asio::io_context io;
  asio::ssl::context tls(asio::ssl::context::tls_client);
  tls.load_verify_file(dir + "/server.pem");
  tls.set_verify_mode(asio::ssl::verify_peer);

  {  // https://: the page.
    beast::ssl_stream<beast::tcp_stream> stream(io, tls);
    stream.next_layer().connect(endpoint);
    stream.next_layer().expires_after(std::chrono::seconds(20));
    stream.set_verify_callback(asio::ssl::host_name_verification("127.0.0.1"));
    stream.handshake(asio::ssl::stream_base::client);
    beast::http::request<beast::http::empty_body> request(beast::http::verb::get, "/?doc=1", 11);
    request.set(beast::http::field::host, "127.0.0.1");
    beast::http::write(stream, request);
    beast::flat_buffer buffer;
    beast::http::response<beast::http::string_body> response;
    beast::http::read(stream, buffer, response);
    EXPECT_EQ(response.result_int(), 200);
    EXPECT_EQ(response.body(), testing::fileBytes(std::string(TESSERA_WEB_DIR) + "/index.html"));
  }
  {  // wss://: the protocol, one frame per message.
    beast::websocket::stream<beast::ssl_stream<beast::tcp_stream>> ws(io, tls);
    beast::get_lowest_layer(ws).connect(endpoint);
    beast::get_lowest_layer(ws).expires_after(std::chrono::seconds(20));
    ws.next_layer().set_verify_callback(asio::ssl::host_name_verification("127.0.0.1"));
    ws.next_layer().handshake(asio::ssl::stream_base::client);
    ws.handshake("127.0.0.1:" + std::to_string(port), "/ws");
    ws.binary(true);
    wire::ClientMessage hello;
    hello.set_client_seq(1);
    hello.mutable_hello()->set_protocol_version(1);
    hello.mutable_hello()->set_token(server->adminToken());
    ws.write(asio::buffer(*encodeFrame(hello)));
    beast::flat_buffer buffer;
    ws.read(buffer);
    FrameDecoder decoder;
    ASSERT_TRUE(decoder.feed(beast::buffers_to_string(buffer.data())).isOk());
    wire::ServerMessage reply;
    auto got = decoder.next(reply);
    ASSERT_TRUE(got.isOk() && *got);
    ASSERT_TRUE(reply.has_hello_ack()) << reply.DebugString();
    EXPECT_EQ(reply.hello_ack().role(), wire::ROLE_ADMIN);
  }
  // Plain HTTP on the TLS port: no page, no upgrade.
  const std::string plain =
      testing::httpExchange(static_cast<uint16_t>(port), "GET / HTTP/1.1\r\nHost: x\r\n\r\n", 5);
  EXPECT_EQ(testing::httpStatus(plain), 0) << plain.substr(0, 100);
  EXPECT_EQ(plain.find("<html"), std::string::npos);
  EXPECT_EQ(server->stop(), 0);
}

}  // namespace
}  // namespace tessera
