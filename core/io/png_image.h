// PNG images in memory (8-bit RGBA, rows top to bottom), read and written
// with Debian's libstb (stb_image, stb_image_write). For the image morph
// (core/morph/image_morph.h, docs/INTERPOLATION.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/util/status.h"

namespace tessera {

struct Image {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;  // width * height * 4

  uint8_t* at(int x, int y) { return rgba.data() + (static_cast<size_t>(y) * width + x) * 4; }
  const uint8_t* at(int x, int y) const { return rgba.data() + (static_cast<size_t>(y) * width + x) * 4; }
};

// Errors name the file: missing, not a PNG, or larger than 16384 pixels a side.
Expected<Image> readPng(const std::string& path);
// The same from bytes in memory (a morph document's images); `source` names them.
Expected<Image> decodePng(const std::string& bytes, const std::string& source);
Status writePng(const std::string& path, const Image& image);

}  // namespace tessera
