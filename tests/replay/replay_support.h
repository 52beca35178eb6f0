// What the replay tests share: running the real tessera-replay binary, and a
// fresh real tessera-server with the creased cube as a document.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

#include "client/lib/session.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "support/test_meshes.h"

namespace tessera::testing {

inline constexpr const char* kEditorToken = "replay-editor-token-0123456789";
inline constexpr const char* kViewerToken = "replay-viewer-token-0123456789";

// Runs a command; its stdout (with stderr too if asked), and the exit code.
inline std::pair<std::string, int> run(const std::string& command, bool withStderr = false) {
  FILE* pipe = popen((command + (withStderr ? " 2>&1" : " 2>/dev/null")).c_str(), "r");
  std::string out;
  char buffer[4096];
  for (size_t n; pipe && (n = fread(buffer, 1, sizeof buffer, pipe)) > 0;) out.append(buffer, n);
  const int status = pipe ? pclose(pipe) : -1;
  return {out, WIFEXITED(status) ? WEXITSTATUS(status) : -1};
}

// V of the line "NAME V" in the tool's output ("version 61", "surface_hash ...").
inline std::string field(const std::string& out, const std::string& name) {
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string key, value;
    if (words >> key >> value && key == name) return value;
  }
  return "";
}

// A fresh server with the creased cube as a document, an editor token and a
// viewer token granted on it.
struct ReplayServer {
  std::optional<ServerProcess> process;
  uint64_t doc = 0;
  std::string connection(const std::string& token = kEditorToken) const {
    return " --port " + std::to_string(process->port()) + " --token " + token + " --document " +
           std::to_string(doc);
  }
};

// The server with one document: the creased cube of triangles, or `mesh`
// (a test data path) without tags, under the scheme its faces call for.
inline void startServer(ReplayServer& s, const std::string& name, const std::string& mesh = "") {
  auto server = ServerProcess::start(makeTempDir(name) + "/data");
  ASSERT_TRUE(server.isOk()) << server.status().message();
  s.process.emplace(std::move(*server));
  auto admin = client::Session::connect(s.process->session("admin", s.process->adminToken()));
  ASSERT_TRUE(admin.isOk()) << admin.status().message();
  auto created =
      (*admin)->call(mesh.empty() ? createDocument("cube", fileBytes(sourceTestDataPath("cube.obj")),
                                                   fileBytes(sourceTestDataPath("cube.tags")), 5)
                                  : createDocument(mesh, fileBytes(sourceTestDataPath(mesh)), "", 5),
                     30);
  ASSERT_TRUE(created.isOk() && created->has_ack())
      << (created.isOk() ? created->DebugString() : created.status().message());
  s.doc = created->ack().document_id();
  for (auto [role, token] :
       {std::pair{wire::ROLE_EDITOR, kEditorToken}, std::pair{wire::ROLE_VIEWER, kViewerToken}}) {
    auto granted = (*admin)->call(grant(s.doc, role, token), 10);
    ASSERT_TRUE(granted.isOk() && granted->has_ack());
  }
}

}  // namespace tessera::testing
