// An offscreen colour target for the renderers of render/: a floating-point framebuffer
// (multisampled where the driver allows, with a single-sample resolve target), read back as an
// sRGB8 Image. Internal to render/: it needs the glad loader header, which is not exported.
#pragma once

#include <glad/gl.h>

#include <cstdint>
#include <string>

#include <glm/vec3.hpp>

#include "render/gl/gl_context.h"
#include "render/image/image.h"

namespace cutaway {

/// A width x height colour target on the current GL context: a framebuffer with one linear-RGB
/// floating-point renderbuffer (`internal_format`, GL_RGBA16F or GL_RGBA32F) of `samples`
/// samples, plus a single-sample framebuffer of the same format that the samples are resolved
/// (averaged, in linear RGB) into before readback. Where the driver offers fewer samples, or
/// refuses the multisampled buffer, it falls back to fewer (down to 1: no MSAA).
/// Needs `context` current for its whole life; deletes its GL objects on destruction.
/// Neither copyable nor movable.
class OffscreenTarget {
 public:
  /// @param context       current context; named in error messages
  /// @param width, height pixels, >= 1
  /// @param samples       MSAA samples requested, >= 1; clamped to GL_MAX_SAMPLES
  /// @param caller        prefix of error messages, e.g. "render_model_preview"
  /// @param internal_format GL_RGBA16F or GL_RGBA32F
  /// @throws InternalError when width or height exceeds GL_MAX_RENDERBUFFER_SIZE
  /// @throws EnvironmentError when not even the single-sample framebuffer can be created
  OffscreenTarget(const GlContext& context, int width, int height, int samples,
                  const std::string& caller, GLenum internal_format = GL_RGBA16F);
  OffscreenTarget(const OffscreenTarget&) = delete;
  OffscreenTarget& operator=(const OffscreenTarget&) = delete;
  ~OffscreenTarget();

  /// Binds the framebuffer to draw into (GL_FRAMEBUFFER) and sets the viewport to all of it.
  void bind() const;

  /// Binds, then clears to the opaque colour `background_srgb` (sRGB 0..1, stored linear).
  void clear(const glm::dvec3& background_srgb) const;

  /// Resolves the samples, reads the pixels back and converts them: rows top first, linear RGB
  /// -> sRGB8 (linear_to_srgb8), alpha 255 (the targets are drawn opaque).
  /// @throws EnvironmentError when OpenGL reports an error
  Image resolve_and_read() const;

  int width() const { return width_; }
  int height() const { return height_; }
  /// Samples per pixel actually in use (1: not multisampled).
  int samples() const { return samples_; }

 private:
  const GlContext& context_;
  std::string caller_;
  int width_ = 0, height_ = 0, samples_ = 1;
  GLuint resolved_ = 0, resolved_buffer_ = 0;          // single-sample framebuffer
  GLuint multisampled_ = 0, multisampled_buffer_ = 0;  // 0 when samples_ == 1
};

}  // namespace cutaway
