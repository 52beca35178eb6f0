#include "client/replay/record.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>

#include "client/lib/command_feed.h"
#include "client/lib/document_view.h"
#include "protocol/commands.h"
#include "protocol/morph_key.h"

namespace tessera::replay {

namespace {

using Clock = std::chrono::steady_clock;

constexpr size_t kMaxActorBytes = 100;  // the script's limits (docs/REPLAY.md §1)
constexpr size_t kMaxActors = 1000;

// At most `bytes` bytes of `s`, without cutting a UTF-8 sequence.
std::string truncated(const std::string& s, size_t bytes) {
  if (s.size() <= bytes) return s;
  size_t n = bytes;
  while (n > 0 && (static_cast<unsigned char>(s[n]) & 0xC0) == 0x80) --n;
  return s.substr(0, n);
}

std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

std::string secondsText(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%g s", s);
  return text;
}

}  // namespace

std::string ScriptRecorder::actorFor(uint64_t session, const std::string& name) {
  if (auto it = actorOf_.find(session); it != actorOf_.end()) return it->second;
  const std::string base = name.empty() ? "session " + std::to_string(session) : name;
  std::string actor = truncated(base, kMaxActorBytes);
  for (int n = 2; taken_.count(actor); ++n) {
    const std::string suffix = "#" + std::to_string(n);
    actor = truncated(base, kMaxActorBytes - suffix.size()) + suffix;
  }
  taken_.insert(actor);
  actorOf_[session] = actor;
  return actor;
}

Expected<ScriptCommand> ScriptRecorder::add(const wire::AppliedCommand& a) {
  const std::string where = "version " + std::to_string(a.version()) + ": ";
  if (!actorOf_.count(a.author_session_id()) && actorOf_.size() >= kMaxActors) {
    return invalidArgument(where + "more than " + std::to_string(kMaxActors) +
                           " actors (a replay opens at most that many)");
  }
  ScriptCommand c;
  // Server times, so that the client's clock and its delays do not matter.
  const int64_t t =
      a.server_time_unix_ms() > startMs_ ? static_cast<int64_t>(a.server_time_unix_ms() - startMs_) : 0;
  lastMs_ = std::max(lastMs_, t);
  c.timeMs = lastMs_;
  c.actor = actorFor(a.author_session_id(), a.author_name());
  // Scripts have no morph keys: an edit of key 1 would replay
  // onto key 0, so it is refused rather than recorded wrongly.
  const uint32_t key = morphKeyOf(a);
  if (key != 0) {
    return invalidArgument(
        where + "an edit of morph key " + std::to_string(key) +
        ": replay scripts edit key 0 only, so a morph document's second key cannot be recorded");
  }
  switch (a.command_case()) {
    case wire::AppliedCommand::kMoveVertex: {
      const wire::MoveVertex& m = a.move_vertex();
      c.kind = ScriptCommand::Kind::kMove;
      c.vertices.assign(m.vertex_ids().begin(), m.vertex_ids().end());
      c.offset = m.mode() == wire::MOVE_MODE_OFFSET;
      c.to = {m.target().x(), m.target().y(), m.target().z()};
      break;
    }
    case wire::AppliedCommand::kSetEdgeSharpness:
      c.kind = ScriptCommand::Kind::kCrease;
      c.edge = a.set_edge_sharpness().edge_id();
      c.sharpness = a.set_edge_sharpness().sharpness();
      break;
    case wire::AppliedCommand::kSetVertexType: {
      const wire::SetVertexType& m = a.set_vertex_type();
      c.kind = ScriptCommand::Kind::kCorner;
      c.vertices.push_back(m.vertex_id());
      // A script's corner is a sharpness; the server maps the types the same
      // way (smooth 0, cusp and corner infinite).
      if (m.value_case() == wire::SetVertexType::kSharpness) {
        c.sharpness = m.sharpness();
      } else {
        c.sharpness = m.type() == wire::VERTEX_TYPE_SMOOTH ? 0.0f : INFINITY;
      }
      break;
    }
    case wire::AppliedCommand::kSetInterpolation: {
      const wire::SetInterpolation& m = a.set_interpolation();
      c.kind = ScriptCommand::Kind::kInterpolate;
      c.vertices.push_back(m.vertex_id());
      c.interpolating = m.interpolating();
      c.tension = m.tension() == 0.0 ? 1.0 : m.tension();
      break;
    }
    case wire::AppliedCommand::kUndo:
    case wire::AppliedCommand::kRedo: {
      const bool undo = a.command_case() == wire::AppliedCommand::kUndo;
      c.kind = undo ? ScriptCommand::Kind::kUndo : ScriptCommand::Kind::kRedo;
      const uint64_t target = undo ? a.undo().edit_id() : a.redo().edit_id();
      const std::vector<uint64_t>& own = edits_[c.actor];
      auto it = std::find(own.begin(), own.end(), target);
      c.edit = it != own.end() ? -static_cast<int64_t>(own.end() - it) : static_cast<int64_t>(target);
      return c;
    }
    case wire::AppliedCommand::kAddMorphKey:
      return invalidArgument(where +
                             "a second morph key (AddMorphKey): replay scripts hold edits of one key, "
                             "so a morph document cannot be recorded");
    default:
      return invalidArgument(where + "an AppliedCommand without a command (one this build does not know)");
  }
  edits_[c.actor].push_back(a.edit_id());
  return c;
}

Expected<std::vector<ScriptCommand>> ScriptRecorder::lines(const wire::AppliedCommand& a) {
  if (a.command_case() != wire::AppliedCommand::kEditBatch) {
    TESSERA_ASSIGN_OR_RETURN(ScriptCommand c, add(a));
    return std::vector<ScriptCommand>{c};
  }
  const auto& commands = a.edit_batch().commands();
  if (a.edit_ids_size() != commands.size()) {
    return invalidArgument("version " + std::to_string(a.version()) + ": an EditBatch of " +
                           std::to_string(commands.size()) + " commands with " +
                           std::to_string(a.edit_ids_size()) + " edit ids");
  }
  std::vector<ScriptCommand> out;
  for (int i = 0; i < commands.size(); ++i) {
    wire::AppliedCommand one = a;
    one.clear_edit_batch();
    one.clear_edit_ids();
    one.set_edit_id(a.edit_ids(i));
    const wire::EditCommand& c = commands[i];
    unwrapEditCommand(c, one);  // none: add() names the empty command
    TESSERA_ASSIGN_OR_RETURN(ScriptCommand line, add(one));
    out.push_back(std::move(line));
  }
  return out;
}

Expected<RecordResult> runRecord(const RecordOptions& o) {
  if (o.document == 0) return invalidArgument("record: no document given");
  if (!(o.seconds > 0) && o.untilVersion == 0)
    return invalidArgument("record: give a duration or a version to stop at");
  TESSERA_ASSIGN_OR_RETURN(auto session, client::Session::connect(o.session));
  client::Session& s = *session;
  client::DocumentView view(o.document);
  TESSERA_RETURN_IF_ERROR(openAndSubscribe(s, o.document, profileOf(o.header), &view,
                                           o.session.timeoutSeconds,
                                           /*withCommands=*/true));
  RecordResult result;
  result.fromVersion = result.lastVersion = view.version();
  if (o.untilVersion != 0 && o.untilVersion <= result.fromVersion) {
    return invalidArgument("document " + std::to_string(o.document) + " is already at version " +
                           std::to_string(result.fromVersion) + ", not before " +
                           std::to_string(o.untilVersion));
  }
  wire::ClientMessage ping;
  ping.mutable_ping();
  TESSERA_ASSIGN_OR_RETURN(wire::ServerMessage pong, s.call(ping, o.session.timeoutSeconds));
  ScriptRecorder recorder(pong.pong().server_time_unix_ms());
  ScriptHeader header = o.header;
  header.document = o.document;
  header.generator = "tessera-replay record: document " + std::to_string(o.document) + " from version " +
                     std::to_string(result.fromVersion) + ", " + utcNow();
  if (o.out) *o.out << headerLine(header) << "\n" << std::flush;
  if (o.started) o.started(result.fromVersion);

  client::CommandFeed feed(o.document, result.fromVersion);
  const auto start = Clock::now();
  const auto deadline = o.seconds > 0 ? start + secondsOf(o.seconds) : Clock::time_point::max();
  auto lastPing = start;
  for (;;) {
    const auto now = Clock::now();
    // The delta of a version arrives before its command: stopping right
    // after the command leaves the view at the same version.
    if (o.untilVersion != 0 && feed.version() >= o.untilVersion) break;
    if (now >= deadline) {
      if (o.untilVersion != 0) {
        result.stopped = ioError("version " + std::to_string(o.untilVersion) + " was not reached within " +
                                 secondsText(o.seconds) + " (recorded up to version " +
                                 std::to_string(feed.version()) + ")");
        break;
      }
      // Timed stop: record the commands whose deltas already arrived too.
      if (!view.ready() || feed.version() >= view.version() || now >= deadline + secondsOf(o.drainSeconds))
        break;
    }
    if (now - lastPing > std::chrono::seconds(30)) {  // the server's idle timeout counts only bytes from us
      if (auto sent = s.send(ping); !sent.isOk()) {
        result.stopped = sent.status();
        break;
      }
      lastPing = now;
    }
    const double left = now >= deadline ? 0.05 : std::chrono::duration<double>(deadline - now).count();
    auto m = s.receive(std::min(left, 0.25));
    if (!m.isOk()) {
      if (client::isReceiveTimeout(m.status())) continue;
      result.stopped = m.status();
      break;
    }
    if (m->has_error() && m->error().fatal()) {
      result.stopped = ioError("server error: " + m->error().message());
      break;
    }
    // After a gap the view waits for the server's resync; the commands go on.
    (void)view.apply(*m);
    auto applied = feed.apply(*m);
    if (!applied.isOk()) {
      result.stopped = applied.status();
      break;
    }
    if (*applied == nullptr) continue;
    auto lines = recorder.lines(**applied);
    if (!lines.isOk()) {
      result.stopped = lines.status();
      break;
    }
    result.commands += lines->size();
    result.lastVersion = (*applied)->version();
    for (const ScriptCommand& line : *lines) {
      if (o.out) *o.out << commandLine(line) << "\n" << std::flush;
    }
  }
  if (view.ready() && view.version() == result.lastVersion) {
    result.surface = SurfaceState{view.version(), view.surfaceHash(), view.numTriangles()};
  }
  result.actors = recorder.actors();
  s.close();
  return result;
}

}  // namespace tessera::replay
