// Optional TLS (docs/PROTOCOL.md §1): with a certificate the server speaks only
// TLS; a client verifying it against the right certificate gets service, a
// plain client or one trusting another certificate does not.
#include <gtest/gtest.h>

#include <cstdlib>

#include "client/lib/session.h"
#include "integration/certificates.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using client::Session;
using testing::ServerProcess;

using testing::makeCertificate;

TEST(ServerTls, ServesVerifiedTlsClientsOnly) {
  const std::string dir = testing::makeTempDir("tessera-server-tls");
  ASSERT_TRUE(makeCertificate(dir, "server"));
  ASSERT_TRUE(makeCertificate(dir, "other"));
  auto server = ServerProcess::start(dir + "/data",
                                     {"--tls-cert", dir + "/server.pem", "--tls-key", dir + "/server.key"});
  ASSERT_TRUE(server.isOk()) << server.status().message();

  client::SessionOptions options = server->session("secure", server->adminToken());
  options.tls = true;
  options.tlsCaFile = dir + "/server.pem";
  auto secure = Session::connect(options);
  ASSERT_TRUE(secure.isOk()) << secure.status().message();
  EXPECT_EQ((*secure)->role(), wire::ROLE_ADMIN);
  EXPECT_TRUE((*secure)->call(testing::ping(), 10)->has_pong());
  auto created = (*secure)->call(
      testing::createDocument("cube", testing::fileBytes(testing::sourceTestDataPath("cube.obj")), "", 3),
      30);
  ASSERT_TRUE(created.isOk() && created->has_ack());

  client::SessionOptions plain = server->session("plain", server->adminToken());
  plain.timeoutSeconds = 3;
  EXPECT_FALSE(Session::connect(plain).isOk());

  client::SessionOptions wrongTrust = options;
  wrongTrust.tlsCaFile = dir + "/other.pem";
  auto refused = Session::connect(wrongTrust);
  ASSERT_FALSE(refused.isOk());
  EXPECT_NE(refused.status().message().find("TLS handshake"), std::string::npos)
      << refused.status().message();

  EXPECT_TRUE((*secure)->call(testing::ping(), 10)->has_pong());
  EXPECT_EQ(server->stop(), 0);
}

TEST(ServerTls, RefusesToStartWithABadCertificate) {
  const std::string dir = testing::makeTempDir("tessera-server-badtls");
  std::ofstream(dir + "/bad.pem") << "not a certificate\n";
  auto server =
      ServerProcess::start(dir + "/data", {"--tls-cert", dir + "/bad.pem", "--tls-key", dir + "/bad.pem"});
  ASSERT_FALSE(server.isOk());
  EXPECT_NE(testing::fileBytes(dir + "/data.log").find("--tls-cert " + dir + "/bad.pem"), std::string::npos)
      << testing::fileBytes(dir + "/data.log");
}

}  // namespace
}  // namespace tessera
