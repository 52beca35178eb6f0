// Acceptance is a function of the document's history alone (docs/PROTOCOL.md
// "The document's bounds"). One random command sequence on CGAL's hand is
// applied four ways:
//   (a) offline, by `tessera doc edit --each`;
//   (b) on a server with no viewer;
//   (c) on a server whose viewers subscribe at several profiles and leave
//       during the run (the levels the hierarchy holds change under it);
//   (d) on a server killed with SIGKILL halfway and restarted.
// Every command must get the same decision in all four, and the four
// documents must export bit-identical GLB files.
#include <gtest/gtest.h>

#include <fstream>
#include <optional>

#include "cli/cli_run.h"
#include "client/lib/script_wire.h"
#include "client/lib/session.h"
#include "core/document/edit_script.h"
#include "core/io/mesh_import.h"
#include "core/tessellation/document_grid.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "support/random_script.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using client::Session;
using testing::ServerProcess;

constexpr int kMaxLevel = 4;
constexpr int kCommands = 200;

// One editor sends the whole history as fast as replies come.
const std::vector<std::string> kServerArgs = {"--commands-per-second", "100000"};

std::optional<ServerProcess> startServer(const std::string& data) {
  auto started = ServerProcess::start(data, kServerArgs);
  EXPECT_TRUE(started.isOk()) << started.status().message();
  if (!started.isOk()) return std::nullopt;
  return std::move(*started);
}

std::unique_ptr<Session> connect(const ServerProcess& server, const std::string& name) {
  auto session = Session::connect(server.session(name, server.adminToken()));
  EXPECT_TRUE(session.isOk()) << session.status().message();
  return session.isOk() ? std::move(*session) : nullptr;
}

uint64_t createDocument(Session& admin, const std::string& meshPath, const std::string& name) {
  wire::ClientMessage create = testing::createDocument(name, testing::fileBytes(meshPath), "", kMaxLevel);
  create.mutable_create_document()->set_mesh_format(wire::MESH_FORMAT_OFF);
  auto created = admin.call(create, 60);
  EXPECT_TRUE(created.isOk() && created->has_ack()) << (created.isOk() ? created->DebugString() : "");
  if (!created.isOk() || !created->has_ack()) return 0;
  const uint64_t doc = created->ack().document_id();
  auto opened = admin.call(testing::openDocument(doc), 60);
  EXPECT_TRUE(opened.isOk() && opened->has_ack()) << (opened.isOk() ? opened->DebugString() : "");
  return doc;
}

// Sends one command and waits for its reply: true for an Ack. `why` gets a
// Reject's message.
bool decide(Session& editor, const ScriptCommand& c, uint64_t doc, std::string* why = nullptr) {
  auto message = client::clientMessageOf(c, doc);
  EXPECT_TRUE(message.isOk()) << message.status().message();
  auto reply = editor.call(*message, 60);
  EXPECT_TRUE(reply.isOk() && (reply->has_ack() || reply->has_reject()))
      << "line " << c.line << ": " << (reply.isOk() ? reply->DebugString() : reply.status().message());
  if (why && reply.isOk() && reply->has_reject()) *why = reply->reject().message();
  return reply.isOk() && reply->has_ack();
}

std::string exportGlb(Session& session, uint64_t doc) {
  wire::ClientMessage m;
  m.mutable_export_document()->set_document_id(doc);
  m.mutable_export_document()->set_level(3);
  m.mutable_export_document()->set_limit(true);
  auto reply = session.call(m, 120);
  EXPECT_TRUE(reply.isOk() && reply->has_export_result()) << (reply.isOk() ? reply->DebugString() : "");
  return reply.isOk() && reply->has_export_result() ? reply->export_result().glb() : "";
}

// Bit-identical, or where the first difference is (not the bytes: they are binary).
::testing::AssertionResult sameBytes(const std::string& a, const std::string& b) {
  if (a == b) return ::testing::AssertionSuccess();
  size_t at = 0;
  while (at < a.size() && at < b.size() && a[at] == b[at]) ++at;
  return ::testing::AssertionFailure()
         << a.size() << " and " << b.size() << " bytes, first difference at byte " << at;
}

std::vector<bool> offlineDecisions(const std::string& out, const std::string& script) {
  std::vector<bool> decisions;
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind(script + ":", 0) != 0) continue;
    decisions.push_back(line.find(": accepted") != std::string::npos);
  }
  return decisions;
}

