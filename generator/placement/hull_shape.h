// A convex hull for Bullet whose support mapping is faster than Bullet's own and gives the same
// corner, bit for bit (doc/algorithms.md §4, Settling).
#pragma once

#include <span>
#include <vector>

#include <BulletCollision/CollisionShapes/btConvexHullShape.h>

namespace cutaway {

/// A btConvexHullShape of fixed corners whose support mapping (the corner farthest along a
/// direction: what GJK, EPA and the plane contact ask a convex shape for, many times a step)
/// scans four corners at a time. Bullet as Debian builds it scans them one by one, each
/// comparison waiting for the last; that scan was a third of the settling time of a salad.
///
/// The answer is the one Bullet's scan gives: each corner's dot product is rounded the same
/// way ((x dx + y dy) + z dz in float, no fused multiply-add), and of equal maxima the first
/// corner wins. The shape reports CUSTOM_POLYHEDRAL_SHAPE_TYPE so that Bullet calls this
/// support mapping instead of inlining its own; it stays polyhedral, so contacts are still
/// clipped face against face (initializePolyhedralFeatures).
ATTRIBUTE_ALIGNED16(class) HullShape final : public btConvexHullShape {
 public:
  BT_DECLARE_ALIGNED_ALLOCATOR();

  /// The hull of `corners` (#corners >= 1, Bullet units, object frame). Computes the local
  /// bounding box; the caller adds polyhedral features and the margin.
  explicit HullShape(std::span<const btVector3> corners);

  /// The corner farthest along `direction` (times the local scaling, as Bullet's); the first
  /// corner when no dot product is a number.
  btVector3 localGetSupportingVertexWithoutMargin(const btVector3& direction) const override;

 private:
  /// The corners' coordinates by axis, padded with NaN (never a maximum) to whole blocks.
  std::vector<float> x_, y_, z_;
};

}  // namespace cutaway
