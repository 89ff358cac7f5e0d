#include "diffusion/diffusion_sheets.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "test_support.h"

namespace cutaway {
namespace {

/// A tetrahedron 1 cm across whose corner 0 has no blur and the other corners 2 mm.
DsModel tetrahedron_blurred_but_one_corner() {
  DsModel model;
  model.surfaces.push_back(test::blurred_tetrahedron(0.0, 0.01, {0.0, 0.002, 0.002, 0.002}));
  return model;
}

// A blurred surface gives two sheets whose vertices are its blur_sheet_points, the front one
// out along the normal and the back one in; where the blur falls to 0 they stay
// kMinSheetOffset_m apart from the surface, so they never meet.
TEST(DiffusionSheets, BlurSheetsLieAtTheBlurAndAtLeastTheSmallestOffsetApart) {
  const DsModel model = tetrahedron_blurred_but_one_corner();
  const DsMesh& mesh = model.surfaces[0].mesh;
  ASSERT_TRUE(is_blurred(mesh));
  const std::vector<DiffusionSheet> sheets = make_diffusion_sheets(model);
  ASSERT_EQ(sheets.size(), 2u);
  const std::vector<glm::dvec3> normals = vertex_normals(mesh);
  for (auto vh : mesh.vertices()) {
    const glm::dvec3 p = to_glm(mesh.point(vh));
    const double expected = std::max(mesh.data(vh).blur, kMinSheetOffset_m);
    for (const int side : {+1, -1}) {
      const glm::dvec3 q = blur_sheet_point(mesh, normals, vh, side);
      EXPECT_NEAR(glm::dot(q - p, normals[vh.idx()]), side * expected, 1e-12);
      const glm::vec3 drawn = sheets[side > 0 ? 0 : 1].position[vh.idx()];
      EXPECT_NEAR(glm::distance(glm::dvec3(drawn), q), 0.0, 1e-8);
    }
    EXPECT_EQ(blur_sheet_point(mesh, normals, vh, 0), p);
  }
  EXPECT_FALSE(sheets[0].two_faced);
  EXPECT_FALSE(sheets[1].two_faced);
}

// A surface without blur is one two-faced sheet where it lies.
TEST(DiffusionSheets, AnUnblurredSurfaceIsOneTwoFacedSheet) {
  DsModel model = tetrahedron_blurred_but_one_corner();
  DsMesh& mesh = model.surfaces[0].mesh;
  for (auto vh : mesh.vertices()) mesh.data(vh).blur = 0;
  ASSERT_FALSE(is_blurred(mesh));
  const std::vector<DiffusionSheet> sheets = make_diffusion_sheets(model);
  ASSERT_EQ(sheets.size(), 1u);
  EXPECT_TRUE(sheets[0].two_faced);
  for (auto vh : mesh.vertices())
    EXPECT_EQ(glm::dvec3(sheets[0].position[vh.idx()]),
              glm::dvec3(glm::vec3(to_glm(mesh.point(vh)))));
}

}  // namespace
}  // namespace cutaway
