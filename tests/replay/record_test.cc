// Recording a live session (docs/REPLAY.md §2.1): the server's
// AppliedCommand stream, the script lines a recorder makes of it, and the
// real `tessera-replay record` against the real server -- recording a
// multi-editor session, then replaying the recording on a fresh server, ends
// at the original's version and surface hash.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "client/lib/command_feed.h"
#include "client/replay/record.h"
#include "client/replay/script.h"
#include "replay/replay_support.h"

namespace tessera {
namespace {

using replay::ScriptCommand;
using testing::field;
using testing::ReplayServer;
using testing::run;

const std::string kReplay = TESSERA_REPLAY_PATH;

wire::AppliedCommand applied(uint64_t version, uint64_t editId, uint64_t session, const std::string& name,
                             uint64_t timeMs) {
  wire::AppliedCommand a;
  a.set_document_id(1);
  a.set_version(version);
  a.set_edit_id(editId);
  a.set_author_session_id(session);
  a.set_author_name(name);
  a.set_server_time_unix_ms(timeMs);
  return a;
}

wire::AppliedCommand move(uint64_t version, uint64_t editId, uint64_t session, const std::string& name,
                          uint64_t timeMs) {
  wire::AppliedCommand a = applied(version, editId, session, name, timeMs);
  a.mutable_move_vertex()->add_vertex_ids(5);
  a.mutable_move_vertex()->mutable_target()->set_z(0.01);
  a.mutable_move_vertex()->set_mode(wire::MOVE_MODE_OFFSET);
  return a;
}

wire::AppliedCommand undo(uint64_t version, uint64_t target, uint64_t session, const std::string& name,
                          uint64_t timeMs) {
  wire::AppliedCommand a = applied(version, target, session, name, timeMs);
  a.mutable_undo()->set_edit_id(target);
  return a;
}

TEST(RecordScript, ActorsTimesAndUndoTargets) {
  replay::ScriptRecorder r(1000);
  std::vector<ScriptCommand> lines;
  auto add = [&](const wire::AppliedCommand& a) {
    auto c = r.add(a);
    ASSERT_TRUE(c.isOk()) << c.status().message();
    lines.push_back(*c);
  };
  add(move(2, 1, 7, "alice", 1200));  // edit 1 by alice (session 7)
  add(move(3, 2, 8, "alice", 1150));  // another session named alice; the server clock stepped back
  add(move(4, 3, 7, "alice", 1300));  // edit 3 by the first alice
  add(undo(5, 1, 7, "alice", 1400));  // her own edit, two back
  add(undo(6, 2, 7, "alice", 1500));  // the second alice's edit, by the first: absolute
  add(undo(7, 9, 9, "bob", 900));     // before the recording: absolute; time before the start: clamped
  wire::AppliedCommand corner = applied(8, 4, 9, "bob", 1600);
  corner.mutable_set_vertex_type()->set_vertex_id(3);
  corner.mutable_set_vertex_type()->set_type(wire::VERTEX_TYPE_CORNER);
  add(corner);
  wire::AppliedCommand smooth = applied(9, 5, 9, "bob", 1700);
  smooth.mutable_set_vertex_type()->set_vertex_id(3);
  smooth.mutable_set_vertex_type()->set_type(wire::VERTEX_TYPE_SMOOTH);
  add(smooth);
  wire::AppliedCommand tag = applied(10, 6, 9, "bob", 1800);
  tag.mutable_set_interpolation()->set_vertex_id(VertexId(1, 9).packed());
  tag.mutable_set_interpolation()->set_interpolating(true);
  tag.mutable_set_interpolation()->set_tension(2.5);
  add(tag);
  ASSERT_EQ(lines.size(), 9u);
  EXPECT_EQ(lines[0].actor, "alice");
  EXPECT_EQ(lines[1].actor, "alice#2");
  EXPECT_EQ(lines[2].actor, "alice");
  EXPECT_EQ(lines[5].actor, "bob");
  EXPECT_EQ(r.actors(), 3u);
  EXPECT_EQ(lines[0].timeMs, 200);
  EXPECT_EQ(lines[1].timeMs, 200) << "times never go backwards";
  EXPECT_EQ(lines[5].timeMs, 500);
  EXPECT_EQ(lines[3].kind, ScriptCommand::Kind::kUndo);
  EXPECT_EQ(lines[3].edit, -2);
  EXPECT_EQ(lines[4].edit, 2);
  EXPECT_EQ(lines[5].edit, 9);
  EXPECT_EQ(lines[6].kind, ScriptCommand::Kind::kCorner);
  EXPECT_TRUE(std::isinf(lines[6].sharpness));
  EXPECT_EQ(lines[7].sharpness, 0.0f);
  EXPECT_TRUE(lines[0].offset);
  EXPECT_EQ(lines[0].to[2], 0.01);
  // The lines are a valid script.
  std::string text = replay::headerLine({.document = 1, .generator = "test"}) + "\n";
  for (const auto& c : lines) text += replay::commandLine(c) + "\n";
  auto parsed = replay::parseScript(text, "recorded");
  ASSERT_TRUE(parsed.isOk()) << parsed.status().message();
  EXPECT_EQ(parsed->header.generator, "test");
  // An interpolation line reads back as it was recorded.
  EXPECT_NE(
      text.find(R"({"t":800,"actor":"bob","cmd":"interpolate","vertex":"v1:9","on":true,"tension":2.5})"),
      std::string::npos)
      << text;
  const ScriptCommand& back = parsed->commands.back();
  EXPECT_EQ(back.kind, ScriptCommand::Kind::kInterpolate);
  EXPECT_EQ(back.vertices.at(0), VertexId(1, 9).packed());
  EXPECT_TRUE(back.interpolating);
  EXPECT_EQ(back.tension, 2.5);
}

// A batch (tessera remote edit) becomes one line per command, each with its
// own edit id, so a later undo inside or after it finds its target.
TEST(RecordScript, ABatchBecomesOneLinePerCommand) {
  replay::ScriptRecorder r(1000);
  ASSERT_TRUE(r.add(move(2, 1, 7, "alice", 1100)).isOk());
  wire::AppliedCommand batch = applied(3, 12, 7, "alice", 1200);
  auto* commands = batch.mutable_edit_batch()->mutable_commands();
  auto* m = commands->Add()->mutable_move_vertex();
  m->add_vertex_ids(6);
  m->mutable_target()->set_x(0.5);
  m->set_mode(wire::MOVE_MODE_OFFSET);
  commands->Add()->mutable_set_edge_sharpness()->set_edge_id(40);
  commands->Add()->mutable_undo()->set_edit_id(10);  // the batch's own first edit
  for (uint64_t id : {10, 11, 10}) batch.add_edit_ids(id);
  auto lines = r.lines(batch);
  ASSERT_TRUE(lines.isOk()) << lines.status().message();
  ASSERT_EQ(lines->size(), 3u);
  EXPECT_EQ((*lines)[0].kind, ScriptCommand::Kind::kMove);
  EXPECT_EQ((*lines)[0].vertices, std::vector<uint64_t>{6});
  EXPECT_EQ((*lines)[1].kind, ScriptCommand::Kind::kCrease);
  EXPECT_EQ((*lines)[1].edge, 40u);
  EXPECT_EQ((*lines)[2].kind, ScriptCommand::Kind::kUndo);
  EXPECT_EQ((*lines)[2].edit, -2) << "edit 10 is alice's second-latest (1, 10, 11)";
  for (const auto& line : *lines) EXPECT_EQ(line.actor, "alice");

  batch.clear_edit_ids();
  batch.add_edit_ids(10);
  auto mismatched = r.lines(batch);
  ASSERT_FALSE(mismatched.isOk());
  EXPECT_NE(mismatched.status().message().find("version 3"), std::string::npos)
      << mismatched.status().message();
}

// Scripts have no morph keys: an edit of a morph document's key 1 would
// replay onto key 0, so the recorder refuses it by name.
TEST(RecordScript, EditsOfASecondMorphKeyAreRefusedByName) {
  replay::ScriptRecorder r(1000);
  wire::AppliedCommand onKey1 = move(4, 2, 7, "alice", 1100);
  onKey1.mutable_move_vertex()->set_key(1);
  auto refused = r.add(onKey1);
  ASSERT_FALSE(refused.isOk());
  EXPECT_NE(refused.status().message().find("version 4: an edit of morph key 1"), std::string::npos)
      << refused.status().message();
  wire::AppliedCommand undoKey1 = undo(5, 2, 7, "alice", 1200);
  undoKey1.mutable_undo()->set_key(1);
  EXPECT_FALSE(r.add(undoKey1).isOk());
  EXPECT_TRUE(r.add(move(6, 3, 7, "alice", 1300)).isOk()) << "key 0 records as before";
  wire::AppliedCommand key = applied(7, 0, 7, "alice", 1400);
  key.mutable_add_morph_key()->set_document_id(1);
  auto keyRefused = r.add(key);
  ASSERT_FALSE(keyRefused.isOk());
  EXPECT_NE(keyRefused.status().message().find("version 7: a second morph key (AddMorphKey)"),
            std::string::npos)
      << keyRefused.status().message();
}

TEST(RecordScript, LongNamesStayDistinctWithinTheActorLimit) {
  replay::ScriptRecorder r(0);
  const std::string name(128, 'x');
  auto a = r.add(move(2, 1, 1, name, 0));
  auto b = r.add(move(3, 2, 2, name, 0));
  ASSERT_TRUE(a.isOk() && b.isOk());
  EXPECT_EQ(a->actor.size(), 100u);
  EXPECT_LE(b->actor.size(), 100u);
  EXPECT_NE(a->actor, b->actor);
  EXPECT_FALSE(r.add(applied(4, 3, 1, name, 0)).isOk()) << "no command in it";
}

TEST(RecordFeed, CommandsFollowTheStartVersionWithoutHoles) {
  client::CommandFeed feed(1, 4);
  wire::ServerMessage m;
  m.mutable_delta()->set_document_id(1);
  auto none = feed.apply(m);
  ASSERT_TRUE(none.isOk());
  EXPECT_EQ(*none, nullptr);
  *m.mutable_applied_command() = move(5, 1, 7, "a", 0);
  auto first = feed.apply(m);
  ASSERT_TRUE(first.isOk() && *first != nullptr);
  EXPECT_EQ((*first)->version(), 5u);
  m.mutable_applied_command()->set_document_id(2);
  EXPECT_EQ(*feed.apply(m), nullptr) << "another document's";
  *m.mutable_applied_command() = move(7, 2, 7, "a", 0);
  auto hole = feed.apply(m);
  ASSERT_FALSE(hole.isOk());
  EXPECT_EQ(hole.status().message(), "document 1: command of version 7 does not follow version 5");
  EXPECT_EQ(feed.version(), 5u);
  EXPECT_EQ(feed.received(), 1u);
}

// The next message with an AppliedCommand, or none within `seconds`.
std::optional<wire::AppliedCommand> nextCommand(client::Session& s, double seconds) {
  for (;;) {
    auto m = s.receive(seconds);
    if (!m.isOk()) return std::nullopt;
    if (m->has_applied_command()) return m->applied_command();
  }
}

TEST(RecordProtocol, DurableCommandsReachViewersThatAskedAndNothingElse) {
  ReplayServer s;
  testing::startServer(s, "tessera-record-protocol");
  if (HasFatalFailure()) return;
  auto editor = client::Session::connect(s.process->session("ed", testing::kEditorToken));
  auto recorder = client::Session::connect(s.process->session("rec", testing::kViewerToken));
  auto plain = client::Session::connect(s.process->session("plain", testing::kViewerToken));
  ASSERT_TRUE(editor.isOk() && recorder.isOk() && plain.isOk());
  wire::ClientMessage sub = testing::subscribe(s.doc, 1, 2);
  sub.mutable_subscribe()->set_with_commands(true);
  // Not open yet: refused like any subscribe.
  auto early = (*recorder)->call(sub, 10);
  ASSERT_TRUE(early.isOk());
  EXPECT_EQ(early->reject().reason(), wire::REJECT_REASON_NOT_OPEN) << early->DebugString();
  for (auto* session : {&*editor, &*recorder, &*plain})
    ASSERT_TRUE((*session)->call(testing::openDocument(s.doc), 10)->has_ack());
  auto subscribed = (*recorder)->call(sub, 30);
  ASSERT_TRUE(subscribed.isOk() && subscribed->has_ack()) << "a viewer may record";
  EXPECT_EQ(subscribed->ack().version(), 1u);
  ASSERT_TRUE((*plain)->call(testing::subscribe(s.doc, 1, 2), 30)->has_ack());

  const uint64_t v5 = (5ull << 58) | 0, e1 = (1ull << 58) | 5;
  auto moved = (*editor)->call(testing::moveVertex(s.doc, v5, 0, 0, 0.02, wire::MOVE_MODE_OFFSET), 10);
  ASSERT_TRUE(moved.isOk() && moved->has_ack());
  // Refused, and taken back (outside the document's grid): never recorded.
  wire::ClientMessage badUndo;
  badUndo.mutable_undo()->set_document_id(s.doc);
  badUndo.mutable_undo()->set_edit_id(99);
  EXPECT_TRUE((*editor)->call(badUndo, 10)->has_reject());
  EXPECT_EQ((*editor)
                ->call(testing::moveVertex(s.doc, v5, 1e9, 0, 0, wire::MOVE_MODE_OFFSET), 10)
                ->reject()
                .reason(),
            wire::REJECT_REASON_LIMIT_EXCEEDED);
  wire::ClientMessage crease;
  crease.mutable_set_edge_sharpness()->set_document_id(s.doc);
  crease.mutable_set_edge_sharpness()->set_edge_id(e1);
  crease.mutable_set_edge_sharpness()->set_sharpness(2.5f);
  ASSERT_TRUE((*editor)->call(crease, 10)->has_ack());

  auto first = nextCommand(**recorder, 10);
  ASSERT_TRUE(first);
  EXPECT_EQ(first->document_id(), s.doc);
  EXPECT_EQ(first->version(), 2u);
  EXPECT_EQ(first->edit_id(), moved->ack().edit_id());
  EXPECT_EQ(first->author_session_id(), (*editor)->sessionId());
  EXPECT_EQ(first->author_name(), "ed");
  EXPECT_GT(first->server_time_unix_ms(), 1700000000000u);
  ASSERT_TRUE(first->has_move_vertex());
  EXPECT_EQ(first->move_vertex().vertex_ids(0), v5);
  EXPECT_EQ(first->move_vertex().target().z(), 0.02);
  auto second = nextCommand(**recorder, 10);
  ASSERT_TRUE(second);
  EXPECT_EQ(second->version(), 3u) << "the refused and taken-back commands made no version";
  ASSERT_TRUE(second->has_set_edge_sharpness());
  EXPECT_EQ(second->set_edge_sharpness().sharpness(), 2.5f);
  EXPECT_FALSE(nextCommand(**recorder, 0.3)) << "nothing else was applied";
  EXPECT_FALSE(nextCommand(**plain, 0.3)) << "a subscriber that did not ask gets no commands";
  // Subscribing again without with_commands stops them.
  ASSERT_TRUE((*recorder)->call(testing::subscribe(s.doc, 1, 2), 30)->has_ack());
  ASSERT_TRUE(
      (*editor)->call(testing::moveVertex(s.doc, v5, 0, 0, 0.01, wire::MOVE_MODE_OFFSET), 10)->has_ack());
  EXPECT_FALSE(nextCommand(**recorder, 0.3)) << "the recorder asked to stop";
}

TEST(RecordCommand, RefusedRecordingsSayWhy) {
  ReplayServer s;
  testing::startServer(s, "tessera-record-refused");
  if (HasFatalFailure()) return;
  const std::string out = testing::makeTempDir("tessera-record-refused") + "/r.jsonl";
  auto [unknown, unknownCode] = run(
      kReplay + " record" + s.connection("never-granted-token-0123456789") + " --seconds 1 -o " + out, true);
  EXPECT_EQ(unknownCode, 1) << unknown;
  // A token no grant names fails the handshake (docs/PROTOCOL.md §4.1).
  EXPECT_NE(
      unknown.find(
          "record: server refused the handshake (ERROR_CODE_AUTH_FAILED): the access token is not known "
          "to this server"),
      std::string::npos)
      << unknown;
  auto [other, otherCode] =
      run(kReplay + " record --port " + std::to_string(s.process->port()) + " --token " +
              testing::kViewerToken + " --document 7 --seconds 1 -o " + out,
          true);
  EXPECT_EQ(otherCode, 1) << other;
  EXPECT_NE(other.find("no access to document 7"), std::string::npos) << other;
  auto [bounded, boundedCode] =
      run(kReplay + " record" + s.connection(testing::kViewerToken) + " -o " + out, true);
  EXPECT_EQ(boundedCode, 2) << bounded;
  EXPECT_NE(bounded.find("record needs --seconds S or --until-version V"), std::string::npos) << bounded;
  auto [late, lateCode] = run(kReplay + " record" + s.connection(testing::kViewerToken) +
                                  " --until-version 3 --seconds 0.5 -o " + out,
                              true);
  EXPECT_EQ(lateCode, 1) << late;
  EXPECT_NE(late.find("version 3 was not reached within 0.5 s (recorded up to version 1)"), std::string::npos)
      << late;
  EXPECT_EQ(field(late, "commands"), "0") << late;
}

// `tessera-replay record` on `s` until `version`, once it has subscribed.
FILE* startRecorder(const ReplayServer& s, int version, const std::string& script,
                    const std::string& errors) {
  FILE* recorder = popen((kReplay + " record" + s.connection(testing::kViewerToken) + " --until-version " +
                          std::to_string(version) + " --seconds 20 -o " + script + " 2>" + errors)
                             .c_str(),
                         "r");
  char first[256] = {};
  if (recorder == nullptr || fgets(first, sizeof first, recorder) == nullptr) return nullptr;
  EXPECT_EQ(std::string(first), "recording document 1 from version 1\n");
  return recorder;
}

// The recorder's summary, after checking that it ended as asked.
std::string finishRecorder(FILE* recorder, const std::string& errors) {
  std::string summary;
  char buffer[4096];
  for (size_t n; (n = fread(buffer, 1, sizeof buffer, recorder)) > 0;) summary.append(buffer, n);
  const int status = pclose(recorder);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << summary << testing::fileBytes(errors);
  return summary;
}

// Replays the recording on a fresh server: the original's version and hash.
void expectReplayOnFreshServer(const std::string& recorded, const std::string& commands,
                               const std::string& original) {
  ReplayServer fresh;
  testing::startServer(fresh, "tessera-record-fresh");
  if (::testing::Test::HasFatalFailure()) return;
  auto [again, againCode] = run(kReplay + " replay " + recorded + fresh.connection() + " --speed 0");
  EXPECT_EQ(againCode, 0) << again;
  EXPECT_EQ(field(again, "commands"), commands) << again;
  EXPECT_EQ(field(again, "rejected"), "0") << again;
  EXPECT_EQ(field(again, "version"), field(original, "version")) << again;
  EXPECT_EQ(field(again, "surface_hash"), field(original, "surface_hash")) << again;
  EXPECT_FALSE(field(again, "surface_hash").empty());
}

// A script for a second session of `editor-1` (another actor than the
// generated one): a crease, a corner and the undo of that corner, `stepMs`
// apart, then `more` lines.
void writeSecondSession(const std::string& path, int stepMs, const std::vector<std::string>& more) {
  std::ofstream out(path);
  out << "{\"format\":\"tessera-replay\",\"version\":1}\n"
      << "{\"t\":0,\"actor\":\"editor-1\",\"cmd\":\"crease\",\"edge\":\"e1:5\",\"sharpness\":\"inf\"}\n"
      << "{\"t\":" << stepMs
      << ",\"actor\":\"editor-1\",\"cmd\":\"corner\",\"vertex\":\"v0:3\",\"sharpness\":2.5}\n"
      << "{\"t\":" << 2 * stepMs << ",\"actor\":\"editor-1\",\"cmd\":\"undo\",\"edit\":-1}\n";
  for (const std::string& line : more) out << line << "\n";
}

// A recording bounded by time only: the commands before the stop, and the
// recorder's view at the last of them. 4 s leaves room for a slow (ASan)
// build to replay the 20 commands inside it.
TEST(RecordCommand, TimedRecordingEndsAtItsLastCommand) {
  const std::string dir = testing::makeTempDir("tessera-record-timed");
  const std::string script = dir + "/script.jsonl", recorded = dir + "/recorded.jsonl";
  ReplayServer original;
  testing::startServer(original, "tessera-record-timed");
  if (HasFatalFailure()) return;
  ASSERT_EQ(run(kReplay + " generate -o " + script + " --editors 2 --rate 20 --seconds 0.5 --seed 3").second,
            0);
  FILE* recorder = popen((kReplay + " record" + original.connection(testing::kViewerToken) +
                          " --seconds 4 -o " + recorded + " 2>/dev/null")
                             .c_str(),
                         "r");
  char first[256] = {};
  ASSERT_TRUE(recorder != nullptr && fgets(first, sizeof first, recorder) != nullptr);
  auto [replayed, code] = run(kReplay + " replay " + script + original.connection() + " --speed 0");
  ASSERT_EQ(code, 0) << replayed;
  const std::string summary = finishRecorder(recorder, "/dev/null");
  EXPECT_EQ(field(summary, "commands"), "20") << summary;
  EXPECT_EQ(field(summary, "version"), "21") << summary;
  EXPECT_EQ(field(summary, "surface_hash"), field(replayed, "surface_hash")) << summary;
  auto [checked, checkCode] = run(kReplay + " check " + recorded);
  EXPECT_EQ(checked, recorded + ": 20 commands\n");
}

TEST(RecordCommand, RecordingThenReplayingOnAFreshServerGivesTheSameSurface) {
  const std::string dir = testing::makeTempDir("tessera-record-session");
  const std::string generated = dir + "/generated.jsonl", extra = dir + "/extra.jsonl",
                    recorded = dir + "/recorded.jsonl";
  ASSERT_EQ(
      run(kReplay + " generate -o " + generated + " --editors 3 --rate 20 --seconds 1 --seed 42").second, 0);
  // New sessions named like the generated actors (so other actors): undo and
  // redo of their own edits and of another session's, a direct move.
  writeSecondSession(extra, 10,
                     {"{\"t\":30,\"actor\":\"editor-2\",\"cmd\":\"undo\",\"edit\":2}",
                      "{\"t\":40,\"actor\":\"editor-2\",\"cmd\":\"move\",\"vertex\":[\"v1:3\",\"v1:4\"],"
                      "\"mode\":\"direct\",\"to\":[0.5,0.5,1.1]}",
                      "{\"t\":50,\"actor\":\"editor-1\",\"cmd\":\"redo\",\"edit\":-1}"});
  ReplayServer original;
  testing::startServer(original, "tessera-record-original");
  if (HasFatalFailure()) return;
  // The recorder, with a viewer token, until the last version of the session.
  const std::string errors = dir + "/record.err";
  FILE* recorder = startRecorder(original, 67, recorded, errors);
  ASSERT_NE(recorder, nullptr) << "the recorder did not start: " << testing::fileBytes(errors);
  auto [replayed, replayCode] = run(kReplay + " replay " + generated + original.connection() + " --speed 4");
  EXPECT_EQ(replayCode, 0) << replayed;
  EXPECT_EQ(field(replayed, "rejected"), "0") << replayed;
  auto [more, moreCode] = run(kReplay + " replay " + extra + original.connection() + " --speed 0");
  EXPECT_EQ(moreCode, 0) << more;
  EXPECT_EQ(field(more, "rejected"), "0") << more;
  EXPECT_EQ(field(more, "version"), "67") << more;
  const std::string summary = finishRecorder(recorder, errors);
  EXPECT_EQ(field(summary, "commands"), "66") << summary;
  EXPECT_EQ(field(summary, "actors"), "5") << summary;
  EXPECT_EQ(field(summary, "version"), "67") << summary;
  EXPECT_EQ(field(summary, "surface_hash"), field(more, "surface_hash")) << "the recorder's own view";

  auto [checked, checkCode] = run(kReplay + " check " + recorded);
  EXPECT_EQ(checkCode, 0) << checked;
  EXPECT_EQ(checked, recorded + ": 66 commands\n");
  auto script = replay::readScript(recorded);
  ASSERT_TRUE(script.isOk()) << script.status().message();
  EXPECT_EQ(script->header.document, original.doc);
  EXPECT_NE(script->header.generator.find("from version 1"), std::string::npos) << script->header.generator;
  std::set<std::string> actors;
  std::map<std::string, std::vector<int64_t>> undoRedo;  // actor -> edit fields
  for (const ScriptCommand& c : script->commands) {
    actors.insert(c.actor);
    if (c.kind == ScriptCommand::Kind::kUndo || c.kind == ScriptCommand::Kind::kRedo)
      undoRedo[c.actor].push_back(c.edit);
  }
  EXPECT_EQ(actors, (std::set<std::string>{"editor-1", "editor-2", "editor-3", "editor-1#2", "editor-2#2"}));
  EXPECT_EQ(undoRedo["editor-1#2"], (std::vector<int64_t>{-1, -1}));
  EXPECT_EQ(undoRedo["editor-2#2"], (std::vector<int64_t>{2})) << "another session's edit: absolute";
  EXPECT_FALSE(undoRedo["editor-1"].empty()) << "the generated undos";
  for (int64_t edit : undoRedo["editor-1"]) EXPECT_EQ(edit, -1);

  expectReplayOnFreshServer(recorded, "66", more);
}

// Editors at the same time, under the server's order: a replay of the
// recording reaches the very surface the original server shows.
TEST(RecordCommand, ConcurrentEditorsReplayToTheOriginalSurface) {
  const std::string dir = testing::makeTempDir("tessera-record-concurrent");
  const std::string generated = dir + "/generated.jsonl", extra = dir + "/extra.jsonl",
                    recorded = dir + "/recorded.jsonl";
  ASSERT_EQ(run(kReplay + " generate -o " + generated +
                " --editors 4 --rate 20 --seconds 3 --seed 7 --vertex-level 2 --vertex-count 98")
                .second,
            0);
  writeSecondSession(extra, 150,
                     {"{\"t\":450,\"actor\":\"editor-1\",\"cmd\":\"move\",\"vertex\":[\"v1:3\",\"v1:4\"],"
                      "\"mode\":\"direct\",\"to\":[0.5,0.5,1.1]}",
                      "{\"t\":600,\"actor\":\"editor-1\",\"cmd\":\"redo\",\"edit\":-2}"});
  ReplayServer original;
  testing::startServer(original, "tessera-record-concurrent-original");
  if (HasFatalFailure()) return;
  const std::string errors = dir + "/record.err";
  FILE* recorder = startRecorder(original, 246, recorded, errors);
  ASSERT_NE(recorder, nullptr) << "the recorder did not start: " << testing::fileBytes(errors);
  FILE* editors =
      popen((kReplay + " replay " + generated + original.connection() + " --speed 1 2>&1").c_str(), "r");
  ASSERT_NE(editors, nullptr);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  auto [more, moreCode] = run(kReplay + " replay " + extra + original.connection() + " --speed 1");
  EXPECT_EQ(moreCode, 0) << more;
  EXPECT_EQ(field(more, "rejected"), "0") << more;
  std::string replayed;
  char buffer[4096];
  for (size_t n; (n = fread(buffer, 1, sizeof buffer, editors)) > 0;) replayed.append(buffer, n);
  EXPECT_EQ(pclose(editors), 0) << replayed;
  EXPECT_EQ(field(replayed, "rejected"), "0") << replayed;
  const std::string summary = finishRecorder(recorder, errors);
  auto [surface, surfaceCode] =
      run(kReplay + " surface" + original.connection(testing::kViewerToken) + " --profile 2,5,10");
  ASSERT_EQ(surfaceCode, 0) << surface;
  EXPECT_EQ(field(surface, "version"), "246");
  EXPECT_EQ(field(summary, "commands"), "245") << summary;
  EXPECT_EQ(field(summary, "actors"), "5") << summary;
  EXPECT_EQ(field(summary, "surface_hash"), field(surface, "surface_hash")) << summary;
  expectReplayOnFreshServer(recorded, "245", surface);
}

}  // namespace
}  // namespace tessera
