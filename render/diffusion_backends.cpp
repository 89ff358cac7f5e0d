#include "render/diffusion_backends.h"

#include <stdexcept>

#include "base/error.h"
#include "render/gl/gl_context.h"
#include "render/gl/pmvc_gl.h"

namespace cutaway {

DiffusionChoice parse_diffusion_choice(const std::string& name) {
  if (name == "auto") return DiffusionChoice::Auto;
  if (name == "cpu") return DiffusionChoice::Cpu;
  if (name == "gl") return DiffusionChoice::Gl;
  throw InternalError("unknown diffusion backend '" + name + "' (auto, cpu or gl)");
}

DiffusionChoice resolve_diffusion_choice(DiffusionChoice choice) {
  if (choice != DiffusionChoice::Auto) return choice;
  bool gpu = false;
  try {
    gpu = create_gpu_context()->hardware();
  } catch (const EnvironmentError&) {
    gpu = false;
  }
  return gpu ? DiffusionChoice::Gl : DiffusionChoice::Cpu;
}

std::unique_ptr<DiffusionBackend> make_diffusion(const DsModel& model,
                                                 const DiffusionOptions& options,
                                                 DiffusionChoice choice) {
  choice = resolve_diffusion_choice(choice);
  return choice == DiffusionChoice::Gl ? make_gl_diffusion(model, options)
                                       : make_cpu_diffusion(model, options);
}

}  // namespace cutaway
