#include "model/crossing_test.h"

#include <gtest/gtest.h>

#include "test_support.h"

namespace cutaway {
namespace {

/// One surface: a tetrahedron `size` across (metres) at the origin, every corner of blur
/// `blur` (metres), and a second, larger one far away of blur `far_blur`, so that the
/// largest blur of the set is not the small one's.
DsModel two_blurred_tetrahedra(double size, double blur, double far_blur) {
  DsModel model;
  model.surfaces.push_back(test::blurred_tetrahedron(0.0, size, {blur, blur, blur, blur}));
  model.surfaces.push_back(
      test::blurred_tetrahedron(0.5, 20 * size, {far_blur, far_blur, far_blur, far_blur}));
  return model;
}

// A point near a surface whose triangles are smaller than the largest blur of the set lies
// within its blur: every triangle near it is tested, also those wholly inside the ball of the
// largest blur around the point (CGAL's Sphere_3 is the sphere's surface and misses them). A
// point farther than the blur is not within it.
TEST(CrossingTest, APointNearSmallBlurredTrianglesLiesWithinTheirBlur) {
  const DsModel model = two_blurred_tetrahedra(0.0005, 0.0015, 0.003);
  const CrossingTest test({&model.surfaces[0].mesh, &model.surfaces[1].mesh}, true);
  // 0.3 mm below the small tetrahedron's base; its triangles lie within 1 mm of the point,
  // wholly inside the 3 mm ball.
  EXPECT_TRUE(test.within_blur({0.0002, 0.0002, -0.0003}));
  // 2 mm below: farther than its 1.5 mm blur, nearer than the largest.
  EXPECT_FALSE(test.within_blur({0.0002, 0.0002, -0.002}));
  // Without the blur's sheets nothing is within a blur.
  const CrossingTest plain({&model.surfaces[0].mesh, &model.surfaces[1].mesh}, false);
  EXPECT_FALSE(plain.within_blur({0.0002, 0.0002, -0.0003}));
}

}  // namespace
}  // namespace cutaway
