// Seeded placement of pieces in a container (doc/algorithms.md §4): every piece rests on the
// container or on pieces placed before it, and no two pieces interpenetrate. The pile is kept
// as a height field over the container (Tetris-like dropping of conservative piece footprints),
// so non-interpenetration holds by construction; cut faces are turned towards the camera.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "scene.h"
#include "shaded_mesh.h"

namespace cutaway {

/// One piece to place: its mesh in its object frame and the outward normal of its largest cap
/// there (zero for a whole object).
struct LayoutPiece {
  const ShadedMesh* mesh = nullptr;  ///< #V >= 1, metres
  glm::dvec3 cap_normal{0.0};        ///< unit, or zero
};

/// Options of layout_pieces.
struct LayoutOptions {
  double cell_m = 0.001;           ///< height-field cell edge, metres
  int candidates = 64;             ///< random positions tried per piece
  double clearance_m = 0.0002;     ///< gap left between a piece and what it rests on, metres
  double centre_weight = 0.25;     ///< score = rest height + centre_weight * distance to the axis
  glm::dvec3 to_camera{0, 0.7, 0.7};  ///< direction from the scene towards the camera
  double none_radius_m = 0.2;      ///< resting radius on the floor (container type none)
  double tilt_deg = 12;            ///< random tilt of each piece's facing direction, degrees
};

/// Where one piece goes: scene point = translation + rotation * (object-frame point).
struct Placement {
  bool placed = false;  ///< false: no position was found (the container is full)
  glm::dquat rotation{1, 0, 0, 0};
  glm::dvec3 translation{0.0};
};

/// Places `pieces` in the given order. Each piece is turned so that its largest cap faces
/// halfway between up and `to_camera` (a whole object stands upright), tilted by up to
/// tilt_deg and spun about that direction at random; then of `candidates` random positions
/// over the container (every vertex must be over the resting area) the one with the lowest
/// score is taken, at the lowest height where every vertex is above the container's resting
/// surface (exact for its convex surfaces) and the piece's footprint (per cell: its lowest and
/// highest surface points over the cell) clears the pile's height field, by
/// clearance_m; the height field then rises to the piece's top. Deterministic in `seed`.
/// @returns one placement per piece, in input order
std::vector<Placement> layout_pieces(const std::vector<LayoutPiece>& pieces,
                                     const Container& container, const LayoutOptions& options,
                                     uint64_t seed);

}  // namespace cutaway
