#include "core/util/file_io.h"

#include <filesystem>
#include <fstream>
#include <sstream>

namespace tessera {

Expected<std::string> readFile(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return notFound(path + ": file not found");
  if (!std::filesystem::is_regular_file(path, ec)) return ioError(path + ": not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) return ioError(path + ": cannot open for reading");
  std::ostringstream data;
  data << in.rdbuf();
  if (in.bad()) return ioError(path + ": read error");
  return data.str();
}

}  // namespace tessera
