// Failover (docs/CLUSTER.md "Failover"): the owning node is killed (kill -9) or paused past
// its lease during an edit storm. A surviving node takes the document over
// from JetStream within a bounded time, every acknowledged edit is in the
// journal exactly once, an old owner that wakes up cannot append, and every
// viewer converges to the surface the journal replays to.
#include <gtest/gtest.h>

#include <signal.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <future>
#include <map>
#include <mutex>
#include <optional>
#include <random>
#include <span>
#include <thread>

#include "cluster/cluster_run.h"
#include "core/document/document.h"
#include "core/hierarchy/ids.h"
#include "core/io/mesh_import.h"
#include "core/io/tag_file.h"
#include "integration/messages.h"
#include "server/cluster/nats_store.h"
#include "server/document/journal_entry.h"
#include "support/test_meshes.h"

namespace tessera {
namespace {

using client::DocumentView;
using client::Session;
using testing::ClusterRun;
using Clock = std::chrono::steady_clock;

// What the editors of a storm were told, per command.
struct StormLog {
  std::mutex mutex;
  std::map<uint64_t, std::string> acked;  // version -> author
  std::map<std::string, int> unknown;     // author -> commands with no answer in time
  std::map<std::string, int> refused;     // author -> Rejects that say the command was not applied
  // When each acknowledged command was sent, and when its Ack arrived.
  std::vector<std::pair<Clock::time_point, Clock::time_point>> ackTimes;

