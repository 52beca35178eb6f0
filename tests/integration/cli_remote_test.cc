// `tessera remote` against the real tessera-server: a refused
// token or an absent server is an error; `remote edit` is one atomic
// EditBatch (a bad line 2 leaves the document as it was, a good script lands
// whole as one version, subscribers see it, it survives kill -9 whole);
// `remote create` takes doc new's import options and names the user's file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cli/cli_run.h"
#include "client/lib/document_view.h"
#include "client/lib/session.h"
#include "integration/messages.h"
#include "integration/server_process.h"
#include "protocol/commands.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using testing::ServerProcess;

struct RemoteCli {
  std::string dir;
  std::optional<ServerProcess> server;
  std::string tokenFile;

  explicit RemoteCli(const std::string& name) : dir(testing::makeTempDir(name)) { start(); }

  void start() {
    auto started = ServerProcess::start(dir + "/data");
    ASSERT_TRUE(started.isOk()) << started.status().toString();
    server.emplace(std::move(*started));
    tokenFile = dir + "/admin.token";
    std::ofstream(tokenFile) << server->adminToken() << "\n";
  }
  std::string remote() const {
    return "remote --port " + std::to_string(server->port()) + " --token-file " + tokenFile + " ";
  }
  CliRun run(const std::string& args) const { return runCli(remote() + args); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir + "/" + name) << text;
    return dir + "/" + name;
  }
  uint64_t createCube() const {
    CliRun made = run("create " + testing::sourceTestDataPath("cube.obj") + " --tags " +
                      testing::sourceTestDataPath("cube.tags") + " --max-level 4 --doc-name cube");
    EXPECT_EQ(made.exitCode, 0) << made.err;
    return std::stoull(made.out);
  }
  // "version N" of the document in `remote list`.
  std::string listed(uint64_t doc) const {
    CliRun list = run("list");
    EXPECT_EQ(list.exitCode, 0) << list.err;
    const std::string prefix = std::to_string(doc) + "\tcube\t";
    const size_t at = list.out.find(prefix);
    if (at == std::string::npos) return "";
    return list.out.substr(at + prefix.size(), list.out.find('\n', at) - at - prefix.size());
  }
  std::string exported(uint64_t doc, const std::string& name) const {
    CliRun r = run("export " + std::to_string(doc) + " --level 3 --limit -o " + dir + "/" + name);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return readAll(dir + "/" + name);
  }
};

TEST(CliRemote, WrongTokenAndNoServerAreErrors) {
  RemoteCli f("tessera-cli-auth");
  const std::string wrong =
      "remote --port " + std::to_string(f.server->port()) + " --token WRONG-TOKEN-0123456789 ";
  const std::string script = f.write("one.txt", "offset v1:3 by 0 0 0.01\n");
  for (const std::string& command : {std::string("list"), std::string("stats"), "edit 1 --script " + script,
                                     "create " + testing::sourceTestDataPath("cube.obj")}) {
    CliRun r = runCli(wrong + command);
    EXPECT_EQ(r.exitCode, 1) << command;
    EXPECT_TRUE(r.out.empty()) << command << ": " << r.out;
    EXPECT_NE(r.err.find("authentication failed"), std::string::npos) << command << ": " << r.err;
    EXPECT_NE(r.err.find("does not know this token"), std::string::npos) << r.err;
  }
  // No token at all: the hint names the options.
  CliRun none = runCli("remote --port " + std::to_string(f.server->port()) + " list");
  EXPECT_EQ(none.exitCode, 1);
  EXPECT_TRUE(none.out.empty()) << none.out;
  EXPECT_NE(none.err.find("no token was given: give --token or --token-file"), std::string::npos) << none.err;
  // The same token file form, and the token in the option after the command.
  CliRun after =
      runCli("remote list --port " + std::to_string(f.server->port()) + " --token WRONG-TOKEN-0123456789");
  EXPECT_EQ(after.exitCode, 1);
  EXPECT_NE(after.err.find("authentication failed"), std::string::npos) << after.err;
  const uint16_t port = f.server->port();
  EXPECT_EQ(f.server->stop(), 0);
  CliRun gone = runCli("remote --port " + std::to_string(port) + " --token-file " + f.tokenFile + " list");
  EXPECT_EQ(gone.exitCode, 1);
  EXPECT_NE(gone.err.find("cannot reach tessera-server at 127.0.0.1:" + std::to_string(port)),
            std::string::npos)
      << gone.err;
  CliRun noFile = runCli("remote --port " + std::to_string(port) + " --token-file " + f.dir + "/none list");
  EXPECT_EQ(noFile.exitCode, 2);
  EXPECT_NE(noFile.err.find("--token-file"), std::string::npos) << noFile.err;
}

