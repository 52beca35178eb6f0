#include "core/io/file_writer.h"

#include <bit>
#include <cerrno>

namespace tessera::io_detail {

static_assert(std::endian::native == std::endian::little,
              "binary exports are written little-endian byte for byte");

FileWriter::FileWriter(std::string path, std::FILE* file)
    : path_(std::move(path)), file_(file), buffer_(new char[kBufferSize]) {}

Expected<FileWriter> FileWriter::open(const std::string& path) {
  errno = 0;
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) return ioError(path + ": cannot open for writing: " + std::strerror(errno));
  return FileWriter(path, file);
}

void FileWriter::writeDirect(const char* data, size_t size) {
  if (error_ != 0 || size == 0) return;
  errno = 0;
  if (std::fwrite(data, 1, size, file_.get()) != size) error_ = errno != 0 ? errno : EIO;
}

void FileWriter::flush() {
  writeDirect(buffer_.get(), used_);
  used_ = 0;
}

Status FileWriter::close() {
  flush();
  // fclose flushes stdio's own buffer; a full disk often shows up only here.
  errno = 0;
  if (std::fclose(file_.release()) != 0 && error_ == 0) error_ = errno != 0 ? errno : EIO;
  if (error_ != 0) return ioError(path_ + ": write failed: " + std::strerror(error_));
  return Status::ok();
}

}  // namespace tessera::io_detail
