#include "client/replay/replay.h"

#include <chrono>
#include <cstdio>
#include <map>
#include <thread>

namespace tessera::replay {

namespace {

using Clock = std::chrono::steady_clock;

std::string describe(const wire::ServerMessage& m) {
  if (m.has_reject()) return wire::RejectReason_Name(m.reject().reason()) + ": " + m.reject().message();
  return "unexpected reply";
}

}  // namespace

wire::LodProfile profileOf(const ScriptHeader& header) {
  wire::LodProfile p;
  p.set_base_level(header.baseLevel);
  p.set_max_level(header.maxLevel);
  p.set_angle_threshold_degrees(header.angleDegrees);
  return p;
}

Status openDocument(client::Session& s, uint64_t document, double timeoutSeconds) {
  wire::ClientMessage open;
  open.mutable_open_document()->set_document_id(document);
  TESSERA_ASSIGN_OR_RETURN(wire::ServerMessage opened, s.call(open, timeoutSeconds));
  if (!opened.has_ack())
    return invalidArgument("document " + std::to_string(document) + ": open: " + describe(opened));
  return Status::ok();
}

Status openAndSubscribe(client::Session& s, uint64_t document, const wire::LodProfile& profile,
                        client::DocumentView* view, double timeoutSeconds, bool withCommands) {
  TESSERA_RETURN_IF_ERROR(openDocument(s, document, timeoutSeconds));
  wire::ClientMessage sub;
  sub.mutable_subscribe()->set_document_id(document);
  *sub.mutable_subscribe()->mutable_profile() = profile;
  sub.mutable_subscribe()->set_with_commands(withCommands);
  TESSERA_ASSIGN_OR_RETURN(wire::ServerMessage subscribed, s.call(sub, timeoutSeconds));
  if (!subscribed.has_ack()) {
    return invalidArgument("document " + std::to_string(document) + ": subscribe: " + describe(subscribed));
  }
  if (view == nullptr) return Status::ok();
  const auto deadline = Clock::now() + std::chrono::duration<double>(timeoutSeconds);
  while (!view->ready()) {
    const double left = std::chrono::duration<double>(deadline - Clock::now()).count();
    if (left <= 0)
      return ioError("document " + std::to_string(document) + ": no snapshot within the timeout");
    TESSERA_ASSIGN_OR_RETURN(wire::ServerMessage m, s.receive(left));
    TESSERA_RETURN_IF_ERROR(view->apply(m));
  }
  return Status::ok();
}

Expected<SurfaceState> readSurface(const client::SessionOptions& options, uint64_t document,
                                   const wire::LodProfile& profile) {
  client::SessionOptions o = options;
  o.name = "tessera-replay-check";
  TESSERA_ASSIGN_OR_RETURN(auto session, client::Session::connect(o));
  client::DocumentView view(document);
  TESSERA_RETURN_IF_ERROR(openAndSubscribe(*session, document, profile, &view, o.timeoutSeconds));
  session->close();
  // The server's own hash of the snapshot (PROTOCOL 6.5): a state this
  // client assembled differently is an error, not a number to compare.
  TESSERA_RETURN_IF_ERROR(view.verifySurface());
  return SurfaceState{view.version(), view.surfaceHash(), view.numTriangles()};
}

Expected<ReplayResult> runReplay(const Script& script, const ReplayOptions& options) {
  const uint64_t doc = options.document != 0 ? options.document : script.header.document;
  if (doc == 0)
    return invalidArgument("no document: give --document or put \"document\" in the script header");
  struct Actor {
    std::unique_ptr<client::Session> session;
    std::vector<uint64_t> edits;  // edit ids of its accepted edits, oldest first
  };
  std::map<std::string, Actor> actors;
  ReplayResult result;
  const auto start = Clock::now();
  for (const ScriptCommand& c : script.commands) {
    if (options.speed > 0) {
      std::this_thread::sleep_until(start +
                                    std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double, std::milli>(c.timeMs / options.speed)));
    }
    Actor& actor = actors[c.actor];
    const std::string where = "line " + std::to_string(c.line) + " (" + c.actor + ")";
    if (!actor.session) {
      if (actors.size() > 1000) return invalidArgument(where + ": more than 1000 actors");
      client::SessionOptions o = options.session;
      o.name = c.actor;
      auto session = client::Session::connect(o);
      if (!session.isOk()) return session.status().withContext(where);
      actor.session = std::move(*session);
      TESSERA_RETURN_IF_ERROR(
          openDocument(*actor.session, doc, options.replyTimeoutSeconds).withContext(where));
    }
    uint64_t editId = 0;
    if (c.kind == ScriptCommand::Kind::kUndo || c.kind == ScriptCommand::Kind::kRedo) {
      if (c.edit > 0) {
        editId = static_cast<uint64_t>(c.edit);
      } else if (static_cast<size_t>(-c.edit) <= actor.edits.size()) {
        editId = actor.edits[actor.edits.size() - static_cast<size_t>(-c.edit)];
      } else {
        ++result.commands;
        ++result.rejected;
        std::fprintf(stderr, "tessera-replay: %s: edit %lld: the actor has made only %zu edits; skipped\n",
                     where.c_str(), static_cast<long long>(c.edit), actor.edits.size());
        continue;
      }
    }
    ++result.commands;
    auto reply = actor.session->call(toWire(c, doc, editId), options.replyTimeoutSeconds);
    if (!reply.isOk()) return reply.status().withContext(where);
    if (reply->has_ack()) {
      ++result.acked;
      result.lastVersion = reply->ack().version();
      if (c.kind != ScriptCommand::Kind::kUndo && c.kind != ScriptCommand::Kind::kRedo) {
        actor.edits.push_back(reply->ack().edit_id());
      }
    } else {
      ++result.rejected;
      std::fprintf(stderr, "tessera-replay: %s: %s\n", where.c_str(), describe(*reply).c_str());
    }
    // Replies the session kept meanwhile (presence) are of no interest.
    for (int i = 0; i < 100; ++i) {
      auto extra = actor.session->receive(0);
      if (!extra.isOk()) break;
    }
  }
  for (auto& [name, actor] : actors) actor.session->close();
  return result;
}

}  // namespace tessera::replay
