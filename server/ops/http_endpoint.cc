#include "server/ops/http_endpoint.h"

#include <httplib.h>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "server/base/log.h"
#include "server/ops/metrics_exposition.h"
#include "tessera/version.h"

namespace tessera::server {

struct HttpEndpoint::Impl {
  HttpSources sources;
  httplib::Server http;
  std::thread serving;
  // Samples the edit counter once a second for tessera_edits_per_second.
  RateWindow edits{std::chrono::seconds(10)};
  std::thread sampling;
  std::mutex mutex;
  std::condition_variable wake;
  bool stopping = false;

  void sampleLoop() {
    std::unique_lock lock(mutex);
    while (!stopping) {
      edits.sample(std::chrono::steady_clock::now(), sources.stats->edits.load());
      wake.wait_for(lock, std::chrono::seconds(1), [this] { return stopping; });
    }
  }

  void routes() {
    http.Get("/healthz", [this](const httplib::Request&, httplib::Response& response) {
      const auto reason = sources.unhealthy();
      std::string body = "{\"status\":\"";
      body += reason ? "unavailable" : "ok";
      body += "\",\"version\":\"";
      body += kVersion;
      body += "\",\"uptime_seconds\":" + std::to_string(static_cast<int64_t>(sources.stats->uptimeSeconds()));
      if (reason) {
        // The reason is the server's own text (never a client's input), but
        // keep the JSON valid whatever it says.
        body += ",\"reason\":\"";
        for (char c : *reason)
          body += (c == '"' || c == '\\' || static_cast<unsigned char>(c) < 0x20) ? ' ' : c;
        body += '"';
      }
      body += "}\n";
      response.status = reason ? 503 : 200;
      response.set_content(body, "application/json");
    });
    http.Get("/metrics", [this](const httplib::Request&, httplib::Response& response) {
      edits.sample(std::chrono::steady_clock::now(), sources.stats->edits.load());
      response.set_content(
          renderMetrics({*sources.stats, sources.storeStats(), sources.documentsOpen(), edits.perSecond()}),
          "text/plain; version=0.0.4; charset=utf-8");
    });
    http.set_error_handler([](const httplib::Request& request, httplib::Response& response) {
      if (response.status == 404) {
        response.set_content("not found: " + request.path + " (try /healthz or /metrics)\n", "text/plain");
      }
    });
    // Scrapes and probes are tiny: refuse bodies, keep slow peers short.
    http.set_payload_max_length(4096);
    http.set_read_timeout(5, 0);
    http.set_write_timeout(5, 0);
    http.set_keep_alive_max_count(100);
    http.new_task_queue = [] { return new httplib::ThreadPool(2); };
  }
};

HttpEndpoint::HttpEndpoint(std::unique_ptr<Impl> impl, uint16_t port) : impl_(std::move(impl)), port_(port) {}

Expected<std::unique_ptr<HttpEndpoint>> HttpEndpoint::start(const std::string& address, int port,
                                                            HttpSources sources) {
  auto impl = std::make_unique<Impl>();
  impl->sources = std::move(sources);
  impl->routes();
  int bound = port;
  if (port == 0) {
    bound = impl->http.bind_to_any_port(address);
  } else if (!impl->http.bind_to_port(address, port)) {
    bound = -1;
  }
  if (bound <= 0) {
    return ioError("--http-port: cannot listen on " + address + ":" + std::to_string(port) +
                   " (address in use, or not an address of this machine)");
  }
  Impl* raw = impl.get();
  impl->serving = std::thread([raw] { raw->http.listen_after_bind(); });
  impl->sampling = std::thread([raw] { raw->sampleLoop(); });
  logEvent(LogLevel::kInfo, "http_listening", {{"address", address}, {"port", static_cast<int64_t>(bound)}});
  return std::unique_ptr<HttpEndpoint>(new HttpEndpoint(std::move(impl), static_cast<uint16_t>(bound)));
}

HttpEndpoint::~HttpEndpoint() {
  {
    std::lock_guard lock(impl_->mutex);
    impl_->stopping = true;
  }
  impl_->wake.notify_all();
  impl_->http.stop();
  if (impl_->serving.joinable()) impl_->serving.join();
  if (impl_->sampling.joinable()) impl_->sampling.join();
}

}  // namespace tessera::server
