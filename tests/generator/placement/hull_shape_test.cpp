// HullShape's support mapping against Bullet's own (doc/algorithms.md §4, Settling): the same
// corner for every direction, on point sets with ties, duplicates and every corner count
// around the block size.
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "base/random.h"
#include "placement/hull_shape.h"

namespace cutaway {
namespace {

/// Bullet's answer: its own convex hull shape of the same corners.
btVector3 bullet_support(const std::vector<btVector3>& corners, const btVector3& d) {
  btConvexHullShape hull;
  for (const btVector3& c : corners) hull.addPoint(c, false);
  return hull.localGetSupportingVertexWithoutMargin(d);
}

/// Whether a and b are the same corner: equal coordinates, bit for bit.
bool same(const btVector3& a, const btVector3& b) {
  return a.x() == b.x() && a.y() == b.y() && a.z() == b.z();
}

TEST(HullShape, GivesBulletsCornerForEveryDirection) {
  Rng rng(7);
  for (int count = 1; count <= 40; ++count) {
    std::vector<btVector3> corners;
    for (int i = 0; i < count; ++i) {
      const glm::dvec3 p = random_direction(rng) * rng.uniform(0.5, 2.0);
      corners.emplace_back(static_cast<float>(p.x), static_cast<float>(p.y),
                           static_cast<float>(p.z));
    }
    const HullShape shape(corners);
    EXPECT_EQ(shape.getShapeType(), CUSTOM_POLYHEDRAL_SHAPE_TYPE);
    for (int k = 0; k < 200; ++k) {
      const glm::dvec3 d = random_direction(rng);
      const btVector3 dir(static_cast<float>(d.x), static_cast<float>(d.y),
                          static_cast<float>(d.z));
      const btVector3 got = shape.localGetSupportingVertexWithoutMargin(dir);
      ASSERT_TRUE(same(got, bullet_support(corners, dir))) << count << " corners, case " << k;
    }
  }
}

TEST(HullShape, TiesGoToTheFirstCornerAsInBullet) {
  // A cube's corners and the middles of its faces, listed twice, in an order where the later
  // copies of a maximum come in other lanes and blocks than the first: along an axis four
  // corners and a face middle tie, and along a diagonal of a face two corners tie.
  std::vector<btVector3> corners;
  for (int copy = 0; copy < 2; ++copy) {
    for (int i = 7; i >= 0; --i)
      corners.emplace_back(i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 1.0f : -1.0f);
    for (int axis = 0; axis < 3; ++axis)
      for (float side : {1.0f, -1.0f}) {
        btVector3 m(0, 0, 0);
        m[axis] = side;
        corners.push_back(m);
      }
  }
  const HullShape shape(corners);
  btConvexHullShape bullet;
  for (const btVector3& c : corners) bullet.addPoint(c, false);
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z) {
        const btVector3 d(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z));
        const btVector3 got = shape.localGetSupportingVertexWithoutMargin(d);
        const btVector3 want = bullet.localGetSupportingVertexWithoutMargin(d);
        EXPECT_TRUE(same(got, want)) << x << " " << y << " " << z;
        // Bullet's first maximum: the same index, not only the same coordinates.
        size_t first = corners.size();
        for (size_t i = 0; i < corners.size() && first == corners.size(); ++i)
          if (same(corners[i], want)) first = i;
        EXPECT_LT(first, 8u + 6u) << "the first copy";
      }
}

TEST(HullShape, ADirectionThatIsNotANumberGivesTheFirstCorner) {
  const std::vector<btVector3> corners = {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {-1, -1, -1}};
  const HullShape shape(corners);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(same(shape.localGetSupportingVertexWithoutMargin(btVector3(nan, 0, 0)), corners[0]));
}

}  // namespace
}  // namespace cutaway
