// Cut segments (doc/algorithms.md §3 step 1): end points on the plane, closed loops for
// closed surfaces even when the plane runs through mesh vertices and along mesh edges, one
// consistent orientation, and the DS attributes carried along.
#include <algorithm>
#include <cmath>
#include <map>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "base/colour.h"
#include "io/template_parser.h"
#include "model/inside_test.h"
#include "model/model_builder.h"
#include "section/cut_segments.h"
#include "test_support.h"

namespace cutaway {
namespace {

using test::model_of;
using test::plane_of;

std::string describe(const Plane& p) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "plane (%g, %g, %g)/(%g, %g, %g)", p.point.x, p.point.y, p.point.z,
                p.normal.x, p.normal.y, p.normal.z);
  return buf;
}

/// Every cut loop of a closed surface closes: each end point of a surface's segments appears
/// exactly twice (within 1e-12 m), once as a start and once as an end. The cut of an open
/// surface (a `span`) is made of chains: no end point starts or ends two segments.
void expect_closed_loops(const DsModel& model, const Plane& plane, const std::string& what,
                         const std::vector<CutSegment>& segs) {
  for (size_t si = 0; si < model.surfaces.size(); ++si) {
    const bool closed = closed_surface(model.surfaces[si].mesh);
    std::vector<const CutSegment*> mine;
    for (const CutSegment& s : segs)
      if (s.surface == static_cast<int>(si)) mine.push_back(&s);
    size_t open = 0, branched = 0;
    for (const CutSegment* s : mine) {
      for (const glm::dvec3* p : {&s->a, &s->b}) {
        size_t starts = 0, ends = 0;
        for (const CutSegment* o : mine) {
          starts += glm::distance(o->a, *p) <= 1e-12;
          ends += glm::distance(o->b, *p) <= 1e-12;
        }
        if (starts != 1 || ends != 1) ++open;
        if (starts > 1 || ends > 1) ++branched;
      }
    }
    EXPECT_EQ(closed ? open : branched, 0u)
        << what << ", " << describe(plane) << ", surface " << model.surfaces[si].name << ": "
        << mine.size() << " segments, end points not shared by exactly two";
  }
}

void expect_closed_loops(const DsModel& model, const Plane& plane, const std::string& what) {
  expect_closed_loops(model, plane, what, cut_segments(model, plane));
}

// Planes in general position and planes through mesh vertices and along mesh edges: the sweeps
// put vertices at angle 0 (and 180 degrees) exactly in z = 0, and their profile samples at
// equal heights in horizontal planes.
TEST(CutSegments, LoopsOfClosedSurfacesClose) {
  for (const char* file : {"templates/spheres.yaml", "templates/onion.yaml",
                           "templates/tomato.yaml", "templates/cucumber.yaml"}) {
    const DsModel model = model_of(file);
    const double mid = 0.5 * (model.bbox_min.y + model.bbox_max.y);
    // The height of a vertex of the skin: a plane through a whole ring of vertices.
    const double ring_y = model.skin().mesh.point(DsMesh::VertexHandle(5))[1];
    for (const Plane& plane :
         {plane_of({0, 0, 0}, {0, 0, 1}), plane_of({0, 0, 0}, {1, 0, 0}),
          plane_of({0, mid, 0}, {0, 1, 0}), plane_of({0, ring_y, 0}, {0, 1, 0}),
          plane_of({0.003, mid, -0.002}, {0.3, 1, 0.2}), plane_of({0, mid, 0}, {1, 0, 1})}) {
      const std::vector<CutSegment> segs = cut_segments(model, plane);
      ASSERT_FALSE(segs.empty()) << file << ", " << describe(plane);
      expect_closed_loops(model, plane, file);
      // Merged as cross-sections merge them (tolerance 0.01 template edge, up to one edge).
      const double edge = load_template(test::source_path(file).string()).edge_m;
      expect_closed_loops(model, plane, std::string(file) + " (merged)",
                          merge_collinear_segments(segs, 0.01 * edge, edge));
    }
  }
}

TEST(CutSegments, EndPointsLieOnThePlaneAndSegmentsHaveLength) {
  const DsModel model = model_of("templates/tomato.yaml");
  const Plane plane = plane_of({0.004, 0.02, 0.001}, {0.2, 1, -0.5});
  const std::vector<CutSegment> segs = cut_segments(model, plane);
  ASSERT_GT(segs.size(), 100u);
  for (const CutSegment& s : segs) {
    EXPECT_LE(std::fabs(glm::dot(s.a - plane.point, plane.normal)), 1e-12);
    EXPECT_LE(std::fabs(glm::dot(s.b - plane.point, plane.normal)), 1e-12);
    EXPECT_GT(glm::distance(s.a, s.b), 0.0);
    EXPECT_NEAR(glm::length(s.front_normal), 1.0, 1e-12);
  }
  // Surface order, deterministic.
  EXPECT_TRUE(
      std::is_sorted(segs.begin(), segs.end(), [](const CutSegment& x, const CutSegment& y) {
        return x.surface < y.surface;
      }));
  const std::vector<CutSegment> again = cut_segments(model, plane);
  ASSERT_EQ(again.size(), segs.size());
  for (size_t i = 0; i < segs.size(); ++i) EXPECT_EQ(again[i].a, segs[i].a);
}

