// FileWriter: streams an export to its file through a 1 MiB buffer, so a
// 135 MB OBJ is never held in memory whole (docs/PERFORMANCE.md "File in to
// file out": the OBJ writer built
// the file in one string, 2.3 times the memory of the tool it was measured
// against). Numbers are formatted with std::to_chars: doubles as the shortest
// text that reads back to the same value. Internal to core/io.
#pragma once

#include <charconv>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/util/status.h"

namespace tessera::io_detail {

class FileWriter {
 public:
  // Opens `path` for writing (replacing it); the error names the path.
  static Expected<FileWriter> open(const std::string& path);

  void append(std::string_view text) {
    if (text.size() > kBufferSize - used_) {
      flush();
      if (text.size() > kBufferSize) return writeDirect(text.data(), text.size());
    }
    std::memcpy(buffer_.get() + used_, text.data(), text.size());
    used_ += text.size();
  }
  void append(char c) {
    if (used_ == kBufferSize) flush();
    buffer_[used_++] = c;
  }
  // Shortest round-trip text of a double (at most 24 characters).
  void appendNumber(double value) {
    reserve(32);
    used_ = static_cast<size_t>(std::to_chars(buffer_.get() + used_, buffer_.get() + kBufferSize, value).ptr -
                                buffer_.get());
  }
  void appendNumber(long long value) {
    reserve(24);
    used_ = static_cast<size_t>(std::to_chars(buffer_.get() + used_, buffer_.get() + kBufferSize, value).ptr -
                                buffer_.get());
  }
  // The bytes of a 4-byte value, little-endian (every binary format Tessera
  // writes is little-endian; so is every host it builds on, checked in .cc).
  template <typename T>
  void appendBytes(const T& value) {
    static_assert(sizeof(T) <= 16);
    reserve(sizeof(T));
    std::memcpy(buffer_.get() + used_, &value, sizeof(T));
    used_ += sizeof(T);
  }

  // Flushes and closes; reports the first write error, naming the path.
  Status close();

 private:
  static constexpr size_t kBufferSize = size_t{1} << 20;
  struct Closer {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  FileWriter(std::string path, std::FILE* file);
  void reserve(size_t bytes) {
    if (kBufferSize - used_ < bytes) flush();
  }
  void flush();
  void writeDirect(const char* data, size_t size);

  std::string path_;
  std::unique_ptr<std::FILE, Closer> file_;
  std::unique_ptr<char[]> buffer_;
  size_t used_ = 0;
  int error_ = 0;  // errno of the first failed write
};

}  // namespace tessera::io_detail
