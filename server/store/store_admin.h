// Operations on a data directory from a second process, for operators
// (docs/OPERATIONS.md): granting a token and taking an online backup work
// while a server runs on the directory (SQLite's file locking arbitrates,
// and a WAL reader sees one consistent instant); restoring replaces the
// store and so needs the server stopped (it takes the directory lock).
#pragma once

#include <string>
#include <string_view>

#include "core/util/status.h"
#include "server/store/store.h"

namespace tessera::store {

// The store file of a data directory: <dataDirectory>/tessera.db.
std::string storePath(const std::string& dataDirectory);

// Grants `token` `role` on `scope` in the store of `dataDirectory`, creating
// the store if there is none yet. Only the token's hash is written.
Status grantTokenInStore(const std::string& dataDirectory, TokenScope scope, std::string_view token,
                         Role role);

// Writes a consistent copy of the store to `destination`, a single SQLite
// file: copied under a temporary name, checked, made durable, then renamed,
// so a failed backup never leaves a truncated file under the final name.
// An existing `destination` is refused rather than overwritten.
Status backupStore(const std::string& dataDirectory, const std::string& destination);

// Replaces the store of `dataDirectory` (no server may be running on it) by
// the backup `source` after checking that it is a Tessera store of this
// version or older and passes SQLite's integrity check. The store that was
// there is kept beside it as tessera.db.before-restore.
Status restoreStore(const std::string& dataDirectory, const std::string& source);

}  // namespace tessera::store
