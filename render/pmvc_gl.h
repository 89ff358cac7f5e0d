// The OpenGL PMVC backend (paper §3.2; design/algorithms.md §2, Backends: gl): per point, "render
// all the DSs viewed from the interior vertex to a cube map", weight every texel's colour "by the
// inverse of the distances", and sum on the GPU, so that "the integration [is] performed entirely
// on the GPU". Same sheets, directions and weights as the CPU backend (make_cpu_diffusion).
#pragma once

#include <memory>

#include "diffusion/diffusion.h"

namespace cutaway {

/// The GL backend of DiffusionBackend; name() is "gl".
///
/// Semantics match make_cpu_diffusion: the sheets of make_diffusion_sheets (a two-faced sheet
/// shows colour_front where the ray meets its front, counter-clockwise, face), the texel centres
/// of make_cube_directions(options.cube_size) as directions, and weight = exact texel solid angle
/// / Euclidean distance to the nearest hit (depth-tested, computed per fragment from the
/// interpolated offset to the point, not from the depth buffer). Results are linear RGB; a point
/// that sees nothing is black.
///
/// How: all sheets are uploaded once. Points are processed in batches (up to 341 per batch, and
/// at most ~64 MiB of targets): one instanced draw renders every cube face of every point of
/// the batch into its own layer of an RGBA32F 2D array texture (colour / r, 1 / r), with a
/// reversed, infinite-far 32-bit float depth buffer (near plane 1e-7 m), then one compute
/// dispatch sums each point's 6 n^2 texels, times their solid angles, in double precision and a
/// fixed order, and one buffer read returns the batch. Results are bit-identical for a point
/// whatever the batch it is in or its position there.
///
/// The backend owns its own offscreen context (create_offscreen_context(): EGL on a GPU, else
/// OSMesa) and makes it current at the start of every diffuse() call, on the calling thread;
/// calls are serialised by a mutex. Another GL context current on that thread is left not current.
/// options.threads is ignored: the GL driver chooses its own parallelism (llvmpipe: one thread
/// per core for rasterisation).
///
/// @param model   the DS model; only its sheets are kept (the model may be destroyed after)
/// @param options cube_size >= 1 texels per cube face edge
/// @throws std::invalid_argument when options.cube_size < 1 or exceeds the texture size limit
/// @throws std::runtime_error when no offscreen OpenGL context can be created, when it lacks
///         OpenGL 4.3 (compute shaders), ARB_clip_control (or 4.5) or
///         ARB_shader_viewport_layer_array (gl_Layer from the vertex shader), or when a shader
///         fails to compile
std::unique_ptr<DiffusionBackend> make_gl_diffusion(const DsModel& model,
                                                    const DiffusionOptions& options);

}  // namespace cutaway
