#include "render/gl/offscreen_target.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "base/colour.h"
#include "base/error.h"

namespace cutaway {
namespace {

/// A framebuffer with one colour renderbuffer of `samples` samples (1: not multisampled).
/// Returns false, with nothing left allocated, when the driver does not accept it.
bool make_colour_framebuffer(int width, int height, int samples, GLenum internal_format,
                             GLuint& framebuffer, GLuint& renderbuffer) {
  glGenRenderbuffers(1, &renderbuffer);
  glBindRenderbuffer(GL_RENDERBUFFER, renderbuffer);
  if (samples > 1)
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, internal_format, width, height);
  else glRenderbufferStorage(GL_RENDERBUFFER, internal_format, width, height);
  glGenFramebuffers(1, &framebuffer);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, renderbuffer);
  const bool ok = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE &&
                  glGetError() == GL_NO_ERROR;
  if (!ok) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &framebuffer);
    glDeleteRenderbuffers(1, &renderbuffer);
    framebuffer = renderbuffer = 0;
  }
  return ok;
}

}  // namespace

OffscreenTarget::OffscreenTarget(const GlContext& context, int width, int height, int samples,
                                 const std::string& caller, GLenum internal_format)
    : context_(context), caller_(caller), width_(width), height_(height) {
  GLint max_side = 0, max_samples = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_side);
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  if (width < 1 || height < 1 || width > max_side || height > max_side)
    throw InternalError(caller_ + ": image size " + std::to_string(width) + "x" +
                        std::to_string(height) + " exceeds the GL limit " +
                        std::to_string(max_side) + " of " + context.description());
  if (!make_colour_framebuffer(width, height, 1, internal_format, resolved_, resolved_buffer_))
    throw EnvironmentError(caller_ + ": cannot create a floating-point framebuffer on " +
                           context.description());
  // Try the requested count, clamped to the driver's maximum, then fewer until one is accepted.
  for (int s = std::min(samples, std::max(max_samples, 1)); s > 1; s /= 2) {
    if (make_colour_framebuffer(width, height, s, internal_format, multisampled_,
                                multisampled_buffer_)) {
      samples_ = s;
      break;
    }
  }
}

OffscreenTarget::~OffscreenTarget() {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  const GLuint framebuffers[2] = {resolved_, multisampled_};
  const GLuint renderbuffers[2] = {resolved_buffer_, multisampled_buffer_};
  glDeleteFramebuffers(2, framebuffers);  // 0 names are ignored
  glDeleteRenderbuffers(2, renderbuffers);
}

void OffscreenTarget::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, multisampled_ ? multisampled_ : resolved_);
  glViewport(0, 0, width_, height_);
}

void OffscreenTarget::clear(const glm::dvec3& background_srgb) const {
  bind();
  const glm::dvec3 background = srgb_to_linear(background_srgb);
  glClearColor(static_cast<float>(background.r), static_cast<float>(background.g),
               static_cast<float>(background.b), 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
}

Image OffscreenTarget::resolve_and_read() const {
  if (multisampled_) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, multisampled_);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolved_);
    glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT,
                      GL_NEAREST);
  }
  const auto pixel_count = static_cast<size_t>(width_) * height_;
  std::vector<float> linear(4 * pixel_count);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, resolved_);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, linear.data());
  if (const GLenum error = glGetError(); error != GL_NO_ERROR) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", error);
    throw EnvironmentError(caller_ + ": OpenGL error " + code + " on " + context_.description());
  }

  // GL rows are bottom first; Image rows are top first. Linear -> sRGB8 on the CPU.
  Image image{width_, height_, std::vector<uint8_t>(4 * pixel_count)};
  const auto row_floats = static_cast<size_t>(4 * width_);
  for (int y = 0; y < height_; ++y) {
    const float* src = linear.data() + static_cast<size_t>(height_ - 1 - y) * row_floats;
    uint8_t* dst = image.rgba.data() + static_cast<size_t>(y) * row_floats;
    for (int x = 0; x < width_; ++x) {
      for (int c = 0; c < 3; ++c) dst[4 * x + c] = linear_to_srgb8(src[4 * x + c]);
      dst[4 * x + 3] = 255;  // opaque
    }
  }
  return image;
}

}  // namespace cutaway
