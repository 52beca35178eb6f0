#include "layering/include_rules.h"

namespace tessera::layering {

namespace {

bool startsWith(std::string_view text, std::string_view prefix) {
  return text.substr(0, prefix.size()) == prefix;
}

// `path` lies in `folder` ("core/loop" holds "core/loop/crease.h", not
// "core/loopy.h").
bool inFolder(std::string_view path, std::string_view folder) {
  return startsWith(path, folder) && path.size() > folder.size() && path[folder.size()] == '/';
}

// Headers no geometry code may reach: the network, the wire format, the
// store's and the cluster's engines, windows.
const std::vector<std::string> kServiceHeaders = {"boost/asio", "boost/beast", "google/protobuf",
                                                  "nats/",      "sqlite3",     "GLFW/"};

const std::vector<std::string> kProjectRoots = {"core/",   "protocol/", "server/",
                                                "client/", "tests/",    "bench/"};

}  // namespace

const std::vector<FolderRule>& includeRules() {
  static const std::vector<FolderRule> rules = [] {
    const std::vector<std::string> protobuf = {".pb.h"};
    std::vector<FolderRule> r = {
        // core: the geometry, lowest first.
        {"core/util", {}, kServiceHeaders},
        {"core/mesh", {"core/util"}, kServiceHeaders},
        {"core/render", {"core/util", "core/mesh"}, kServiceHeaders},
        {"core/io", {"core/util", "core/mesh"}, kServiceHeaders},
        // topology: the one Level of every scheme, under the schemes that use it.
        {"core/topology", {"core/util", "core/mesh"}, kServiceHeaders},
        {"core/loop", {"core/util", "core/mesh", "core/topology"}, kServiceHeaders},
        // Catmull-Clark's rules, which the sparse hierarchy and the one-shot schemes share.
        {"core/catmark", {"core/util", "core/mesh", "core/topology", "core/loop"}, kServiceHeaders},
        {"core/hierarchy",
         {"core/util", "core/mesh", "core/topology", "core/loop", "core/catmark"},
         kServiceHeaders},
        {"core/schemes",
         {"core/util", "core/mesh", "core/topology", "core/loop", "core/catmark", "core/io"},
         kServiceHeaders},
        {"core/document",
         {"core/util", "core/mesh", "core/topology", "core/loop", "core/catmark", "core/hierarchy"},
         kServiceHeaders},
        {"core/tessellation",
         {"core/util", "core/mesh", "core/topology", "core/loop", "core/catmark", "core/hierarchy",
          "core/document"},
         kServiceHeaders},
        {"core/morph",
         {"core/util", "core/mesh", "core/topology", "core/loop", "core/hierarchy", "core/document",
          "core/io"},
         kServiceHeaders},
        // protocol: the wire, no geometry.
        {"protocol", {"core/util"}, {"boost/asio", "nats/", "sqlite3", "GLFW/"}},
        // server: one stage per folder, each over the ones before it.
        {"server/base", {"core", "protocol"}, {"GLFW/"}},
        {"server/store",
         {"core/util", "protocol", "server/base"},
         {"boost/asio", "google/protobuf", ".pb.h", "GLFW/"}},
        {"server/document",
         {"core", "protocol", "server/base", "server/store"},
         {"boost/beast", "nats/", "GLFW/"}},
        {"server/cluster",
         {"core", "protocol", "server/base", "server/store", "server/document"},
         {"boost/beast", "GLFW/"}},
        {"server/net",
         {"core", "protocol", "server/base", "server/store", "server/document"},
         {"nats/", "GLFW/"}},
        {"server/ops", {"core/util", "protocol", "server/base", "server/store"}, {"nats/", "GLFW/"}},
        {"server/app", {"core", "protocol", "server"}, {"GLFW/"}},
        // client: the library over core and protocol; every tool over it.
        {"client/lib", {"core", "protocol"}, {}},
        {"client", {"core", "protocol", "client"}, {}},
    };
    // No code under core/ ever includes generated wire messages.
    for (FolderRule& rule : r) {
      if (startsWith(rule.folder, "core/"))
        rule.neverUses.insert(rule.neverUses.end(), protobuf.begin(), protobuf.end());
    }
    return r;
  }();
  return rules;
}

std::optional<std::string> violation(std::string_view file, std::string_view header) {
  const FolderRule* rule = nullptr;
  for (const FolderRule& r : includeRules()) {
    if (inFolder(file, r.folder)) {
      rule = &r;
      break;
    }
  }
  if (rule == nullptr) return std::nullopt;  // tests, benchmarks, tools: not layered
  for (const std::string& banned : rule->neverUses) {
    if (header.find(banned) != std::string_view::npos) {
      return std::string(rule->folder) + " never includes " + banned;
    }
  }
  bool project = false;
  for (const std::string& root : kProjectRoots) project = project || startsWith(header, root);
  if (!project) return std::nullopt;  // the standard library or a dependency, not banned above
  if (inFolder(header, rule->folder)) return std::nullopt;
  for (const std::string& allowed : rule->mayUse) {
    if (inFolder(header, allowed)) return std::nullopt;
  }
  std::string allowed;
  for (const std::string& a : rule->mayUse) allowed += (allowed.empty() ? "" : ", ") + a;
  return std::string(rule->folder) + " may include only itself" + (allowed.empty() ? "" : " and " + allowed);
}

}  // namespace tessera::layering
