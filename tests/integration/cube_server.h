// A real tessera-server holding the creased cube (tests/data cube.obj with
// cube.tags), created and opened by an admin session: the set-up of the
// integration tests that hold one document's replies and stream against
// the docs (protocol_document_test.cc, region_codec_stream_test.cc).
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "client/lib/session.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "support/test_meshes.h"

namespace tessera::testing {

struct CubeServer {
  std::optional<ServerProcess> process;
  std::unique_ptr<client::Session> admin;
  uint64_t doc = 0;  // the cube's document id
};

// Starts a server on a fresh data directory (makeTempDir(name)), creates the
// cube with max level `maxLevel` and opens it as the admin. Fails the test
// fatally otherwise: callers return on HasFatalFailure().
inline void startWithCube(CubeServer& s, const std::string& name, int maxLevel) {
  const std::string dir = makeTempDir(name);
  auto process = ServerProcess::start(dir + "/data");
  ASSERT_TRUE(process.isOk()) << process.status().message();
  s.process.emplace(std::move(*process));
  auto admin = client::Session::connect(s.process->session("admin", s.process->adminToken()));
  ASSERT_TRUE(admin.isOk()) << admin.status().message();
  s.admin = std::move(*admin);
  auto created = s.admin->call(createDocument("cube", fileBytes(sourceTestDataPath("cube.obj")),
                                              fileBytes(sourceTestDataPath("cube.tags")), maxLevel),
                               30);
  ASSERT_TRUE(created.isOk() && created->has_ack())
      << (created.isOk() ? created->DebugString() : created.status().message());
  s.doc = created->ack().document_id();
  auto opened = s.admin->call(openDocument(s.doc), 10);
  ASSERT_TRUE(opened.isOk() && opened->has_ack());
}

}  // namespace tessera::testing
