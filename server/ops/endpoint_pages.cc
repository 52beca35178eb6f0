#include "server/ops/endpoint_pages.h"

#include "tessera/version.h"

namespace tessera::server {

EndpointPage EndpointPages::get(std::string_view path) {
  if (path == "/healthz") return health();
  if (path == "/metrics") return metrics();
  // The path is the client's, but the page is plain text (and the endpoint
  // sends it with nosniff): nothing in it is ever interpreted.
  return {404, "text/plain; charset=utf-8",
          "not found: " + std::string(path) + " (try /healthz or /metrics)\n"};
}

void EndpointPages::sampleEdits() {
  edits_.sample(std::chrono::steady_clock::now(), sources_.stats->edits.load());
}

EndpointPage EndpointPages::health() const {
  const auto reason = sources_.unhealthy();
  std::string body = "{\"status\":\"";
  body += reason ? "unavailable" : "ok";
  body += "\",\"version\":\"";
  body += kVersion;
  body += "\",\"uptime_seconds\":" + std::to_string(static_cast<int64_t>(sources_.stats->uptimeSeconds()));
  if (reason) {
    // The reason is the server's own text (never a client's input), but
    // keep the JSON valid whatever it says.
    body += ",\"reason\":\"";
    for (char c : *reason) body += (c == '"' || c == '\\' || static_cast<unsigned char>(c) < 0x20) ? ' ' : c;
    body += '"';
  }
  body += "}\n";
  return {reason ? 503 : 200, "application/json", std::move(body)};
}

EndpointPage EndpointPages::metrics() {
  sampleEdits();
  return {200, "text/plain; version=0.0.4; charset=utf-8",
          renderMetrics({*sources_.stats, sources_.storeStats(), sources_.documentsOpen(), edits_.perSecond(),
                         sources_.durability})};
}

}  // namespace tessera::server
