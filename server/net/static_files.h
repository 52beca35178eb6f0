// The browser viewer's files (docs/WEB_VIEWER.md, "Serving it"), served by the web port: a fixed
// set of names, read once at start-up from the built web directory and
// kept in memory with a gzip copy. A request names one of them exactly or
// gets a 404: there is no directory listing and no path is ever joined to
// the root, so no request can reach another file.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <string_view>

#include "core/util/status.h"

namespace tessera::server {

struct StaticFile {
  std::string name;  // as in the root, e.g. "viewer.js"
  std::string contentType;
  std::string body;
  std::string gzipped;  // empty when gzip does not make it smaller
};

class StaticFiles {
 public:
  // The files every build of client/web writes (decode_worker.js: the Web
  // Worker that decodes region payloads, docs/WEB_VIEWER.md "Decoding in a
  // worker").
  static constexpr const char* kNames[] = {"index.html", "viewer.js", "viewer.css", "decode_worker.js",
                                           "draco_decoder.wasm"};

  // Reads every file of kNames from `root`; a missing or unreadable one is
  // an error naming it (the server does not start half a viewer).
  static Expected<StaticFiles> load(const std::filesystem::path& root);

  // The file a request target names: "/" and "/index.html" are the page,
  // "/viewer.js" the bundle, and so on; a query ("?doc=3") is ignored.
  // Anything else, null.
  const StaticFile* find(std::string_view target) const;

  // The bytes one page load transfers (every file, gzipped where smaller).
  uint64_t transferBytes() const;

 private:
  std::map<std::string, StaticFile, std::less<>> files_;  // by URL path
};

}  // namespace tessera::server
