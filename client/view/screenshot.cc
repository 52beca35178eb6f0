#include "client/view/screenshot.h"

#include <stb_image_write.h>

#include <algorithm>
#include <string>
#include <vector>

#include "client/view/gl.h"

namespace tessera::view {

Status writeScreenshot(const std::string& path, int width, int height) {
  if (width <= 0 || height <= 0) return invalidArgument(path + ": empty framebuffer");
  std::vector<unsigned char> pixels(static_cast<size_t>(width) * height * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());
  if (const GLenum error = glGetError(); error != GL_NO_ERROR)
    return internalError(path + ": glReadPixels failed (GL error " + std::to_string(error) + ")");
  // OpenGL's rows run bottom to top; PNG's top to bottom.
  std::vector<unsigned char> flipped(pixels.size());
  const size_t row = static_cast<size_t>(width) * 3;
  for (int y = 0; y < height; ++y) {
    std::copy_n(pixels.data() + static_cast<size_t>(height - 1 - y) * row, row,
                flipped.data() + static_cast<size_t>(y) * row);
  }
  if (!stbi_write_png(path.c_str(), width, height, 3, flipped.data(), static_cast<int>(row))) {
    return ioError(path + ": cannot write the PNG");
  }
  return Status::ok();
}

}  // namespace tessera::view
