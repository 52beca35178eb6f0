// Reads the current read framebuffer back and writes it as an RGB PNG
// (stb_image_write from Debian's libstb).
#pragma once

#include <string>

#include "core/util/status.h"

namespace tessera::view {

// Reads the colour buffer selected by glReadBuffer of the bound
// GL_READ_FRAMEBUFFER (OffscreenTarget::writePng binds its resolved one).
Status writeScreenshot(const std::string& path, int width, int height);

}  // namespace tessera::view
