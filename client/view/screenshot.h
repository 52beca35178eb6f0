// Reads the current framebuffer back and writes it as an RGB PNG
// (stb_image_write from Debian's libstb).
#pragma once

#include <string>

#include "core/util/status.h"

namespace tessera::view {

// Reads the back buffer of the current context (call before swapping).
Status writeScreenshot(const std::string& path, int width, int height);

}  // namespace tessera::view
