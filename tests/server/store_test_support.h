// Shared by the store tests: temporary data directories, deterministic entry
// bytes, and raw file access for tests that inspect or damage tessera.db.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <system_error>

#include "server/store/sqlite_store.h"
#include "support/test_meshes.h"

namespace tessera::testing {

// A fresh data directory, removed with everything in it at scope exit.
class TempDataDir {
 public:
  explicit TempDataDir(const std::string& prefix = "tessera-store") : path_(makeTempDir(prefix)) {}
  ~TempDataDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDataDir(const TempDataDir&) = delete;
  TempDataDir& operator=(const TempDataDir&) = delete;

  const std::string& path() const { return path_; }
  std::string file(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

// Opens a store, recording a test failure (and returning null) if it cannot.
inline std::unique_ptr<store::SqliteStore> openStoreOrFail(const std::string& directory,
                                                           const store::SqliteStoreOptions& options = {}) {
  auto store = store::SqliteStore::open(directory, options);
  if (!store.isOk()) {
    ADD_FAILURE() << "opening " << directory << ": " << store.status().toString();
    return nullptr;
  }
  return std::move(store).value();
}

// The bytes of journal entry `version` of document `salt`: a pure function of
// both, of varying length and with zero bytes, so a lost, swapped or
// truncated entry cannot go unnoticed.
inline std::string entryBytes(uint64_t version, uint64_t salt = 0) {
  std::string bytes(8 + version % 37, '\0');
  for (size_t i = 0; i < bytes.size(); ++i) {
    bytes[i] = static_cast<char>((version * 131 + salt * 17 + i * 7) & 0xff);
  }
  return bytes;
}

inline std::string readFileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline void writeFileBytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace tessera::testing
