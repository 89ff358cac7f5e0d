// Vertex tangents for normal-mapped meshes (glTF's TANGENT attribute): per vertex, the unit
// direction of increasing u on the surface and the handedness that gives the direction of the
// normal map's +Y (up the texture: decreasing v), after Lengyel 2001, "Computing Tangent Space
// Basis Vectors for an Arbitrary Mesh" (per-triangle uv gradients summed at the vertices, then
// made orthogonal to the vertex normal).
#pragma once

#include <span>
#include <vector>

#include <glm/ext/vector_uint3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace cutaway {

/// The tangents of #V vertices with `position` (metres), unit `normal` and texture coordinates
/// `uv` (glTF: v down from the top row) over the triangles of `lists` (indices below #V): per
/// vertex (x, y, z, w), xyz the sum over its triangles of d(position)/du made orthogonal to its
/// normal and normalised, w = +1 when cross(normal, xyz) points up the texture (along the
/// summed -d(position)/dv) and -1 otherwise, so that glTF's bitangent cross(normal, xyz) * w
/// is the normal map's +Y. A vertex without a usable gradient (in no triangle, or with
/// degenerate uv) gets a unit vector orthogonal to its normal and w = +1. Deterministic.
/// Preconditions: the three arrays are #V long.
std::vector<glm::dvec4> vertex_tangents(const std::vector<glm::dvec3>& position,
                                        const std::vector<glm::dvec3>& normal,
                                        const std::vector<glm::dvec2>& uv,
                                        const std::vector<std::span<const glm::uvec3>>& lists);

}  // namespace cutaway
