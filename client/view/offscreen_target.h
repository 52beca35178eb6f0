// Where headless frames are drawn: a multisampled framebuffer object
// (colour and depth renderbuffers with `samples` samples per pixel),
// resolved into a single-sampled one before the pixels are read back, the
// same anti-aliasing a window gets from GLFW_SAMPLES. With 0 samples it is
// a plain framebuffer and the resolve is a copy.
#pragma once

#include <memory>
#include <string>

#include "client/view/gl.h"
#include "core/util/status.h"

namespace tessera::view {

class OffscreenTarget {
 public:
  // Needs a current OpenGL 3.3 context. `samples` is capped at the
  // driver's GL_MAX_SAMPLES.
  static Expected<std::unique_ptr<OffscreenTarget>> create(int width, int height, int samples);
  ~OffscreenTarget();
  OffscreenTarget(const OffscreenTarget&) = delete;
  OffscreenTarget& operator=(const OffscreenTarget&) = delete;

  // Binds the multisampled framebuffer for drawing.
  void bind() const;
  // Resolves the samples and writes the picture as an RGB PNG.
  Status writePng(const std::string& path) const;

  int width() const { return width_; }
  int height() const { return height_; }
  int samples() const { return samples_; }

 private:
  OffscreenTarget() = default;
  int width_ = 0, height_ = 0, samples_ = 0;
  GLuint drawFbo_ = 0, colour_ = 0, depth_ = 0;  // multisampled
  GLuint resolveFbo_ = 0, resolved_ = 0;         // single-sampled
};

}  // namespace tessera::view