// A script whose line 2 is bad: nothing of it lands, the line is named; the
// subscriber sees nothing. The good script then lands whole as one version.
TEST(CliRemote, EditScriptIsAtomic) {
  RemoteCli f("tessera-cli-batch");
  const uint64_t doc = f.createCube();
  ASSERT_EQ(f.listed(doc), "version 1");
  const std::string before = f.exported(doc, "before.glb");

  auto watcher = client::Session::connect(f.server->session("watcher", f.server->adminToken()));
  ASSERT_TRUE(watcher.isOk()) << watcher.status().toString();
  ASSERT_TRUE((*watcher)->call(testing::openDocument(doc), 20).isOk());
  wire::ClientMessage sub = testing::subscribe(doc, 1, 3);
  sub.mutable_subscribe()->set_with_commands(true);
  auto subscribed = (*watcher)->call(sub, 20);
  ASSERT_TRUE(subscribed.isOk() && subscribed->has_ack()) << subscribed.status().toString();
  client::DocumentView view(doc);
  for (int parts = 0; !view.ready() && parts < 100; ++parts) {
    auto m = (*watcher)->receive(10);
    ASSERT_TRUE(m.isOk()) << m.status().toString();
    ASSERT_TRUE(view.apply(*m).isOk());
  }
  const uint64_t hashBefore = view.surfaceHash();

  const std::string bad = f.write("bad.txt", "offset v1:3 by 0 0 0.1\nmove v9:1 to 1 2 3\ncrease e1:4 2\n");
  CliRun refused = f.run("edit " + std::to_string(doc) + " --script " + bad);
  EXPECT_EQ(refused.exitCode, 1);
  EXPECT_NE(refused.err.find("bad.txt:2: REJECT_REASON_NOT_FOUND"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("nothing of the batch was applied"), std::string::npos) << refused.err;
  EXPECT_EQ(f.listed(doc), "version 1");
  EXPECT_EQ(f.exported(doc, "after-bad.glb"), before);
  // Line 3 of another script refers to an edit the batch itself would make
  // and undo twice: refused at line 3, and line 1 and 2 are taken back.
  const std::string twice = f.write("twice.txt", "offset v2:5 by 0 0 0.05\nundo 1\nundo 1\n");
  CliRun refused2 = f.run("edit " + std::to_string(doc) + " --script " + twice);
  EXPECT_EQ(refused2.exitCode, 1);
  EXPECT_NE(refused2.err.find("twice.txt:3: REJECT_REASON_INVALID_STATE"), std::string::npos) << refused2.err;
  EXPECT_EQ(f.listed(doc), "version 1");
  EXPECT_EQ(f.exported(doc, "after-twice.glb"), before);

  const std::string good = f.write("good.txt",
                                   "# three lines, one version\noffset v1:3 by 0 0 0.1\n"
                                   "crease e1:4 2\ncorner v2:5 inf\n");
  CliRun applied = f.run("edit " + std::to_string(doc) + " --script " + good);
  ASSERT_EQ(applied.exitCode, 0) << applied.err;
  EXPECT_NE(applied.out.find("good.txt:2: edit 1\n"), std::string::npos) << applied.out;
  EXPECT_NE(applied.out.find("good.txt:4: edit 3\n"), std::string::npos) << applied.out;
  EXPECT_NE(applied.out.find("applied 3 commands to document " + std::to_string(doc) + " as version 2"),
            std::string::npos)
      << applied.out;
  EXPECT_EQ(f.listed(doc), "version 2");
  const std::string after = f.exported(doc, "after-good.glb");
  EXPECT_NE(after, before);

  // The subscriber saw nothing of the refused scripts: the next delta is the
  // batch, 1 -> 2, and the recorder gets the whole batch as one command.
  bool sawDelta = false, sawCommand = false;
  for (int i = 0; i < 50 && !(sawDelta && sawCommand); ++i) {
    auto m = (*watcher)->receive(10);
    ASSERT_TRUE(m.isOk()) << m.status().toString();
    if (m->has_delta()) {
      EXPECT_EQ(m->delta().from_version(), 1u);
      EXPECT_EQ(m->delta().to_version(), 2u);
      ASSERT_TRUE(view.apply(*m).isOk());
      sawDelta = true;
    }
    if (m->has_applied_command()) {
      EXPECT_EQ(m->applied_command().version(), 2u);
      ASSERT_TRUE(m->applied_command().has_edit_batch());
      EXPECT_EQ(m->applied_command().edit_batch().commands_size(), 3);
      EXPECT_EQ(m->applied_command().edit_id(), 3u);
      sawCommand = true;
    }
  }
  EXPECT_TRUE(sawDelta && sawCommand);
  EXPECT_NE(view.surfaceHash(), hashBefore);

  // Durable whole: after kill -9 and a restart on the same store, version 2
  // and the same surface.
  f.server->kill9();
  f.start();
  EXPECT_EQ(f.listed(doc), "version 2");
  EXPECT_EQ(f.exported(doc, "after-restart.glb"), after);
  // `remove` is local only: refused before anything is sent.
  const std::string removing = f.write("remove.txt", "offset v1:3 by 0 0 0.1\nremove 1\n");
  CliRun removed = f.run("edit " + std::to_string(doc) + " --script " + removing);
  EXPECT_EQ(removed.exitCode, 1);
  EXPECT_NE(removed.err.find("remove.txt:2: remove is local only"), std::string::npos) << removed.err;
  EXPECT_EQ(f.listed(doc), "version 2");
}

// Above kMaxEditBatchCommands: the CLI refuses before sending, and the
// server refuses such a batch (LIMIT_EXCEEDED) before applying anything.
TEST(CliRemote, BatchSizeIsBounded) {
  RemoteCli f("tessera-cli-bound");
  const uint64_t doc = f.createCube();
  std::string text;
  for (int i = 0; i <= kMaxEditBatchCommands; ++i) text += "offset v1:3 by 0 0 0.0001\n";
  CliRun r = f.run("edit " + std::to_string(doc) + " --script " + f.write("long.txt", text));
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("1025 commands, above the server's limit of 1024"), std::string::npos) << r.err;

  auto s = client::Session::connect(f.server->session("big", f.server->adminToken()));
  ASSERT_TRUE(s.isOk());
  ASSERT_TRUE((*s)->call(testing::openDocument(doc), 20).isOk());
  wire::ClientMessage batch;
  batch.mutable_edit_batch()->set_document_id(doc);
  for (int i = 0; i <= kMaxEditBatchCommands; ++i) {
    auto* move = batch.mutable_edit_batch()->add_commands()->mutable_move_vertex();
    move->add_vertex_ids(VertexId(1, 3).packed());
    move->mutable_target()->set_z(0.0001);
    move->set_mode(wire::MOVE_MODE_OFFSET);
  }
  auto reply = (*s)->call(batch, 20);
  ASSERT_TRUE(reply.isOk()) << reply.status().toString();
  ASSERT_TRUE(reply->has_reject());
  EXPECT_EQ(reply->reject().reason(), wire::REJECT_REASON_LIMIT_EXCEEDED);
  EXPECT_NE(reply->reject().message().find("above the limit of 1024"), std::string::npos);
  EXPECT_EQ(f.listed(doc), "version 1");
  // Exactly the limit is accepted, as one version.
  batch.mutable_edit_batch()->mutable_commands()->RemoveLast();
  auto accepted = (*s)->call(batch, 60);
  ASSERT_TRUE(accepted.isOk()) << accepted.status().toString();
  ASSERT_TRUE(accepted->has_ack()) << accepted->DebugString();
  EXPECT_EQ(accepted->ack().edit_ids_size(), kMaxEditBatchCommands);
  EXPECT_EQ(f.listed(doc), "version 2");
}

