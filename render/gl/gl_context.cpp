#include "render/gl/gl_context.h"

// glad first: it defines the GL types and guards GL/gl.h, which osmesa.h would include.
#include <glad/gl.h>
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/osmesa.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/error.h"

namespace cutaway {
namespace {

const char* gl_string(GLenum name) {
  const GLubyte* s = glGetString(name);
  return s ? reinterpret_cast<const char*>(s) : "?";
}

/// The last EGL error as hexadecimal text, e.g. "0x3001".
std::string egl_error() {
  char text[16];
  std::snprintf(text, sizeof text, "0x%04x", static_cast<unsigned>(eglGetError()));
  return text;
}

/// OSMesa (Mesa's llvmpipe, software). Made current on a 1x1 RGBA buffer that nothing draws into.
class OsMesaContext final : public GlContext {
 public:
  OsMesaContext() {
    for (const auto [major, minor] : {std::array{4, 5}, std::array{3, 3}}) {
      const int attribs[] = {OSMESA_FORMAT,
                             OSMESA_RGBA,
                             OSMESA_DEPTH_BITS,
                             0,
                             OSMESA_STENCIL_BITS,
                             0,
                             OSMESA_PROFILE,
                             OSMESA_CORE_PROFILE,
                             OSMESA_CONTEXT_MAJOR_VERSION,
                             major,
                             OSMESA_CONTEXT_MINOR_VERSION,
                             minor,
                             0};
      context_ = OSMesaCreateContextAttribs(attribs, nullptr);
      if (context_) break;
    }
    if (!context_)
      throw EnvironmentError(
          "OSMesa: cannot create an OpenGL 4.5 or 3.3 core context (is Mesa's OSMesa with "
          "llvmpipe installed?)");
    make_current();
    const int version = gladLoadGL(reinterpret_cast<GLADloadfunc>(OSMesaGetProcAddress));
    if (version == 0) {
      OSMesaDestroyContext(context_);
      throw EnvironmentError("OSMesa: cannot load the OpenGL entry points (glad)");
    }
  }

  ~OsMesaContext() override { OSMesaDestroyContext(context_); }

  void make_current() override {
    if (!OSMesaMakeCurrent(context_, dummy_.data(), GL_UNSIGNED_BYTE, 1, 1))
      throw EnvironmentError("OSMesa: cannot make the context current");
  }

  std::string description() const override {
    return std::string("OSMesa: ") + gl_string(GL_RENDERER) + ", " + gl_string(GL_VERSION);
  }
  bool hardware() const override { return false; }

 private:
  OSMesaContext context_ = nullptr;
  std::array<unsigned char, 4> dummy_{};  // the 1x1 RGBA default framebuffer
};

/// EGL on a GPU without a display (EGL_EXT_platform_device), surfaceless: the GL backend's way
/// to a real GPU (doc/architecture.md, Diffusion backends). Software EGL devices
/// (EGL_MESA_device_software) are skipped: OSMesa serves those.
class EglContext final : public GlContext {
 public:
  EglContext() {
    auto query_devices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto query_device_string = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
        eglGetProcAddress("eglQueryDeviceStringEXT"));
    auto platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!query_devices || !query_device_string || !platform_display)
      throw EnvironmentError("EGL: no device enumeration (EGL_EXT_device_enumeration)");
    std::array<EGLDeviceEXT, 16> devices{};
    EGLint count = 0;
    if (!query_devices(static_cast<EGLint>(devices.size()), devices.data(), &count) || count == 0)
      throw EnvironmentError("EGL: no devices (eglQueryDevicesEXT: " + egl_error() + ")");
    std::string reasons;  // why each device was passed over
    for (EGLint i = 0; i < count && context_ == EGL_NO_CONTEXT; ++i) {
      const char* ext = query_device_string(devices[i], EGL_EXTENSIONS);
      const std::string device = "; device " + std::to_string(i) + ": ";
      if (ext && std::strstr(ext, "EGL_MESA_device_software")) {
        reasons += device + "software";
        continue;
      }
      EGLDisplay display = platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
      if (display == EGL_NO_DISPLAY || !eglInitialize(display, nullptr, nullptr)) {
        reasons += device + "eglInitialize failed (" + egl_error() + ")";
        continue;
      }
      const std::string refused = try_context(display);
      if (refused.empty()) {
        display_ = display;
      } else {
        reasons += device + refused;
        eglTerminate(display);
      }
    }
    if (context_ == EGL_NO_CONTEXT)
      throw EnvironmentError("EGL: no GPU device gives an OpenGL 4.5 core context" + reasons);
    make_current();
    if (gladLoadGL(reinterpret_cast<GLADloadfunc>(eglGetProcAddress)) == 0) {
      eglDestroyContext(display_, context_);
      eglTerminate(display_);
      throw EnvironmentError("EGL: cannot load the OpenGL entry points (glad)");
    }
  }
  ~EglContext() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
    eglTerminate(display_);
  }
  void make_current() override {
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
      throw EnvironmentError("EGL: cannot make the context current");
  }
  std::string description() const override {
    return std::string("EGL: ") + gl_string(GL_RENDERER) + ", " + gl_string(GL_VERSION);
  }
  bool hardware() const override { return true; }

 private:
  /// Creates context_ on `display`; returns "" on success, else why not.
  std::string try_context(EGLDisplay display) {
    const char* ext = eglQueryString(display, EGL_EXTENSIONS);
    if (!ext || !std::strstr(ext, "EGL_KHR_surfaceless_context"))
      return "no EGL_KHR_surfaceless_context";
    if (!eglBindAPI(EGL_OPENGL_API)) return "eglBindAPI(OpenGL) failed (" + egl_error() + ")";
    // EGL_SURFACE_TYPE defaults to EGL_WINDOW_BIT, which a device display without a window
    // system has no config for (the NVIDIA driver answers none): ask for pbuffer configs.
    const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                     EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config;
    EGLint n = 0;
    if (!eglChooseConfig(display, config_attribs, &config, 1, &n) || n == 0)
      return "no OpenGL config (" + egl_error() + ")";
    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                      4,
                                      EGL_CONTEXT_MINOR_VERSION,
                                      5,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                      EGL_NONE};
    context_ = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attribs);
    return context_ != EGL_NO_CONTEXT ? ""
                                      : "eglCreateContext(4.5 core) failed (" + egl_error() + ")";
  }
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

std::unique_ptr<GlContext> create_gpu_context() {
  const char* choice = std::getenv("CUTAWAY_GL");
  if (choice && std::string(choice) == "osmesa") {
    throw EnvironmentError("EGL: not tried (CUTAWAY_GL=osmesa)");
  }
  return std::make_unique<EglContext>();
}

std::unique_ptr<GlContext> create_offscreen_context() {
  std::string gpu_error;
  try {
    return create_gpu_context();
  } catch (const EnvironmentError& e) {
    gpu_error = e.what();  // no GPU reachable through EGL: software
  }
  try {
    return std::make_unique<OsMesaContext>();
  } catch (const EnvironmentError& e) {
    throw EnvironmentError(std::string(e.what()) + "; and no GPU: " + gpu_error);
  }
}

}  // namespace cutaway
