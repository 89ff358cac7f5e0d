// Adaptive PMVC sampling of a cap's interior (cross_section.h, CapSampling::Adaptive): diffuse a
// Poisson-disc subset of the vertices, fill in the others by harmonic interpolation over the
// cap's mesh (the cut vertices' colours and the diffused samples are its boundary values), and
// refine where test points halfway between samples disagree with the interpolation.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "base/colour.h"
#include "diffusion/diffusion.h"

namespace cutaway {

/// How sparsely a cap's interior is sampled. Lengths in metres.
struct HarmonicSamplingOptions {
  double spacing_m = 0;        ///< Poisson-disc radius of the first samples
  double min_spacing_m = 0;    ///< refinement halves the radius down to this; a region still
                               ///< failing below it has every vertex diffused
  VisibleTolerance tolerance;  ///< largest accepted differences (colour.h) between a test
                               ///< point's diffused and interpolated values
};

/// Counts of one sampling.
struct HarmonicSamplingCounts {
  size_t free = 0;      ///< vertices to colour
  size_t diffused = 0;  ///< of which diffused (first samples and test points)
  size_t failed = 0;    ///< test points whose interpolation was off
  size_t rounds = 0;    ///< test rounds
};

/// Colours the `free` vertices of a triangle mesh on a plane (`position` #V metres, `triangle`
/// #F, `colour` #V linear RGB, `material` #V; the other vertices' colour and material are
/// boundary values and are not changed) with few PMVC evaluations:
/// 1. the free vertices of a Poisson-disc set of radius spacing_m (greedy in vertex order)
///    are diffused;
/// 2. the rest get the harmonic interpolation of all known values: the solution of the
///    cotangent Laplace equation (weights clamped to at least 0.05) with known vertices fixed,
///    solved by sparse LDLT (Eigen);
/// 3. round by round with the radius halved, a Poisson-disc set of test points is diffused
///    among the vertices still interpolated near last round's failures (the diffused free
///    vertices count as disc centres) (everywhere in the first round); a test point whose
///    diffused value differs from its interpolation by more than `tolerance` allows marks its
///    neighbourhood (1.5 radii) for the next round; once the radius is below min_spacing_m
///    every remaining vertex near a failure is diffused. Then step 2 again.
/// A connected set of free vertices with no known neighbour gets its first vertex diffused;
/// should the solve fail all the same, every vertex still interpolated is diffused.
/// Deterministic (vertex order); every diffusion is one batch.
/// Source: harmonic (Laplace) interpolation of scattered samples over a mesh, with a posteriori
/// refinement; paper §3.2 diffuses every vertex instead.
/// @throws InternalError when the sizes disagree or spacing_m <= 0
HarmonicSamplingCounts sample_harmonically(
    std::span<const glm::dvec3> position, std::span<const glm::uvec3> triangle,
    const std::vector<bool>& free, std::span<glm::dvec3> colour, std::span<glm::dvec2> material,
    const DiffusionBackend& diffusion, const HarmonicSamplingOptions& options);

}  // namespace cutaway
