// tessera_timed_editor: the C++ editor of the browser viewer's benchmark
// (bench/web_viewer_bench.mjs). Sends N small offset edits to
// one document at a fixed interval and prints, per acknowledged edit, its
// version and the wall-clock time (Unix ms, system_clock) just before it
// was sent, so that a browser on the same machine can time edit-to-pixels
// against its own Date.now().
//   tessera_timed_editor --port P --token T --document D --edits 50 --interval-ms 200 [--vertex-level 1
//   --vertex-index 2]
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <thread>

#include "client/lib/session.h"
#include "core/hierarchy/ids.h"
#include "protocol/tessera.pb.h"

namespace {

double unixMs() {
  return std::chrono::duration<double, std::milli>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "tessera_timed_editor: timed offset edits, one line per acknowledged edit: VERSION SENT_UNIX_MS"};
  int port = 7878, edits = 50, intervalMs = 200, level = 1;
  uint64_t document = 0, index = 2;
  std::string token;
  app.add_option("--port", port)->required();
  app.add_option("--token", token)->required();
  app.add_option("--document", document)->required();
  app.add_option("--edits", edits);
  app.add_option("--interval-ms", intervalMs);
  app.add_option("--vertex-level", level);
  app.add_option("--vertex-index", index);
  CLI11_PARSE(app, argc, argv);

  tessera::client::SessionOptions options{.host = "127.0.0.1",
                                          .port = static_cast<uint16_t>(port),
                                          .name = "timed-editor",
                                          .token = token,
                                          .timeoutSeconds = 20};
  auto session = tessera::client::Session::connect(options);
  if (!session.isOk()) {
    std::fprintf(stderr, "connect: %s\n", session.status().message().c_str());
    return 1;
  }
  tessera::wire::ClientMessage open;
  open.mutable_open_document()->set_document_id(document);
  auto opened = (*session)->call(open, 20);
  if (!opened.isOk() || !opened->has_ack()) {
    std::fprintf(stderr, "open: %s\n",
                 opened.isOk() ? opened->DebugString().c_str() : opened.status().message().c_str());
    return 1;
  }
  const uint64_t vertex = tessera::VertexId(level, index).packed();
  for (int k = 0; k < edits; ++k) {
    tessera::wire::ClientMessage m;
    auto* move = m.mutable_move_vertex();
    move->set_document_id(document);
    move->add_vertex_ids(vertex);
    move->mutable_target()->set_z(k % 2 == 0 ? 0.02 : -0.02);
    move->set_mode(tessera::wire::MOVE_MODE_OFFSET);
    const double sent = unixMs();
    auto reply = (*session)->call(m, 20);
    if (!reply.isOk() || !reply->has_ack()) {
      std::fprintf(stderr, "edit %d: %s\n", k,
                   reply.isOk() ? reply->DebugString().c_str() : reply.status().message().c_str());
      return 1;
    }
    std::printf("%llu %.3f\n", static_cast<unsigned long long>(reply->ack().version()), sent);
    std::fflush(stdout);
    std::this_thread::sleep_for(std::chrono::milliseconds(intervalMs));
  }
  return 0;
}