// remote create has doc new's import options and scheme choice, and its
// errors name the user's file, never a server path.
TEST(CliRemote, CreateTakesImportOptionsAndNamesTheUsersFile) {
  RemoteCli f("tessera-cli-create");
  const std::string quads = testing::sourceTestDataPath("good/cube_quads.obj");
  CliRun catmark = f.run("create " + quads + " --doc-name cc");
  ASSERT_EQ(catmark.exitCode, 0) << catmark.err;
  EXPECT_NE(catmark.err.find(quads + ": faces that are not triangles: a catmull-clark document"),
            std::string::npos)
      << catmark.err;
  CliRun refused = f.run("create " + quads + " --scheme loop");
  EXPECT_EQ(refused.exitCode, 1);
  EXPECT_NE(refused.err.find(quads), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("--triangulate"), std::string::npos) << refused.err;
  EXPECT_EQ(refused.err.find("tessera-import"), std::string::npos) << refused.err;
  CliRun made = f.run("create " + quads +
                      " --triangulate --crease-method chaikin --boundary edge-and-corner "
                      "--max-level 3 --doc-name quads");
  ASSERT_EQ(made.exitCode, 0) << made.err;
  const std::string badTags = f.write("bad.tags", "crease 0 1 inf\ncrease 0 99 2\n");
  CliRun tags = f.run("create " + testing::sourceTestDataPath("cube.obj") + " --tags " + badTags);
  EXPECT_EQ(tags.exitCode, 1);
  EXPECT_NE(tags.err.find("bad.tags:2"), std::string::npos) << tags.err;
  CliRun truncated = f.run("create " + f.write("broken.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n"));
  EXPECT_EQ(truncated.exitCode, 1);
  EXPECT_NE(truncated.err.find("broken.obj"), std::string::npos) << truncated.err;
  // A Draco GLB is a mesh like any other.
  CliRun draco = runCli("refine " + testing::sourceTestDataPath("cube.obj") + " --level 1 --draco -o " +
                        f.dir + "/d.glb");
  ASSERT_EQ(draco.exitCode, 0) << draco.err;
  CliRun fromDraco = f.run("create " + f.dir + "/d.glb");
  EXPECT_EQ(fromDraco.exitCode, 0) << fromDraco.err;
}

