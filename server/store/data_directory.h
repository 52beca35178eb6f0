// The data directory: created on first use (owner-only, since it holds the
// documents and token hashes) and locked so that one process at a time uses
// it. Two servers on one directory would each believe they are the single
// writer of every document; the second one is refused at open instead.
//
// The lock is an flock(2) on <directory>/tessera.lock, released by the kernel
// when the process dies, so a kill -9 never leaves a stale lock behind.
#pragma once

#include <string>

#include "core/util/status.h"

namespace tessera::store {

class DataDirectoryLock {
 public:
  // Creates `directory` (and missing parents) if needed, then takes the lock.
  static Expected<DataDirectoryLock> acquire(const std::string& directory);

  DataDirectoryLock(DataDirectoryLock&& other) noexcept;
  DataDirectoryLock& operator=(DataDirectoryLock&& other) noexcept;
  DataDirectoryLock(const DataDirectoryLock&) = delete;
  DataDirectoryLock& operator=(const DataDirectoryLock&) = delete;
  ~DataDirectoryLock();

  void release();

 private:
  explicit DataDirectoryLock(int fd) : fd_(fd) {}
  int fd_ = -1;
};

}  // namespace tessera::store
