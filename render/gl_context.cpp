#include "gl_context.h"

// glad first: it defines the GL types and guards GL/gl.h, which osmesa.h would include.
#include <glad/gl.h>
#include <GL/osmesa.h>

#include <array>
#include <stdexcept>
#include <vector>

namespace cutaway {
namespace {

const char* gl_string(GLenum name) {
  const GLubyte* s = glGetString(name);
  return s ? reinterpret_cast<const char*>(s) : "?";
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
      throw std::runtime_error(
          "OSMesa: cannot create an OpenGL 4.5 or 3.3 core context (is Mesa's OSMesa with "
          "llvmpipe installed?)");
    make_current();
    const int version = gladLoadGL(reinterpret_cast<GLADloadfunc>(OSMesaGetProcAddress));
    if (version == 0) {
      OSMesaDestroyContext(context_);
      throw std::runtime_error("OSMesa: cannot load the OpenGL entry points (glad)");
    }
  }

  ~OsMesaContext() override { OSMesaDestroyContext(context_); }

  void make_current() override {
    if (!OSMesaMakeCurrent(context_, dummy_.data(), GL_UNSIGNED_BYTE, 1, 1))
      throw std::runtime_error("OSMesa: cannot make the context current");
  }

  std::string description() const override {
    return std::string("OSMesa: ") + gl_string(GL_RENDERER) + ", " + gl_string(GL_VERSION);
  }

 private:
  OSMesaContext context_ = nullptr;
  std::array<unsigned char, 4> dummy_{};  // the 1x1 RGBA default framebuffer
};

}  // namespace

std::unique_ptr<GlContext> create_offscreen_context() { return std::make_unique<OsMesaContext>(); }

}  // namespace cutaway
