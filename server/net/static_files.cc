#include "server/net/static_files.h"

#include <zlib.h>
#include <fstream>
#include <sstream>

namespace tessera::server {

namespace {

// Larger files are not the viewer's (the bundle is well under a megabyte).
constexpr uintmax_t kMaxFileBytes = 32u << 20;

const char* contentTypeOf(std::string_view name) {
  if (name.ends_with(".html")) return "text/html; charset=utf-8";
  if (name.ends_with(".js")) return "text/javascript; charset=utf-8";
  if (name.ends_with(".css")) return "text/css; charset=utf-8";
  if (name.ends_with(".wasm")) return "application/wasm";
  return "application/octet-stream";
}

// A gzip stream (windowBits 16 + 15), as browsers accept for
// Content-Encoding: gzip.
std::string gzip(const std::string& in) {
  z_stream z{};
  if (deflateInit2(&z, Z_BEST_COMPRESSION, Z_DEFLATED, 16 + 15, 9, Z_DEFAULT_STRATEGY) != Z_OK) return {};
  std::string out(deflateBound(&z, in.size()), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data()));
  z.avail_in = static_cast<uInt>(in.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  const int rc = deflate(&z, Z_FINISH);
  out.resize(z.total_out);
  deflateEnd(&z);
  return rc == Z_STREAM_END ? out : std::string();
}

}  // namespace

Expected<StaticFiles> StaticFiles::load(const std::filesystem::path& root) {
  StaticFiles files;
  for (const char* name : kNames) {
    const auto path = root / name;
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    if (ec) {
      return ioError("--web-root: " + path.string() + ": " + ec.message() +
                     " (build the web viewer: the tessera_web target, docs/WEB_VIEWER.md)");
    }
    if (size > kMaxFileBytes)
      return invalidArgument("--web-root: " + path.string() + " is larger than 32 MiB");
    std::ifstream in(path, std::ios::binary);
    std::ostringstream body;
    body << in.rdbuf();
    if (!in && !in.eof()) return ioError("--web-root: cannot read " + path.string());
    StaticFile file{name, contentTypeOf(name), body.str(), {}};
    file.gzipped = gzip(file.body);
    if (file.gzipped.size() >= file.body.size()) file.gzipped.clear();
    files.files_["/" + std::string(name)] = std::move(file);
  }
  files.files_["/"] = files.files_["/index.html"];
  return files;
}

const StaticFile* StaticFiles::find(std::string_view target) const {
  const std::string_view path = target.substr(0, target.find('?'));
  auto it = files_.find(path);
  return it == files_.end() ? nullptr : &it->second;
}

uint64_t StaticFiles::transferBytes() const {
  uint64_t total = 0;
  for (const char* name : kNames) {
    const StaticFile& f = files_.at("/" + std::string(name));
    total += f.gzipped.empty() ? f.body.size() : f.gzipped.size();
  }
  return total;
}

}  // namespace tessera::server
