#include "server/store/data_directory.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <utility>

namespace tessera::store {
namespace {

std::string errnoText(int error) {
  return std::strerror(error);
}

// A new directory entry is only durable once its parent is fsynced; without
// this a power loss right after the first commit could lose the directory.
Status syncDirectory(const std::filesystem::path& directory) {
  const int fd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return ioError(directory.string() + ": cannot open to sync: " + errnoText(errno));
  const int result = ::fsync(fd);
  const int error = errno;
  ::close(fd);
  if (result != 0) return ioError(directory.string() + ": fsync failed: " + errnoText(error));
  return Status::ok();
}

Status ensureDirectory(const std::filesystem::path& directory) {
  std::error_code error;
  if (std::filesystem::is_directory(directory, error)) return Status::ok();
  if (std::filesystem::exists(directory, error)) {
    return ioError(directory.string() + ": data directory path exists but is not a directory");
  }
  const std::filesystem::path parent = directory.has_parent_path() ? directory.parent_path() : ".";
  std::filesystem::create_directories(parent, error);
  if (error) return ioError(parent.string() + ": cannot create: " + error.message());
  if (::mkdir(directory.c_str(), 0700) != 0 && errno != EEXIST) {
    return ioError(directory.string() + ": cannot create data directory: " + errnoText(errno));
  }
  return syncDirectory(parent);
}

}  // namespace

Expected<DataDirectoryLock> DataDirectoryLock::acquire(const std::string& directory) {
  if (directory.empty()) return invalidArgument("the data directory path is empty");
  // Without this, "data/" would make the parent "data" and mkdir would then fail.
  const std::filesystem::path path = std::filesystem::path(directory).lexically_normal();
  const std::filesystem::path cleaned = path.has_filename() ? path : path.parent_path();
  TESSERA_RETURN_IF_ERROR(ensureDirectory(cleaned));

  const std::string lockPath = (cleaned / "tessera.lock").string();
  const int fd = ::open(lockPath.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0600);
  if (fd < 0) return ioError(lockPath + ": cannot open the lock file: " + errnoText(errno));
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(fd);
    if (error == EWOULDBLOCK) {
      return ioError(cleaned.string() + ": data directory is in use by another store (" + lockPath +
                     " is locked)");
    }
    return ioError(lockPath + ": cannot lock: " + errnoText(error));
  }
  return DataDirectoryLock(fd);
}

DataDirectoryLock::DataDirectoryLock(DataDirectoryLock&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)) {}

DataDirectoryLock& DataDirectoryLock::operator=(DataDirectoryLock&& other) noexcept {
  if (this != &other) {
    release();
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

DataDirectoryLock::~DataDirectoryLock() {
  release();
}

void DataDirectoryLock::release() {
  // Closing the only descriptor of the open file description drops the flock.
  if (fd_ >= 0) ::close(std::exchange(fd_, -1));
}

}  // namespace tessera::store
