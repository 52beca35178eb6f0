// The store's schema: recognising a Tessera database file and migrating it.
//
// A Tessera file carries kStoreApplicationId in its header (PRAGMA
// application_id) and its schema version in PRAGMA user_version. Opening
// accepts an empty file (and migrates it) or a Tessera file of this version
// or older; it refuses anything else without writing to it: random bytes, a
// damaged file, another program's database, or a file from a newer Tessera.
#pragma once

#include <cstdint>

#include "core/util/status.h"
#include "server/store/sqlite_connection.h"

namespace tessera::store {

inline constexpr int64_t kStoreApplicationId = 0x54455353;  // "TESS"
inline constexpr int64_t kStoreSchemaVersion = 1;

struct SchemaOptions {
  // PRAGMA quick_check reads the whole file: O(size), so a huge store may
  // want to skip it and rely on SQLite reporting damaged pages when read.
  bool verifyIntegrity = true;
};

// Checks the file behind `connection` (which must be in autocommit mode) and
// migrates it to kStoreSchemaVersion. Switches it to WAL journaling, which is
// persistent in the file, only once it is known to be ours.
Status prepareSchema(SqliteConnection& connection, const SchemaOptions& options);

}  // namespace tessera::store