TEST(Acceptance, DecisionsAndExportsAreTheSameOfflineWithOrWithoutViewersAndAcrossKillNine) {
  const std::string dir = testing::makeTempDir("tessera-acceptance");
  const std::string meshPath = testing::cgalMeshPath("hand.off");
  auto mesh = importMesh(meshPath);
  ASSERT_TRUE(mesh.isOk()) << mesh.status().message();
  auto model = Document::create(*mesh, {.maxLevel = kMaxLevel});
  ASSERT_TRUE(model.isOk());
  auto grid = documentGrid(*model);
  ASSERT_TRUE(grid.isOk());
  const std::vector<std::string> lines = testing::randomScriptLines(*model, *grid, kCommands, 2026);
  const std::string script = dir + "/history.script";
  {
    std::ofstream out(script);
    for (const std::string& line : lines) out << line << "\n";
  }
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  auto commands = parseEditScript(text, script);
  ASSERT_TRUE(commands.isOk()) << commands.status().message();

  // (a) Offline.
  CliRun made = runCli("doc new " + meshPath + " --max-level " + std::to_string(kMaxLevel) + " -o " + dir +
                       "/offline.doc");
  ASSERT_EQ(made.exitCode, 0) << made.err;
  CliRun edited = runCli("doc edit " + dir + "/offline.doc --script " + script + " --each");
  ASSERT_EQ(edited.exitCode, 0) << edited.err;
  const std::vector<bool> offline = offlineDecisions(edited.out, script);
  ASSERT_EQ(offline.size(), commands->size()) << edited.out;
  CliRun exported = runCli("doc export " + dir + "/offline.doc --level 3 --limit -o " + dir + "/offline.glb");
  ASSERT_EQ(exported.exitCode, 0) << exported.err;
  const std::string offlineGlb = readAll(dir + "/offline.glb");
  ASSERT_FALSE(offlineGlb.empty());
  const int accepted = static_cast<int>(std::count(offline.begin(), offline.end(), true));
  EXPECT_GT(accepted, kCommands / 3) << "the history must be mostly accepted";
  EXPECT_GT(kCommands - accepted, 10) << "and exercise refusals";
  size_t byBounds = 0;
  for (size_t at = 0; (at = edited.out.find("outside the document's bounds", at)) != std::string::npos; ++at)
    ++byBounds;
  EXPECT_GT(byBounds, 5u) << "refusals by the bounds among them";
  std::printf("offline: %d of %d accepted, %zu refused by the bounds\n", accepted, kCommands, byBounds);

  const std::string data = dir + "/data";
  std::optional<ServerProcess> server = startServer(data);
  ASSERT_TRUE(server);
  auto admin = connect(*server, "admin");
  ASSERT_TRUE(admin);

  // (b) No viewer.
  const uint64_t plain = createDocument(*admin, meshPath, "plain");
  ASSERT_NE(plain, 0u);
  for (const ScriptCommand& c : *commands) {
    std::string why;
    EXPECT_EQ(decide(*admin, c, plain, &why), offline[c.line - 1])
        << "(b) line " << c.line << ": " << lines[c.line - 1] << ": " << why;
  }
  EXPECT_TRUE(sameBytes(exportGlb(*admin, plain), offlineGlb)) << "(b) export";

  // (c) Viewers come and go at several profiles.
  const uint64_t watched = createDocument(*admin, meshPath, "watched");
  ASSERT_NE(watched, 0u);
  const std::vector<std::pair<uint32_t, uint32_t>> profiles = {{0, 2}, {1, 3}, {3, 4}, {2, 4}};
  std::vector<std::unique_ptr<Session>> viewers;
  for (int i = 0; i < 3; ++i) {
    viewers.push_back(connect(*server, "viewer" + std::to_string(i)));
    ASSERT_TRUE(viewers.back());
    ASSERT_TRUE(viewers.back()->call(testing::openDocument(watched), 60)->has_ack());
  }
  for (const ScriptCommand& c : *commands) {
    if (c.line % 15 == 1) {
      // Each viewer leaves, and most come back at another profile.
      for (size_t i = 0; i < viewers.size(); ++i) {
        wire::ClientMessage leave;
        leave.mutable_unsubscribe()->set_document_id(watched);
        viewers[i]->call(leave, 30);
        if ((c.line / 15 + i) % 4 == 3) continue;
        const auto [base, max] = profiles[(c.line / 15 + i) % profiles.size()];
        auto joined = viewers[i]->call(testing::subscribe(watched, base, max, 10), 60);
        EXPECT_TRUE(joined.isOk() && joined->has_ack()) << "viewer " << i << " at " << base << ".." << max;
      }
    }
    EXPECT_EQ(decide(*admin, c, watched), offline[c.line - 1])
        << "(c) line " << c.line << ": " << lines[c.line - 1];
  }
  viewers.clear();
  EXPECT_TRUE(sameBytes(exportGlb(*admin, watched), offlineGlb)) << "(c) export";

  // (d) Killed with SIGKILL halfway, restarted on the same store.
  const uint64_t killed = createDocument(*admin, meshPath, "killed");
  ASSERT_NE(killed, 0u);
  for (const ScriptCommand& c : *commands) {
    if (c.line == kCommands / 2) {
      admin.reset();
      server->kill9();
      server.reset();
      auto restarted = ServerProcess::start(data, kServerArgs);
      ASSERT_TRUE(restarted.isOk()) << restarted.status().message();
      server.emplace(std::move(*restarted));
      admin = connect(*server, "admin");
      ASSERT_TRUE(admin);
      ASSERT_TRUE(admin->call(testing::openDocument(killed), 60)->has_ack());
    }
    EXPECT_EQ(decide(*admin, c, killed), offline[c.line - 1])
        << "(d) line " << c.line << ": " << lines[c.line - 1];
  }
  EXPECT_TRUE(sameBytes(exportGlb(*admin, killed), offlineGlb)) << "(d) export";
  EXPECT_EQ(server->stop(), 0);
}

}  // namespace
}  // namespace tessera
