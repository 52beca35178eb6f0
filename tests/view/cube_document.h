// The cube of tests/data as a document on a running test server, for the
// viewer's tests.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "client/lib/session.h"
#include "client/view/view_options.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "support/test_meshes.h"

namespace tessera::testing {

// Creates `mesh` of tests/data (with the tag file `tags` unless empty)
// through an admin session, the scheme chosen by the server from the faces:
// the document id, or an error saying what failed.
inline Expected<uint64_t> createFromTestData(const ServerProcess& server, const std::string& mesh,
                                             const std::string& tags, int maxLevel) {
  TESSERA_ASSIGN_OR_RETURN(std::unique_ptr<client::Session> admin,
                           client::Session::connect(server.session("admin", server.adminToken())));
  auto created = admin->call(
      createDocument(std::filesystem::path(mesh).stem().string(), fileBytes(sourceTestDataPath(mesh)),
                     tags.empty() ? "" : fileBytes(sourceTestDataPath(tags)), maxLevel),
      30);
  if (!created.isOk()) return created.status();
  if (!created->has_ack()) return internalError("creating " + mesh + ": " + created->DebugString());
  return created->ack().document_id();
}

// Creates cube.obj (with cube.tags when `tags`).
inline Expected<uint64_t> createCube(const ServerProcess& server, bool tags, int maxLevel) {
  return createFromTestData(server, "cube.obj", tags ? "cube.tags" : "", maxLevel);
}

// A viewer connection's options for `document` on `server`, with the admin
// token and the LOD profile baseLevel..maxLevel.
inline view::ViewOptions viewOptionsFor(const ServerProcess& server, uint64_t document, uint32_t baseLevel,
                                        uint32_t maxLevel) {
  view::ViewOptions options;
  options.port = server.port();
  options.token = server.adminToken();
  options.document = document;
  options.baseLevel = baseLevel;
  options.maxLevel = maxLevel;
  return options;
}

}  // namespace tessera::testing
