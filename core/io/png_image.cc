#include "core/io/png_image.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <cstring>
#include <filesystem>
#include <memory>

namespace tessera {

namespace {

constexpr int kMaxSide = 16384;

}  // namespace

Expected<Image> readPng(const std::string& path) {
  if (!std::filesystem::exists(path)) return notFound(path + ": no such file");
  int w = 0, h = 0, channels = 0;
  // Checked before decoding, so that a crafted header cannot ask for gigabytes.
  if (!stbi_info(path.c_str(), &w, &h, &channels)) {
    return parseError(path + ": not a readable image (" + std::string(stbi_failure_reason()) + ")");
  }
  if (w <= 0 || h <= 0 || w > kMaxSide || h > kMaxSide) {
    return invalidArgument(path + ": " + std::to_string(w) + " x " + std::to_string(h) + " pixels; at most " +
                           std::to_string(kMaxSide) + " a side");
  }
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels(stbi_load(path.c_str(), &w, &h, &channels, 4),
                                                   stbi_image_free);
  if (!pixels) return parseError(path + ": cannot decode (" + std::string(stbi_failure_reason()) + ")");
  Image image{w, h, {}};
  image.rgba.assign(pixels.get(), pixels.get() + static_cast<size_t>(w) * h * 4);
  return image;
}

Expected<Image> decodePng(const std::string& bytes, const std::string& source) {
  if (bytes.size() > static_cast<size_t>(INT32_MAX)) return invalidArgument(source + ": too large");
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = static_cast<int>(bytes.size());
  int w = 0, h = 0, channels = 0;
  if (!stbi_info_from_memory(data, size, &w, &h, &channels)) {
    return parseError(source + ": not a readable image (" + std::string(stbi_failure_reason()) + ")");
  }
  if (w <= 0 || h <= 0 || w > kMaxSide || h > kMaxSide) {
    return invalidArgument(source + ": " + std::to_string(w) + " x " + std::to_string(h) +
                           " pixels; at most " + std::to_string(kMaxSide) + " a side");
  }
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels(stbi_load_from_memory(data, size, &w, &h, &channels, 4),
                                                   stbi_image_free);
  if (!pixels) return parseError(source + ": cannot decode (" + std::string(stbi_failure_reason()) + ")");
  Image image{w, h, {}};
  image.rgba.assign(pixels.get(), pixels.get() + static_cast<size_t>(w) * h * 4);
  return image;
}

Status writePng(const std::string& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != static_cast<size_t>(image.width) * image.height * 4) {
    return invalidArgument(path + ": not a whole image");
  }
  if (!stbi_write_png(path.c_str(), image.width, image.height, 4, image.rgba.data(), image.width * 4)) {
    return ioError(path + ": cannot write the PNG");
  }
  return Status::ok();
}

}  // namespace tessera
