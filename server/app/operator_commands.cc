#include "server/app/operator_commands.h"

#include <sys/random.h>
#include <array>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>

#include "core/util/hex.h"
#include "server/app/server.h"
#include "server/base/log.h"
#include "server/ops/http_get.h"
#include "server/store/store_admin.h"

namespace tessera::server {

namespace {

// Within the container image's HEALTHCHECK --timeout of 5 s (deploy/Dockerfile).
constexpr std::chrono::seconds kHealthTimeout{3};

int failed(std::string_view event, const Status& status) {
  logEvent(LogLevel::kError, event, {{"error", status.message()}});
  return 1;
}

// 32 bytes from the kernel's CSPRNG, as 64 hex digits: 256 bits, far above
// the 16-byte minimum the server accepts.
Expected<std::string> randomToken() {
  std::array<unsigned char, 32> bytes{};
  size_t filled = 0;
  while (filled < bytes.size()) {
    const ssize_t n = ::getrandom(bytes.data() + filled, bytes.size() - filled, 0);
    if (n < 0) {
      if (errno == EINTR) continue;
      return ioError(std::string("getrandom failed: ") + std::strerror(errno));
    }
    filled += static_cast<size_t>(n);
  }
  return hexBytes(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace

int runTokenNew(const ServerCommandLine& command) {
  auto role = store::parseRole(command.role);
  if (!role.isOk()) return failed("token_new_failed", role.status());
  auto token = randomToken();
  if (!token.isOk()) return failed("token_new_failed", token.status());
  const store::TokenScope scope = command.documentId == 0
                                      ? store::TokenScope::allDocuments()
                                      : store::TokenScope::document(store::DocumentId{command.documentId});
  Status stored;
  if (command.config.cluster.empty()) {
    stored = store::grantTokenInStore(command.config.dataDirectory, scope, *token, *role);
  } else {
    // A cluster's tokens live in NATS, shared by every node: no node needs
    // to be stopped or told.
    auto store = openStore(command.config);
    stored = store.isOk() ? (*store)->addToken(scope, *token, *role) : store.status();
  }
  if (!stored.isOk()) return failed("token_new_failed", stored);
  // The token itself goes to stdout only (never to the log).
  logEvent(
      LogLevel::kInfo, "token_created",
      {{"role", command.role},
       {"scope", scope.toString()},
       {"store", command.config.cluster.empty() ? command.config.dataDirectory : command.config.cluster}});
  std::printf("%s\n", token->c_str());
  return 0;
}

int runBackup(const ServerCommandLine& command) {
  const Status done = store::backupStore(command.config.dataDirectory, command.path);
  if (!done.isOk()) return failed("backup_failed", done);
  logEvent(LogLevel::kInfo, "backup_written",
           {{"data", command.config.dataDirectory}, {"file", command.path}});
  return 0;
}

int runRestore(const ServerCommandLine& command) {
  const Status done = store::restoreStore(command.config.dataDirectory, command.path);
  if (!done.isOk()) return failed("restore_failed", done);
  logEvent(LogLevel::kInfo, "restored", {{"data", command.config.dataDirectory}, {"file", command.path}});
  return 0;
}

int runHealth(const ServerCommandLine& command) {
  std::string url = command.url;
  if (url.empty()) {
    if (command.config.httpPort <= 0) {
      return failed("health_failed",
                    invalidArgument("health needs --url or --http-port (or a --config that sets it)"));
    }
    const std::string& host = command.config.httpListenAddress;
    url = "http://" + (host.find(':') == std::string::npos ? host : "[" + host + "]") + ":" +
          std::to_string(command.config.httpPort) + "/healthz";
  }
  auto reply = httpGet(url, kHealthTimeout);
  if (!reply.isOk()) {
    const bool badOption = !command.url.empty() && reply.status().code() == ErrorCode::kInvalidArgument;
    return failed("health_failed", badOption ? reply.status().withContext("--url") : reply.status());
  }
  std::fputs(reply->body.c_str(), stdout);
  return reply->status == 200 ? 0 : 1;
}

}  // namespace tessera::server
