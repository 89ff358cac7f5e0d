// Choosing a colour diffusion backend (doc/architecture.md, Diffusion backends):
// `--backend auto|cpu|gl`.
#pragma once

#include <memory>
#include <string>

#include "diffusion/diffusion.h"

namespace cutaway {

/// Which diffusion backend to use.
enum class DiffusionChoice {
  Auto,  ///< gl where a GPU is reachable through EGL, cpu otherwise (llvmpipe is far slower
         ///< than Embree: it is never chosen automatically)
  Cpu,   ///< each point's cube-map texels cast as rays with Embree (make_cpu_diffusion)
  Gl,    ///< the same rays cast in an OpenGL compute shader (make_gl_diffusion): on a GPU,
         ///< or OSMesa without one
};

/// "auto", "cpu" or "gl" to a DiffusionChoice.
/// @throws InternalError for any other text
DiffusionChoice parse_diffusion_choice(const std::string& name);

/// `choice` with Auto replaced by what it picks on this machine (Gl when a GPU is reachable
/// through EGL, else Cpu): probes the GPU for Auto.
DiffusionChoice resolve_diffusion_choice(DiffusionChoice choice);

/// The backend for `choice` (Auto: resolve_diffusion_choice). Both give the same colours
/// within the tolerance the tests state.
/// @throws EnvironmentError when the chosen backend cannot start (see make_cpu_diffusion,
///         make_gl_diffusion)
std::unique_ptr<DiffusionBackend> make_diffusion(const DsModel& model,
                                                 const DiffusionOptions& options,
                                                 DiffusionChoice choice);

}  // namespace cutaway
