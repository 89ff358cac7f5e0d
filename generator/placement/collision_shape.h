// A piece's collision geometry for rigid-body settling (doc/algorithms.md §4, Settling): one
// convex hull when the piece is convex enough, else an approximate convex decomposition (HACD,
// Mamou and Ghorbel 2009, as shipped with Bullet) whose parts are grown back to cover every
// vertex of the piece, so the parts together enclose the whole piece.
#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "assets/scene_assets.h"
#include "pieces/shaded_mesh.h"

namespace cutaway {

/// Options of collision_shape.
struct CollisionShapeOptions {
  /// A piece whose volume is at least this fraction of its convex hull's volume collides as
  /// its hull; a less convex one (a pepper half's cup, an okra slice's ring) is decomposed.
  double min_convexity = 0.8;
  /// HACD's concavity bound, as a fraction of the piece's largest bounding-box extent.
  double concavity = 0.1;
  /// The piece is simplified to about this many triangles before the decomposition (HACD's
  /// time grows faster than the count: a board with four pepper halves spent 5.2 s in physics
  /// at 1500, 1.4 s at 800; the eleven slices of a star fruit take 5.1 s at 800, 1.0 s at 400,
  /// where their parts' union grows from 1.18 to 1.23 times the slices' volume).
  int decomposition_triangles = 400;
  int max_parts = 16;  ///< at most this many convex parts
  /// A part's hull is refined from seed_corners corners (farthest-point sampling of the full
  /// hull's) by adding the corners farthest outside until none lies more than
  /// corner_tolerance_m (metres) outside, keeping at most max_corners: the cost of a contact
  /// grows with them.
  int seed_corners = 24;
  double corner_tolerance_m = 0.0005;
  int max_corners = 128;
};

/// One convex part: the corners of a convex hull of at most max_corners corners, and how far
/// the piece's vertices it stands for lie outside that hull (the rigid body's collision margin
/// must be at least this, so the part still encloses them).
struct ConvexPart {
  std::vector<glm::dvec3> corners;  ///< object frame, metres; >= 4, not coplanar
  double outside_m = 0;             ///< metres, >= 0
};

/// The convex parts of a piece, object frame (metres), and its mass properties.
struct CollisionShape {
  std::vector<ConvexPart> parts;  ///< #parts >= 1
  double volume_m3 = 0;           ///< the piece's enclosed volume, cubic metres
  glm::dvec3 centroid{0.0};       ///< centre of its volume (uniform density), metres
  double convexity = 1;           ///< volume / convex hull volume, in (0, 1]
  bool decomposed = false;        ///< whether `parts` came from the decomposition
};

/// The collision shape of `mesh`, a closed piece wound counter-clockwise seen from outside
/// (#V >= 4 not all coplanar; vertices are welded by exact position). Deterministic.
/// Errors: CUTAWAY_CHECK on an empty or flat mesh.
CollisionShape collision_shape(const ShadedMesh& mesh, const CollisionShapeOptions& options = {});

/// collision_shape of each of `meshes` (#pieces), entry k for mesh k, the pieces shared out over
/// the cores (the process's TBB limit, `--threads`): the same result with any thread count.
/// `processor_seconds`, when given, receives the processor time the pieces took, summed over
/// the threads that made them (thread_processor_seconds): unlike wall time, it does not grow
/// when other work shares the cores.
std::vector<CollisionShape> collision_shapes(const std::vector<ShadedMesh>& meshes,
                                             const CollisionShapeOptions& options = {},
                                             double* processor_seconds = nullptr);

/// The convex parts of a collision shape (collision_shape) as closed meshes for export, in
/// the piece's frame (metres): each part's hull corners, its facets fanned into triangles
/// wound counter-clockwise seen from outside. A part does not grow by its `outside_m`: engines
/// add their own collision margin. Deterministic.
std::vector<AssetHull> collision_hulls(const CollisionShape& shape);

}  // namespace cutaway
