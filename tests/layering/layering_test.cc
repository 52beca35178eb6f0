// Holds every #include of core/, protocol/, server/ and client/ against the
// table in include_rules.h (docs/ARCHITECTURE.md, "Layers").
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "layering/include_rules.h"

namespace tessera::layering {
namespace {

namespace fs = std::filesystem;

TEST(IncludeRules, RefuseTheDirectionsTheTreeForbids) {
  // Each of these would run a layer backwards.
  EXPECT_TRUE(violation("core/loop/crease.cc", "core/io/mesh_export.h"));
  EXPECT_TRUE(violation("core/document/document.h", "protocol/tessera.pb.h"));
  EXPECT_TRUE(violation("core/tessellation/region_codec.cc", "server/net/outbox.h"));
  EXPECT_TRUE(violation("core/util/status.h", "boost/asio/post.hpp"));
  EXPECT_TRUE(violation("core/mesh/base_mesh.cc", "google/protobuf/message.h"));
  EXPECT_TRUE(violation("protocol/framing.h", "core/loop/level.h"));
  EXPECT_TRUE(violation("server/document/document_host.h", "server/net/outbox.h"));
  EXPECT_TRUE(violation("server/document/document_host.cc", "server/cluster/cluster_node.h"));
  EXPECT_TRUE(violation("server/net/connection.cc", "server/app/server.h"));
  EXPECT_TRUE(violation("server/net/connection.cc", "server/cluster/cluster_node.h"));
  EXPECT_TRUE(violation("server/cluster/cluster_node.cc", "server/net/server_context.h"));
  EXPECT_TRUE(violation("server/base/log.cc", "server/store/store.h"));
  EXPECT_TRUE(violation("client/view/viewer.cc", "server/document/delta.h"));
  EXPECT_TRUE(violation("client/lib/session.cc", "client/view/camera.h"));
  // The one topology lies under every scheme: it names none of them.
  EXPECT_TRUE(violation("core/topology/level.h", "core/loop/crease.h"));
  EXPECT_TRUE(violation("core/topology/level_builder.cc", "core/catmark/quad_split.h"));
  EXPECT_TRUE(violation("core/topology/tags.cc", "core/io/tag_file.h"));
}

TEST(IncludeRules, AllowTheDirectionsTheTreeUses) {
  EXPECT_FALSE(violation("core/loop/crease.cc", "core/loop/crease.h"));
  EXPECT_FALSE(violation("core/loop/surfaces.h", "core/mesh/surface_mesh.h"));
  EXPECT_FALSE(violation("core/loop/refinement.h", "core/topology/level.h"));
  EXPECT_FALSE(violation("core/catmark/quad_split.h", "core/topology/level.h"));
  EXPECT_FALSE(violation("core/topology/level.h", "core/mesh/sharpness.h"));
  EXPECT_FALSE(violation("core/tessellation/tessellation.h", "core/document/document.h"));
  EXPECT_FALSE(violation("protocol/framing.h", "core/util/status.h"));
  EXPECT_FALSE(violation("server/document/subscriber.h", "server/document/delta.h"));
  EXPECT_FALSE(violation("server/net/outbox.h", "server/document/delta.h"));
  EXPECT_FALSE(violation("server/cluster/cluster_document.h", "server/document/document_host.h"));
  EXPECT_FALSE(violation("server/app/server.cc", "server/cluster/cluster_node.h"));
  EXPECT_FALSE(violation("client/view/viewer.cc", "client/lib/session.h"));
  EXPECT_FALSE(violation("core/util/status.h", "string"));
  EXPECT_FALSE(violation("tests/server/outbox_test.cc", "server/net/outbox.h"));  // tests are not layered
}

struct Include {
  std::string file;
  int line;
  std::string header;
};

std::vector<Include> includesUnder(const fs::path& root, const std::string& top) {
  static const std::regex include(R"(^\s*#\s*include\s*[<"]([^>"]+)[>"])");
  std::vector<Include> found;
  for (const auto& entry : fs::recursive_directory_iterator(root / top)) {
    const fs::path& path = entry.path();
    if (!entry.is_regular_file()) continue;
    const std::string ext = path.extension().string();
    if (ext != ".h" && ext != ".cc" && ext != ".cpp") continue;
    const std::string relative = fs::relative(path, root).generic_string();
    if (relative.find("node_modules") != std::string::npos) continue;
    std::ifstream in(path);
    std::string text;
    int number = 0;
    while (std::getline(in, text)) {
      ++number;
      std::smatch match;
      if (std::regex_search(text, match, include)) found.push_back({relative, number, match[1].str()});
    }
  }
  return found;
}

TEST(Layering, EveryIncludeOfTheTreeRunsAnAllowedWay) {
  const fs::path root = TESSERA_SOURCE_ROOT;
  int checked = 0;
  std::string wrong;
  for (const std::string top : {"core", "protocol", "server", "client"}) {
    for (const Include& inc : includesUnder(root, top)) {
      ++checked;
      if (auto why = violation(inc.file, inc.header)) {
        wrong += "\n  " + inc.file + ":" + std::to_string(inc.line) + " includes " + inc.header + ": " + *why;
      }
    }
  }
  EXPECT_GT(checked, 1000) << "the walk found too few includes under " << root;
  EXPECT_TRUE(wrong.empty()) << "includes against the layering (tests/layering/include_rules.cc):" << wrong;
}

}  // namespace
}  // namespace tessera::layering
