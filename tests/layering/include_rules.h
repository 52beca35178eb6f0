// The layering of the tree (docs/ARCHITECTURE.md, "Layers"), as a table a
// test can hold every #include against. A folder may include itself and the
// folders its rule lists; `core` never reaches sockets, wire formats or the
// store, `protocol` knows no geometry, the server's stages use only the
// stages below them, and the clients never include the server.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tessera::layering {

struct FolderRule {
  std::string folder;                  // "core/loop", "server/document", "client"
  std::vector<std::string> mayUse;     // project folders it may include, besides itself
  std::vector<std::string> neverUses;  // system or library headers it must not include (prefixes)
};

// The table, most specific folder first.
const std::vector<FolderRule>& includeRules();

// Why `file` (a path from the source root) must not include `header` (as
// written between the quotes or angle brackets), or nothing when it may.
std::optional<std::string> violation(std::string_view file, std::string_view header);

}  // namespace tessera::layering