  void ack(uint64_t version, const std::string& author, Clock::time_point sent = Clock::now()) {
    std::lock_guard<std::mutex> lock(mutex);
    EXPECT_TRUE(acked.emplace(version, author).second) << "version " << version << " acknowledged twice";
    ackTimes.emplace_back(sent, Clock::now());
  }
  size_t ackedCount() {
    std::lock_guard<std::mutex> lock(mutex);
    return acked.size();
  }
};

// One editor on `node`, sending moves one at a time until `stop`.
void editLoop(ClusterRun& run, int node, uint64_t doc, int seed, StormLog& log, std::atomic<bool>& stop) {
  const std::string author = "editor@" + run.nodeName(node);
  auto session = Session::connect(run.session(node, author, testing::kEditorToken));
  ASSERT_TRUE(session.isOk()) << session.status().message();
  auto opened = (*session)->call(testing::openDocument(doc), 30);
  ASSERT_TRUE(opened.isOk() && opened->has_ack());
  std::mt19937 rng(static_cast<uint32_t>(seed));
  while (!stop.load()) {
    // Every command is answered: by its owner, or, when the owner died
    // before answering, by the next owner from the journal (Ack or Reject).
    const auto sent = Clock::now();
    auto reply = (*session)->call(testing::smallMove(doc, rng), 15);
    if (!reply.isOk()) {
      std::lock_guard<std::mutex> lock(log.mutex);
      if (log.unknown[author]++ < 2)
        std::printf("%s: no answer: %s\n", author.c_str(), reply.status().message().c_str());
      continue;
    }
    if (reply->has_ack()) {
      log.ack(reply->ack().version(), author, sent);
    } else if (reply->reject().message().find("may be lost") != std::string::npos) {
      // An answer that does not decide: counted as unknown.
      std::lock_guard<std::mutex> lock(log.mutex);
      if (log.unknown[author]++ < 2)
        std::printf("%s: an answer that does not decide: %s\n", author.c_str(),
                    reply->ShortDebugString().c_str());
    } else {
      std::lock_guard<std::mutex> lock(log.mutex);
      if (log.refused[author]++ < 2)
        std::printf("%s refused: %s\n", author.c_str(), reply->ShortDebugString().c_str());
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }
}

// Every acknowledged version holds its editor's entry; an entry nobody was
// told of comes from a command whose outcome its editor never learned.
void expectJournalHoldsExactlyTheAcknowledged(const testing::JournalState& journal, StormLog& log) {
  std::lock_guard<std::mutex> lock(log.mutex);
  std::map<std::string, int> unacknowledged;
  for (size_t i = 0; i < journal.entries.size(); ++i) {
    const uint64_t version = i + 2;  // entry 1 makes version 2
    auto it = log.acked.find(version);
    if (it != log.acked.end()) {
      EXPECT_EQ(journal.entries[i].author, it->second) << "version " << version;
    } else {
      ++unacknowledged[journal.entries[i].author];
    }
  }
  for (const auto& [version, author] : log.acked) {
    EXPECT_LE(version, journal.version) << "acknowledged version " << version << " is not in the journal";
  }
  for (const auto& [author, n] : unacknowledged) {
    EXPECT_LE(n, log.unknown[author]) << author << " has " << n << " journaled edits it was never told of";
  }
}

void waitForAcks(StormLog& log, size_t count, std::chrono::seconds limit) {
  const auto deadline = Clock::now() + limit;
  while (log.ackedCount() < count && Clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
}

TEST(ClusterFailover, OwnerKilledDuringAStormThenANatsServerKilled) {
  auto run = ClusterRun::start(3);
  ASSERT_TRUE(run.isOk()) << run.status().message();
  ClusterRun& c = **run;
  auto doc = c.createCube();
  ASSERT_TRUE(doc.isOk()) << doc.status().message();
  testing::ClusterViewer onOwner = testing::viewerOn(c, 0, *doc);  // node 0 opens first: it owns the document
  std::vector<testing::ClusterViewer> viewers;
  viewers.push_back(testing::viewerOn(c, 1, *doc));
  viewers.push_back(testing::viewerOn(c, 2, *doc));
  for (const auto* v : {&onOwner, &viewers[0], &viewers[1]}) ASSERT_TRUE(v->session) << v->error;

  StormLog log;
  std::atomic<bool> stop{false};
  std::thread a(editLoop, std::ref(c), 1, *doc, 1, std::ref(log), std::ref(stop));
  std::thread b(editLoop, std::ref(c), 2, *doc, 2, std::ref(log), std::ref(stop));
  waitForAcks(log, 20, std::chrono::seconds(30));
  ASSERT_GE(log.ackedCount(), 20u);

  c.nodes[0]->kill9();
  const auto killed = Clock::now();
  const size_t ackedAtKill = log.ackedCount();
  waitForAcks(log, ackedAtKill + 20, std::chrono::seconds(30));
  ASSERT_GE(log.ackedCount(), ackedAtKill + 20) << "no survivor took the document over";
  // Only edits sent after the kill: an Ack the owner wrote just before it
  // died may arrive after the kill and would measure nothing.
  Clock::time_point firstAfter = Clock::now();
  {
    std::lock_guard<std::mutex> lock(log.mutex);
    for (const auto& [sent, received] : log.ackTimes) {
      if (sent > killed) firstAfter = std::min(firstAfter, received);
    }
  }
  const double takeover = std::chrono::duration<double>(firstAfter - killed).count();
  std::printf("kill -9 of the owner to the first Ack of an edit sent after it: %.2f s (lease 1.5 s)\n",
              takeover);
  EXPECT_LT(takeover, 15.0);

  // One NATS server of three dies: JetStream keeps its quorum.
  c.nats.kill9(0);
  const size_t ackedAtNatsKill = log.ackedCount();
  waitForAcks(log, ackedAtNatsKill + 20, std::chrono::seconds(40));
  EXPECT_GE(log.ackedCount(), ackedAtNatsKill + 20) << "edits stopped after one NATS server died";
  stop = true;
  a.join();
  b.join();

  auto journal = testing::journalState(c.nats, *doc);
  ASSERT_TRUE(journal.isOk()) << journal.status().message();
  expectJournalHoldsExactlyTheAcknowledged(*journal, log);
  for (auto& v : viewers) {
    ASSERT_TRUE(testing::followUntil(*v.session, *v.view, journal->version, 30));
    EXPECT_EQ(v.view->version(), journal->version);
    EXPECT_EQ(v.view->surfaceHash(), journal->surfaceHash);
  }
  std::printf(
      "storm: %zu acknowledged, %d + %d refused, %d + %d without an answer, journal at version %llu\n",
      log.acked.size(), log.refused["editor@node1"], log.refused["editor@node2"], log.unknown["editor@node1"],
      log.unknown["editor@node2"], static_cast<unsigned long long>(journal->version));
  // Every command is answered, and every answer decides: an Ack (in the
  // journal) or a Reject saying it was not applied, also for a journal
  // write JetStream did not answer in time (the reloaded journal decides).
  EXPECT_EQ(log.unknown["editor@node1"] + log.unknown["editor@node2"], 0);
  EXPECT_EQ(journal->entries.size(), log.acked.size()) << "the journal holds an edit nobody was told of";
}

// Split brain: the owner is paused (SIGSTOP) past its lease while an edit
// sent to it waits in its socket, another node takes over and edits, then
// the old owner wakes (SIGCONT) still believing it owns the document. Its
// append is refused by JetStream's expected-sequence check, its edit is not
// acknowledged, its clients are moved to the new owner, and no acknowledged
// edit is lost or doubled.
TEST(ClusterFailover, APausedOwnerWakesUpAndCannotAppend) {
  auto run = ClusterRun::start(2);
  ASSERT_TRUE(run.isOk()) << run.status().message();
  ClusterRun& c = **run;
  auto doc = c.createCube();
  ASSERT_TRUE(doc.isOk()) << doc.status().message();
  testing::ClusterViewer onOld = testing::viewerOn(c, 0, *doc);  // node 0 owns the document
  testing::ClusterViewer onNew = testing::viewerOn(c, 1, *doc);
  for (const auto* v : {&onOld, &onNew}) ASSERT_TRUE(v->session) << v->error;
  auto stale = Session::connect(c.session(0, "editor@node0", testing::kEditorToken));
  auto other = Session::connect(c.session(1, "editor@node1", testing::kEditorToken));
  ASSERT_TRUE(stale.isOk() && other.isOk());
  for (Session* s : {stale->get(), other->get()})
    ASSERT_TRUE(s->call(testing::openDocument(*doc), 30)->has_ack());
  std::mt19937 rng(5);
  StormLog log;
  for (int i = 0; i < 5; ++i) {
    auto r = (*stale)->call(testing::smallMove(*doc, rng), 10);
    ASSERT_TRUE(r.isOk() && r->has_ack());
    log.ack(r->ack().version(), "editor@node0");
  }

  ::kill(c.nodes[0]->pid(), SIGSTOP);
  auto pending = (*stale)->send(testing::smallMove(*doc, rng));  // waits in node 0's socket
  ASSERT_TRUE(pending.isOk());
  // Node 1 sees the lease run out and takes the document over.
  int ackedByNew = 0;
  const auto deadline = Clock::now() + std::chrono::seconds(20);
  while (ackedByNew < 10 && Clock::now() < deadline) {
    auto r = (*other)->call(testing::smallMove(*doc, rng), 3);
    if (r.isOk() && r->has_ack()) {
      log.ack(r->ack().version(), "editor@node1");
      ++ackedByNew;
    }
  }
  ASSERT_EQ(ackedByNew, 10) << "node 1 did not take the document over from the paused node 0";

  ::kill(c.nodes[0]->pid(), SIGCONT);
  // The edit node 0 held is never acknowledged by node 0's stale host. It
  // is either refused or, once node 0 moved its sessions, applied by node 1.
  bool answered = false;
  for (int i = 0; i < 40 && !answered; ++i) {
    auto m = (*stale)->receive(0.5);
    if (!m.isOk()) continue;
    if (m->has_ack() && m->ack().client_seq() == *pending) {
      log.ack(m->ack().version(), "editor@node0");
      answered = true;
    } else if (m->has_reject() && m->reject().client_seq() == *pending) {
      std::printf("the paused owner's edit: %s\n", m->reject().message().c_str());
      answered = true;
    } else if (m->has_error()) {
      std::printf("node 0 tells its editor: %s\n", m->error().message().c_str());
    }
  }
  EXPECT_TRUE(answered) << "the edit sent to the paused owner got no answer";
  // Moved to node 1, node 0's editor edits again. Until node 0's monitor
  // has seen the lost lease and moved the session (a lease period, longer
  // on a loaded machine), its stale host refuses at once: the attempts are
  // bounded in time, not in count, which 20 instant refusals once used up.
  std::optional<uint64_t> againVersion;
  const auto handover = Clock::now() + std::chrono::seconds(20);
  while (!againVersion && Clock::now() < handover) {
    auto r = (*stale)->call(testing::smallMove(*doc, rng), 3);
    if (r.isOk() && r->has_ack()) {
      againVersion = r->ack().version();
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
  }
  ASSERT_TRUE(againVersion.has_value()) << "node 0's editor was not handed over";
  log.ack(*againVersion, "editor@node0");

  auto journal = testing::journalState(c.nats, *doc);
  ASSERT_TRUE(journal.isOk()) << journal.status().message();
  {
    std::lock_guard<std::mutex> lock(log.mutex);
    log.unknown["editor@node0"] = answered ? 0 : 1;
  }
  expectJournalHoldsExactlyTheAcknowledged(*journal, log);
  EXPECT_EQ(journal->version, 1 + log.acked.size()) << "the journal holds an edit nobody was told of";
  for (testing::ClusterViewer* v : {&onOld, &onNew}) {
    ASSERT_TRUE(testing::followUntil(*v->session, *v->view, journal->version, 30));
    EXPECT_EQ(v->view->surfaceHash(), journal->surfaceHash);
  }
}

// The owner journaled a command (JetStream acknowledged it) and died before
// its Ack left: the next owner finds the command in the journal, by its
// author's session and client_seq, and sends the Ack its author never got.
// Here the test plays the dying owner: node 0 is paused with the command
// in its inbox, the test appends the entry node 0 would have appended,
// then kills node 0.
TEST(ClusterFailover, ACommandJournaledJustBeforeItsOwnerDiedIsAcknowledgedByTheNext) {
  auto run = ClusterRun::start(2);
  ASSERT_TRUE(run.isOk()) << run.status().message();
  ClusterRun& c = **run;
  auto doc = c.createCube();
  ASSERT_TRUE(doc.isOk()) << doc.status().message();
  testing::ClusterViewer onOwner = testing::viewerOn(c, 0, *doc);  // node 0 owns the document
  testing::ClusterViewer onOther = testing::viewerOn(c, 1, *doc);
  for (const auto* v : {&onOwner, &onOther}) ASSERT_TRUE(v->session) << v->error;
  auto editor = Session::connect(c.session(1, "editor@node1", testing::kEditorToken));
  ASSERT_TRUE(editor.isOk());
  ASSERT_TRUE((*editor)->call(testing::openDocument(*doc), 30)->has_ack());

  ::kill(c.nodes[0]->pid(), SIGSTOP);
  const VertexId vertex(1, 5);
  auto seq = (*editor)->send(testing::moveVertex(*doc, vertex.packed(), 0, 0, 0.02, wire::MOVE_MODE_OFFSET));
  ASSERT_TRUE(seq.isOk());
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // node 1 forwarded it to the paused node 0

  // What node 0 would have journaled: the same move as edit 1 of the cube.
  auto mesh = importMesh(testing::sourceTestDataPath("cube.obj"));
  ASSERT_TRUE(mesh.isOk());
  ASSERT_TRUE(applyTagFile(testing::sourceTestDataPath("cube.tags"), *mesh).isOk());
  auto local = Document::create(*mesh, {.maxLevel = testing::kClusterMaxLevel});
  ASSERT_TRUE(local.isOk());
  ASSERT_TRUE(local->moveBy(std::span(&vertex, 1), Vec3(0, 0, 0.02)).isOk());
  server::JournalEntry entry;
  entry.kind = server::JournalEntry::Kind::kEdit;
  entry.edit = local->edits().back();
  cluster::NatsStoreOptions options;
  options.link.urls = *cluster::parseNatsUrls(c.nats.urls());
  options.replicas = 3;
  auto store = cluster::NatsStore::open(options);
  ASSERT_TRUE(store.isOk()) << store.status().message();
  auto promise = std::make_shared<std::promise<Status>>();
  (*store)->appendFrom(store::DocumentId{*doc}, 1, "editor@node1", (*editor)->sessionId(), *seq,
                       server::encodeJournalEntry(entry), [promise](Status s) { promise->set_value(s); });
  const Status appended = promise->get_future().get();
  ASSERT_TRUE(appended.isOk()) << appended.message();
  c.nodes[0]->kill9();

  // Node 1 takes the document over and answers the command from the journal.
  std::optional<wire::ServerMessage> answer;
  for (int i = 0; i < 60 && !answer; ++i) {
    auto m = (*editor)->receive(0.5);
    if (m.isOk() && ((m->has_ack() && m->ack().client_seq() == *seq) ||
                     (m->has_reject() && m->reject().client_seq() == *seq))) {
      answer = *m;
    }
  }
  ASSERT_TRUE(answer.has_value()) << "the command never got an answer";
  ASSERT_TRUE(answer->has_ack()) << answer->DebugString();
  EXPECT_EQ(answer->ack().version(), 2u);
  EXPECT_EQ(answer->ack().edit_id(), entry.edit.id.value);
  auto journal = testing::journalState(c.nats, *doc);
  ASSERT_TRUE(journal.isOk()) << journal.status().message();
  EXPECT_EQ(journal->version, 2u);  // applied once: node 0 never appended it too
  ASSERT_TRUE(testing::followUntil(*onOther.session, *onOther.view, 2, 30));
  EXPECT_EQ(onOther.view->surfaceHash(), journal->surfaceHash);
}

// Not dead, only slow: a node that does not renew its TESSERA_ALIVE key in
// time (paused here past the key's lifetime, as a busy machine can delay
// its monitor) has its sessions removed by the owner as if it had died.
// Once it runs again, the owner's NotOwner makes it move them back, so its
// viewer converges instead of waiting for deltas that no longer come.
TEST(ClusterFailover, ANodeTakenForDeadGetsItsViewerBackWhenItRunsAgain) {
  constexpr int kLeaseMs = 1500;
  auto run = ClusterRun::start(2, kLeaseMs);
  ASSERT_TRUE(run.isOk()) << run.status().message();
  ClusterRun& c = **run;
  auto doc = c.createCube();
  ASSERT_TRUE(doc.isOk()) << doc.status().message();
  testing::ClusterViewer onOwner = testing::viewerOn(c, 0, *doc);  // node 0 opens first: it owns the document
  testing::ClusterViewer onSlow = testing::viewerOn(c, 1, *doc);
  for (const auto* v : {&onOwner, &onSlow}) ASSERT_TRUE(v->session) << v->error;
  auto editor = Session::connect(c.session(0, "editor@node0", testing::kEditorToken));
  ASSERT_TRUE(editor.isOk());
  ASSERT_TRUE((*editor)->call(testing::openDocument(*doc), 30)->has_ack());
  std::mt19937 rng(11);
  auto edit = [&] {
    auto r = (*editor)->call(testing::smallMove(*doc, rng), 10);
    return r.isOk() && r->has_ack();
  };
  ASSERT_TRUE(edit());

  // Past the alive key's lifetime (three lease times) and the owner's next
  // check of it; node 1 holds no lease, so nothing else moves.
  ::kill(c.nodes[1]->pid(), SIGSTOP);
  for (int i = 0; i < 4; ++i) {
    ASSERT_TRUE(edit());
    std::this_thread::sleep_for(std::chrono::milliseconds(kLeaseMs));
  }
  ::kill(c.nodes[1]->pid(), SIGCONT);
  ASSERT_TRUE(edit());

  auto journal = testing::journalState(c.nats, *doc);
  ASSERT_TRUE(journal.isOk()) << journal.status().message();
  for (testing::ClusterViewer* v : {&onOwner, &onSlow}) {
    ASSERT_TRUE(testing::followUntil(*v->session, *v->view, journal->version, 30));
    EXPECT_EQ(v->view->surfaceHash(), journal->surfaceHash);
  }
}

// A node restarted at once under its name finds the document's lease
// still under that name, its first process's: for up to a lease time no
// node can take the document. A viewer that opens it there meanwhile is
// served once the lease lapses, not refused for good (docs/CLUSTER.md
// "Fault-injection soak", finding 4: a refused viewer never asked again).
TEST(ClusterFailover, AViewerOfARestartedOwnerIsServedOnceItsOldLeaseLapses) {
  // Long enough that the restart comes well within the old lease.
  constexpr int kLeaseMs = 8000;
  auto run = ClusterRun::start(2, kLeaseMs);
  ASSERT_TRUE(run.isOk()) << run.status().message();
  ClusterRun& c = **run;
  auto doc = c.createCube();
  ASSERT_TRUE(doc.isOk()) << doc.status().message();
  // Open through the kill: a document whose last session leaves gives its
  // lease up, and then there is no old lease to wait for.
  testing::ClusterViewer first = testing::viewerOn(c, 0, *doc);  // node 0 takes the lease
  ASSERT_TRUE(first.session) << first.error;
  auto editor = Session::connect(c.session(0, "editor@node0", testing::kEditorToken));
  ASSERT_TRUE(editor.isOk());
  ASSERT_TRUE((*editor)->call(testing::openDocument(*doc), 30)->has_ack());
  std::mt19937 rng(5);
  auto moved = (*editor)->call(testing::smallMove(*doc, rng), 10);
  ASSERT_TRUE(moved.isOk() && moved->has_ack()) << (moved.isOk() ? moved->DebugString() : "no answer");
  c.nodes[0]->kill9();
  ASSERT_TRUE(c.startNode(0).isOk());

  testing::ClusterViewer again = testing::viewerOn(c, 0, *doc);
  ASSERT_TRUE(again.session) << "refused: " << again.error;
  auto journal = testing::journalState(c.nats, *doc);
  ASSERT_TRUE(journal.isOk()) << journal.status().message();
  // The notice says the session waited for an owner (ClusterDocument::
  // rehome, from no owner): the case under test, not a lease that had
  // lapsed before the viewer came.
  bool waited = false;
  const auto deadline = Clock::now() + std::chrono::seconds(30);
  while (Clock::now() < deadline && !(again.view->ready() && again.view->version() >= journal->version)) {
    auto m = again.session->receive(0.5);
    if (!m.isOk()) {
      ASSERT_TRUE(client::isReceiveTimeout(m.status())) << m.status().message();
      continue;
    }
    if (m->has_error()) {
      waited = waited || m->error().message().find("moved from node ? to node node0") != std::string::npos;
      continue;
    }
    ASSERT_TRUE(again.view->apply(*m).isOk());
  }
  EXPECT_TRUE(waited) << "no notice of an owner found after the open: the old lease had lapsed already";
  ASSERT_TRUE(again.view->ready());
  EXPECT_EQ(again.view->version(), journal->version);
  EXPECT_EQ(again.view->surfaceHash(), journal->surfaceHash);
}

}  // namespace
}  // namespace tessera
