// The OpenGL PMVC backend (paper §3.2; doc/algorithms.md §2, Backends: gl): the colour at a
// point is the average over its cube map's texels of the colour each texel sees, weighted "by
// the inverse of the distances", with "the integration performed entirely on the GPU". The
// texels are cast as rays in a compute shader instead of rasterised: the result is the same
// (a rasteriser samples each texel at its centre, our ray goes through it), and a GPU's compute
// units are many more than its raster units. Measured on an H100 (graphics on a few of its
// 132 SMs): a tomato cut's 2,340 points took 1.7 s rasterised (instanced cube faces; 2.3 s with
// per-face culling in a geometry shader) and 10 ms cast.
#pragma once

#include <memory>

#include "diffusion/diffusion.h"

namespace cutaway {

/// The GL backend of DiffusionBackend; name() is "gl".
///
/// Semantics match make_cpu_diffusion: the sheets of make_diffusion_sheets (a two-faced sheet
/// shows colour_front where the ray meets its front face), the texel centres of
/// make_cube_directions(options.cube_size) turned by each point's cube_rotation as ray
/// directions, the nearest hit at t >= 0, and weight = exact texel solid angle / hit distance.
/// Results are linear RGB; a point that sees nothing is black. Agrees with the cpu backend to
/// about 1e-8 (float rounding of the same rays).
///
/// How: the sheets' triangles are put into a BVH once (build_sheet_bvh) and uploaded with the
/// vertices' colours and material channels. Points go in batches of up to 16,384, one compute
/// dispatch each (shaders/pmvc_trace.comp): a work group of 256 threads per point casts its
/// 6 n^2 rays through the BVH (with adaptive directions, the coarse rays and the fine rays of
/// the texels adaptive_directions.h refines, by the cpu backend's rule) and sums colour / r,
/// 1 / r and material / r, times the solid angles, in double precision in a fixed order; one
/// buffer read returns the batch. Results are bit-identical for a point whatever the batch it
/// is in or its position there.
///
/// The backend owns its own offscreen context (create_offscreen_context(): EGL on a GPU, else
/// OSMesa) and makes it current at the start of every diffuse() call, on the calling thread;
/// calls are serialised by a mutex. Another GL context current on that thread is left not current.
/// options.threads is ignored: the GL driver chooses its own parallelism (llvmpipe: one thread
/// per core).
///
/// @param model   the DS model; only its sheets are kept (the model may be destroyed after)
/// @param options cube_size >= 1 texels per cube face edge
/// @throws InternalError when options.cube_size < 1
/// @throws EnvironmentError when no offscreen OpenGL context can be created, when it lacks
///         OpenGL 4.3 (compute shaders), when the shader fails to compile, or when the sheets'
///         BVH is deeper than the shader's traversal stack (64)
std::unique_ptr<DiffusionBackend> make_gl_diffusion(const DsModel& model,
                                                    const DiffusionOptions& options);

}  // namespace cutaway
