// The vertex data every coloured triangle mesh of the pipeline shares: pieces as cut
// (ShadedMesh, pieces/shaded_mesh.h) and meshes as exported (AssetMesh, assets/scene_assets.h)
// both extend it, so that a piece becomes an asset by copying this part, not field by field.
#pragma once

#include <vector>

#include <glm/vec3.hpp>

namespace cutaway {

/// Plain data: position, normal and colour have the same length #V.
struct ColouredMesh {
  std::vector<glm::dvec3> position;  ///< #V, metres
  std::vector<glm::dvec3> normal;    ///< #V, unit shading normals (outward)
  std::vector<glm::dvec3> colour;    ///< #V, linear RGB 0..1
  std::vector<glm::uvec3> triangle;  ///< #F indices into the vertex arrays, counter-clockwise
                                     ///< seen from outside (the normal side)
};

}  // namespace cutaway