// The server imports with --drop-unused and --crease-angle (docs/FORMATS.md):
// tags keep the file's numbers, and the Ack says what the import changed.
TEST(CliRemote, CreateDropsUnusedVerticesAndCreasesByAngle) {
  RemoteCli f("tessera-cli-create-options");
  const std::string mesh = f.write("unused.obj",
                                   "v 0 0 0\nv 1 0 0\nv 7 7 7\nv 0 1 0\nv 0 0 1\n"
                                   "f 1 4 2\nf 1 2 5\nf 2 4 5\nf 1 5 4\n");
  CliRun refused = f.run("create " + mesh);
  EXPECT_EQ(refused.exitCode, 1);
  EXPECT_NE(refused.err.find("unused.obj: vertex 2 (7, 7, 7): not used by any face"), std::string::npos)
      << refused.err;
  EXPECT_NE(refused.err.find("--drop-unused"), std::string::npos) << refused.err;
  const std::string onDropped = f.write("dropped.tags", "corner 2 inf\n");
  CliRun badTag = f.run("create " + mesh + " --drop-unused --tags " + onDropped);
  EXPECT_EQ(badTag.exitCode, 1);
  EXPECT_NE(badTag.err.find("dropped.tags:1: corner 2: vertex 2 was dropped"), std::string::npos)
      << badTag.err;
  CliRun made = f.run("create " + mesh + " --drop-unused --tags " + f.write("ok.tags", "crease 3 4 inf\n"));
  ASSERT_EQ(made.exitCode, 0) << made.err;
  EXPECT_NE(made.err.find("tessera remote create: " + mesh + ": dropped 1 unused vertex (--drop-unused)"),
            std::string::npos)
      << made.err;
  const std::string quads = testing::sourceTestDataPath("good/cube_quads.obj");
  CliRun creased = f.run("create " + quads + " --triangulate --crease-angle 30");
  ASSERT_EQ(creased.exitCode, 0) << creased.err;
  EXPECT_NE(creased.err.find("creased 12 edges sharper than 30 degrees (--crease-angle)"), std::string::npos)
      << creased.err;
  CliRun badAngle = f.run("create " + quads + " --triangulate --crease-angle 181");
  EXPECT_EQ(badAngle.exitCode, 2);
  EXPECT_NE(badAngle.err.find("--crease-angle"), std::string::npos) << badAngle.err;
}

// Stats for people: no exponents, units on bytes, rates and milliseconds.
TEST(CliRemote, StatsArePrintedForPeople) {
  RemoteCli f("tessera-cli-stats");
  f.createCube();
  CliRun r = f.run("stats");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(r.out.find("e+"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("e-"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("uptime_seconds"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" B\n"), std::string::npos) << r.out;   // bytes_sent
  EXPECT_NE(r.out.find(" ms\n"), std::string::npos) << r.out;  // *_ms
  EXPECT_NE(r.out.find("/s\n"), std::string::npos) << r.out;   // *_per_second
}

}  // namespace
}  // namespace tessera
