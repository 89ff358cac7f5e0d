// parse_cut_spec (generator/pieces/cut_spec.h): the command line's `--cut` forms, their units and
// their rejections; template_extents and estimate_piece_count on the shipped templates.
#include "io/cut_notation.h"
#include "pieces/cut_spec.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "io/template_parser.h"
#include "model/template.h"
#include "test_support.h"

namespace cutaway {
namespace {

/// The reason parse_cut_spec refuses `text` (fails the test when it is accepted).
std::string error_of(const std::string& text, double metres_per_unit = 1e-3) {
  const Outcome<CutSpec> cut = parse_cut_spec(text, metres_per_unit);
  if (!cut) return cut.reason();
  ADD_FAILURE() << "'" << text << "' was accepted";
  return "";
}

TEST(CutSpec, WholeAndHalves) {
  EXPECT_EQ(parse_cut_spec("whole", 1e-3)->type, CutType::Whole);
  EXPECT_EQ(parse_cut_spec("halves", 1e-3)->type, CutType::Halves);
}

TEST(CutSpec, SlicesAndDiceInMetres) {
  const CutSpec s = *parse_cut_spec("slices:5", 1e-3);
  EXPECT_EQ(s.type, CutType::Slices);
  EXPECT_DOUBLE_EQ(s.thickness_m, 0.005);
  EXPECT_DOUBLE_EQ(parse_cut_spec("slices:0.5", 1e-2)->thickness_m, 0.005);
  EXPECT_DOUBLE_EQ(parse_cut_spec("slices:1.5e1", 1e-3)->thickness_m, 0.015);
  const CutSpec d = *parse_cut_spec("dice:12.5", 1e-3);
  EXPECT_EQ(d.type, CutType::Dice);
  EXPECT_DOUBLE_EQ(d.size_m, 0.0125);
  EXPECT_DOUBLE_EQ(parse_cut_spec("dice:0.5", 1e-3)->size_m, kMinCutLength_m);
  EXPECT_NEAR(parse_cut_spec("dice:0.05", 1e-2)->size_m, kMinCutLength_m, 1e-15);
}

TEST(CutSpec, Wedges) {
  const CutSpec w = *parse_cut_spec("wedges:6", 1e-3);
  EXPECT_EQ(w.type, CutType::Wedges);
  EXPECT_EQ(w.count, 6);
  EXPECT_EQ(parse_cut_spec("wedges:2", 1e-3)->count, 2);
  EXPECT_EQ(parse_cut_spec("wedges:64", 1e-3)->count, 64);
}

TEST(CutSpec, PlaneUsesThePlaneNotation) {
  const CutSpec p = *parse_cut_spec("plane:y=20", 1e-3);
  EXPECT_EQ(p.type, CutType::Plane);
  EXPECT_DOUBLE_EQ(p.plane.point.y, 0.020);
  EXPECT_DOUBLE_EQ(p.plane.normal.y, 1.0);
  const CutSpec q = *parse_cut_spec("plane:0,10,0/3,0,4", 1e-3);
  EXPECT_DOUBLE_EQ(q.plane.point.y, 0.010);
  EXPECT_NEAR(q.plane.normal.x, 0.6, 1e-12);
  EXPECT_NEAR(q.plane.normal.z, 0.8, 1e-12);
}

TEST(CutSpec, Rejections) {
  EXPECT_NE(error_of("quarters").find("is not a cut"), std::string::npos);
  EXPECT_NE(error_of("").find("is not a cut"), std::string::npos);
  EXPECT_NE(error_of("Halves").find("is not a cut"), std::string::npos);
  EXPECT_NE(error_of("halves:2").find("takes no value"), std::string::npos);
  EXPECT_NE(error_of("slices").find("write slices:THICKNESS"), std::string::npos);
  EXPECT_NE(error_of("slices:").find("write slices:THICKNESS"), std::string::npos);
  EXPECT_NE(error_of("slices:0").find("must be positive"), std::string::npos);
  EXPECT_NE(error_of("slices:-3").find("must be positive"), std::string::npos);
  EXPECT_NE(error_of("slices:0.2").find("at least 0.5 mm"), std::string::npos);
  EXPECT_NE(error_of("slices:thin").find("must be a number"), std::string::npos);
  EXPECT_NE(error_of("slices:nan").find("must be a number"), std::string::npos);
  EXPECT_NE(error_of("slices:inf").find("must be a number"), std::string::npos);
  EXPECT_NE(error_of("slices:0x10").find("must be a number"), std::string::npos);
  EXPECT_NE(error_of("slices:1e999").find("is too large"), std::string::npos);
  EXPECT_NE(error_of("dice:0").find("must be positive"), std::string::npos);
  EXPECT_NE(error_of("wedges:1").find("from 2 to 64"), std::string::npos);
  EXPECT_NE(error_of("wedges:65").find("from 2 to 64"), std::string::npos);
  EXPECT_NE(error_of("wedges:2.5").find("from 2 to 64"), std::string::npos);
  EXPECT_NE(error_of("wedges:six").find("must be a number"), std::string::npos);
  EXPECT_NE(error_of("plane:").find("write plane:SPEC"), std::string::npos);
  EXPECT_NE(error_of("plane:w=3").find("is not a plane"), std::string::npos);
}

TEST(CutSpec, PieceCountEstimates) {
  const ObjectExtents e{0.02, 0.1};  // 40 mm across, 100 mm tall
  EXPECT_EQ(estimate_piece_count(*parse_cut_spec("whole", 1e-3), e), 1);
  EXPECT_EQ(estimate_piece_count(*parse_cut_spec("halves", 1e-3), e), 2);
  EXPECT_EQ(estimate_piece_count(*parse_cut_spec("plane:y=3", 1e-3), e), 2);
  EXPECT_EQ(estimate_piece_count(*parse_cut_spec("wedges:7", 1e-3), e), 7);
  EXPECT_EQ(estimate_piece_count(*parse_cut_spec("slices:10", 1e-3), e), 11);
  EXPECT_EQ(estimate_piece_count(*parse_cut_spec("slices:30", 1e-3), e), 5);
  EXPECT_EQ(estimate_piece_count(*parse_cut_spec("dice:10", 1e-3), e), 4 * 4 * 10);
  // Huge objects saturate instead of overflowing.
  EXPECT_EQ(estimate_piece_count(*parse_cut_spec("dice:0.5", 1e-3), ObjectExtents{900, 900}),
            1000000000);
}

TEST(CutSpec, TemplateExtents) {
  // Tomato: profile r at most 35 mm, its section's radius at angle 0 is its largest.
  const ObjectExtents tomato =
      template_extents(load_template(test::source_path("templates/tomato.yaml").string()));
  EXPECT_NEAR(tomato.radius_m, 0.035, 1e-9);
  EXPECT_NEAR(tomato.height_m, 0.052 - 0.0008, 1e-9);
  // Onion: the loop reaches 41.09 mm where its radius at angle 0 is 40.63 mm.
  const ObjectExtents onion =
      template_extents(load_template(test::source_path("templates/onion.yaml").string()));
  EXPECT_NEAR(onion.radius_m, 0.040 * 41.09 / 40.63, 1e-6);
  EXPECT_NEAR(onion.height_m, 0.080, 1e-9);
  // A mesh skin (an octahedron of radius 20 mm): the corners of its bounding box.
  const ObjectExtents mesh =
      template_extents(load_template(test::source_path("tests/data/mesh_octahedra.yaml").string()));
  EXPECT_NEAR(mesh.radius_m, std::hypot(0.020, 0.020), 1e-9);
  EXPECT_NEAR(mesh.height_m, 0.040, 1e-9);
}

}  // namespace
}  // namespace cutaway