// Every segment runs with its front side on one hand: seen from the plane's normal, the front
// normal points to the same side of the segment direction everywhere; on a sphere the front
// (outside) is away from the centre.
TEST(CutSegments, OrientationAndAttributes) {
  const DsModel model = model_of("templates/spheres.yaml");
  const glm::dvec3 skin_front = srgb_to_linear(glm::dvec3(0xc0, 0x30, 0x20) / 255.0);
  for (const Plane& plane : {plane_of({0, 0.01, 0}, {0, 1, 0}), plane_of({0, 0, 0}, {0, 0, 1}),
                             plane_of({0.002, -0.003, 0.004}, {-0.4, 0.2, 1})}) {
    const std::vector<CutSegment> segs = cut_segments(model, plane);
    int left = 0, right = 0;
    for (const CutSegment& s : segs) {
      const glm::dvec3 side = glm::cross(plane.normal, s.b - s.a);
      (glm::dot(side, s.front_normal) > 0 ? left : right)++;
      const glm::dvec3 mid = 0.5 * (s.a + s.b);
      const double in_plane_out =
          glm::dot(s.front_normal, mid - plane.normal * glm::dot(mid, plane.normal));
      EXPECT_GT(in_plane_out, 0) << "front normal points inwards";
      EXPECT_EQ(s.at_a.blur, 0.0);
      EXPECT_EQ(s.at_b.blur, 0.0);
      if (s.surface == 0) {
        EXPECT_LT(glm::length(s.at_a.front - skin_front), 1e-12);
        EXPECT_LT(glm::length(s.at_b.back - glm::dvec3(1, 0, 0)), 1e-12);
      } else {
        EXPECT_LT(glm::length(s.at_b.front - glm::dvec3(0, 1, 0)), 1e-12);
        EXPECT_LT(glm::length(s.at_a.back - glm::dvec3(0, 1, 0)), 1e-12);
      }
    }
    EXPECT_TRUE(left == 0 || right == 0) << describe(plane) << ": " << left << " / " << right;
  }
}

// Blur and colour gradients are interpolated linearly along the crossed edge.
TEST(CutSegments, AttributesInterpolateAlongTheEdge) {
  const DsModel model = model_of("templates/tomato.yaml");
  const Plane plane = plane_of({0, 0.021, 0}, {0.1, 1, 0.05});
  double blur_min = 1e9, blur_max = -1e9;
  for (const CutSegment& s : cut_segments(model, plane)) {
    if (model.surfaces[s.surface].name != "core") continue;
    blur_min = std::min({blur_min, s.at_a.blur, s.at_b.blur});
    blur_max = std::max({blur_max, s.at_a.blur, s.at_b.blur});
  }
  EXPECT_NEAR(blur_min, 0.0015, 1e-12);
  EXPECT_NEAR(blur_max, 0.0015, 1e-12);
  // The chambers' back colour runs along the profile: cut segments carry values between its
  // stops, not outside them (#d8a844, #e0b450, #d8a442: per component from #d8a442 to #e0b450).
  const glm::dvec3 lo = srgb_to_linear(glm::dvec3(0xd8, 0xa4, 0x42) / 255.0);
  const glm::dvec3 hi = srgb_to_linear(glm::dvec3(0xe0, 0xb4, 0x50) / 255.0);
  size_t chamber = 0;
  for (const CutSegment& s : cut_segments(model, plane)) {
    if (model.surfaces[s.surface].name != "chambers") continue;
    ++chamber;
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(s.at_a.back[k], std::min(lo[k], hi[k]) - 1e-9);
      EXPECT_LE(s.at_a.back[k], std::max(lo[k], hi[k]) + 1e-9);
    }
  }
  EXPECT_GT(chamber, 0u);
}

// Planes that miss the object or only touch it give nothing.
TEST(CutSegments, TouchingOrMissingGivesNothing) {
  const DsModel model = model_of("templates/spheres.yaml");
  EXPECT_TRUE(cut_segments(model, plane_of({0, 0.1, 0}, {0, 1, 0})).empty());
  EXPECT_TRUE(cut_segments(model, plane_of({0, model.bbox_max.y, 0}, {0, 1, 0})).empty());
  EXPECT_TRUE(cut_segments(model, plane_of({0, model.bbox_min.y, 0}, {0, -1, 0})).empty());
  // Just inside the pole: a tiny closed loop.
  const Plane near_pole = plane_of({0, 0.039999, 0}, {0, 1, 0});
  const auto segs = cut_segments(model, near_pole);
  EXPECT_FALSE(segs.empty());
  expect_closed_loops(model, near_pole, "spheres near the pole");
  // Merging nearly collinear segments (tolerance 0.01 edge, as cross-sections do) must not
  // collapse a loop smaller than the tolerance into two segments of no area.
  const double edge = 0.0015;
  const std::vector<CutSegment> merged = merge_collinear_segments(segs, 0.01 * edge, edge);
  EXPECT_GE(merged.size(), 3u);
  EXPECT_LT(merged.size(), segs.size());
  expect_closed_loops(model, near_pole, "spheres near the pole, merged", merged);
  // On a horizontal plane through the middle the merged loops still close.
  const Plane mid = plane_of({0, 0.0101, 0}, {0, 1, 0});
  expect_closed_loops(model, mid, "spheres, merged",
                      merge_collinear_segments(cut_segments(model, mid), 0.01 * edge, edge));
}

}  // namespace
}  // namespace cutaway
