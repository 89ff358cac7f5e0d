// Offscreen OpenGL contexts. One interface, one backend per way of reaching OpenGL: EGL on a
// GPU (EGL_EXT_platform_device, no display) and OSMesa (llvmpipe, software) without one
// (doc/architecture.md, Diffusion backends; Style: interfaces with several backends).
#pragma once

#include <memory>
#include <string>

namespace cutaway {

/// An OpenGL core-profile context (4.5, or 3.3 where 4.5 is unavailable) with no window.
/// It is current on the creating thread after construction and all GL entry points are loaded
/// (glad). Rendering goes into framebuffer objects; the default framebuffer is a small dummy.
/// Not copyable or movable; destroying it releases the context.
class GlContext {
 public:
  GlContext() = default;
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;
  virtual ~GlContext() = default;

  /// Makes this context current on the calling thread (contexts are per thread).
  /// @throws EnvironmentError when the backend refuses
  virtual void make_current() = 0;

  /// Human-readable description for logs: backend, GL_RENDERER and GL_VERSION, e.g.
  /// "OSMesa: llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Core Profile) Mesa 22.3.6".
  virtual std::string description() const = 0;
  /// True when the context runs on a GPU (EGL), false for software rendering (OSMesa).
  virtual bool hardware() const = 0;
};

/// Creates an offscreen context with the best backend available: EGL on a GPU device when one
/// gives an OpenGL 4.5 core context, OSMesa otherwise. The environment variable
/// CUTAWAY_GL=osmesa forces OSMesa.
/// @returns a context that is current on the calling thread
/// @throws EnvironmentError with both reasons (OSMesa's and EGL's) when no OpenGL 3.3+ core
///         context can be created or its entry points cannot be loaded
std::unique_ptr<GlContext> create_offscreen_context();

/// Creates an offscreen context on a GPU through EGL only (what `--backend auto` asks for).
/// @throws EnvironmentError when no GPU device gives an OpenGL 4.5 core context, or when
///         CUTAWAY_GL=osmesa
std::unique_ptr<GlContext> create_gpu_context();

}  // namespace cutaway
