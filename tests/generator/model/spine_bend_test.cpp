// The bent axis (generator/model/spine_bend.h, doc/template-format.md `spine`): a vertical
// spine through the axis changes nothing; a bent one carries every surface onto the curve,
// keeps the skin closed and every other surface inside it, and keeps lengths along the axis;
// spines that fold the object over, turn downwards or bend a mesh template are refused at
// `spine`.
#include "model/spine_bend.h"

#include <gtest/gtest.h>

#include <string>

#include <glm/geometric.hpp>

#include "io/template_parser.h"
#include "model/model_builder.h"
#include "model/model_checks.h"
#include "test_support.h"

namespace cutaway {
namespace {

/// The shipped cucumber (three-fold, 160 mm) with `spine_yaml` added at the top level.
Template cucumber_with(const std::string& spine_yaml) {
  const std::string path = test::source_path("templates/cucumber.yaml").string();
  return parse_template(test::read_file(path) + "\n" + spine_yaml + "\n", path,
                        test::source_path("templates").string());
}

std::string refusal(const std::string& spine_yaml) {
  try {
    build_model(cucumber_with(spine_yaml));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SpineBend, AVerticalSpineThroughTheAxisChangesNothing) {
  const Template bent = cucumber_with("spine: [[0, 0], [0, 100], [0, 250]]");
  Template straight = bent;
  straight.spine = {};
  const DsModel a = build_model(bent), b = build_model(straight);
  ASSERT_EQ(a.surfaces.size(), b.surfaces.size());
  for (size_t i = 0; i < a.surfaces.size(); ++i) {
    const DsMesh &ma = a.surfaces[i].mesh, &mb = b.surfaces[i].mesh;
    ASSERT_EQ(ma.n_vertices(), mb.n_vertices());
    for (auto vh : ma.vertices())
      EXPECT_LT((ma.point(vh) - mb.point(vh)).norm(), 1e-12) << a.surfaces[i].name;
  }
}

TEST(SpineBend, ABentCucumberStaysClosedWithEverySurfaceInsideItsSkin) {
  // A gentle banana-like curve: 60 mm sideways over 210 mm.
  const Template t = cucumber_with("spine: [[0, 0], [8, 70], [25, 140], [60, 215]]");
  const DsModel straight = [&] {
    Template s = t;
    s.spine = {};
    return build_model(s);
  }();
  const DsModel bent = build_model(t);
  // The upper part moved sideways (the spine is 28 mm off the axis at the skin's top, 160 mm
  // up), the bottom stayed.
  EXPECT_GT(bent.bbox_max.x - straight.bbox_max.x, 0.02);
  EXPECT_NEAR(bent.bbox_min.y, straight.bbox_min.y, 2e-3);
  // Skin closed, every surface inside it without crossing (exact predicates).
  std::vector<int> order{t.skin};
  for (int i = 0; i < static_cast<int>(t.surfaces.size()); ++i)
    if (i != t.skin) order.push_back(i);
  EXPECT_NO_THROW(check_model(t, bent, order));
  // Along the axis (x = 0) lengths are kept: the bend is an isometry of the centre line.
  const SpineBend bend(t.spine);
  const glm::dvec3 a = bend.map({0, 0.05, 0}), b = bend.map({0, 0.0501, 0});
  EXPECT_NEAR(glm::length(b - a), 1e-4, 1e-7);
  // The inside of the bend is squeezed, the outside stretched.
  const glm::dvec3 mid{0, 0.14, 0};
  EXPECT_LT(bend.stretch(mid + glm::dvec3(0.01, 0, 0)), 1.0);
  EXPECT_GT(bend.stretch(mid - glm::dvec3(0.01, 0, 0)), 1.0);
}

TEST(SpineBend, SpinesThatFoldTheObjectOrTurnDownAreRefusedAtTheSpine) {
  // A bend of about 15 mm radius in a 36 mm thick cucumber.
  EXPECT_NE(refusal("spine: [[0, 0], [0, 100], [11, 111], [26, 115]]")
                .find("spine: bends more tightly than the object is thick"),
            std::string::npos);
  EXPECT_NE(refusal("spine: [[0, 0], [10, 100], [20, 90]]")
                .find("spine: each point must lie higher than the one before it"),
            std::string::npos);
  const std::string kidney = test::source_path("templates/kidney.yaml").string();
  try {
    parse_template(test::read_file(kidney) + "\nspine: [[0, 0], [1, 10], [3, 20]]\n", kidney,
                   test::source_path("templates").string());
    ADD_FAILURE() << "a spine on a mesh template was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("symmetry none has none"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace cutaway
