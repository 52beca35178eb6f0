#include "client/view/offscreen_target.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include "client/view/screenshot.h"

namespace tessera::view {

namespace {

Status incomplete(const char* which, GLenum status) {
  char hex[16];
  std::snprintf(hex, sizeof hex, "0x%04x", static_cast<unsigned>(status));
  return internalError(std::string("headless rendering: the ") + which +
                       " framebuffer is incomplete (status " + hex + ")");
}

}  // namespace

Expected<std::unique_ptr<OffscreenTarget>> OffscreenTarget::create(int width, int height, int samples) {
  std::unique_ptr<OffscreenTarget> t(new OffscreenTarget());
  GLint maxSamples = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
  t->width_ = width, t->height_ = height, t->samples_ = std::clamp(samples, 0, static_cast<int>(maxSamples));

  glGenRenderbuffers(1, &t->colour_);
  glBindRenderbuffer(GL_RENDERBUFFER, t->colour_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, t->samples_, GL_RGBA8, width, height);
  glGenRenderbuffers(1, &t->depth_);
  glBindRenderbuffer(GL_RENDERBUFFER, t->depth_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, t->samples_, GL_DEPTH24_STENCIL8, width, height);
  glGenFramebuffers(1, &t->drawFbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, t->drawFbo_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t->colour_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, t->depth_);
  if (GLenum s = glCheckFramebufferStatus(GL_FRAMEBUFFER); s != GL_FRAMEBUFFER_COMPLETE)
    return incomplete("multisampled", s);

  glGenRenderbuffers(1, &t->resolved_);
  glBindRenderbuffer(GL_RENDERBUFFER, t->resolved_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glGenFramebuffers(1, &t->resolveFbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, t->resolveFbo_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t->resolved_);
  if (GLenum s = glCheckFramebufferStatus(GL_FRAMEBUFFER); s != GL_FRAMEBUFFER_COMPLETE)
    return incomplete("resolve", s);
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  t->bind();
  return t;
}

OffscreenTarget::~OffscreenTarget() {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteFramebuffers(1, &drawFbo_);
  glDeleteFramebuffers(1, &resolveFbo_);
  glDeleteRenderbuffers(1, &colour_);
  glDeleteRenderbuffers(1, &depth_);
  glDeleteRenderbuffers(1, &resolved_);
}

void OffscreenTarget::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, drawFbo_);
  if (samples_ > 0) glEnable(GL_MULTISAMPLE);
}

Status OffscreenTarget::writePng(const std::string& path) const {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, drawFbo_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolveFbo_);
  glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, resolveFbo_);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  const Status written = writeScreenshot(path, width_, height_);
  bind();
  return written;
}

}  // namespace tessera::view
