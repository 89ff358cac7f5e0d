// Rigid surfaces (stones, pits) under every kind of cut: the template rules, one piece holding
// the whole stone (the halves' volumes differ by the stone's), the other pieces holding its
// imprint, and every piece a closed 2-manifold.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <map>
#include <memory>

#include "base/colour.h"
#include "base/error.h"
#include "diffusion/diffusion.h"
#include "io/cut_notation.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "pieces/manifold_check.h"
#include "pieces/pieces.h"
#include "pieces/rigid_stones.h"
#include "model/inside_test.h"
#include "test_support.h"
#include "variation/variation.h"

namespace cutaway {
namespace {

/// Concentric spheres (radii 40 and 20 mm) with `inner` added to the inner sphere's fields and
/// `more` appended as further surfaces.
std::string spheres(const std::string& inner, const std::string& more = "") {
  return "format: cutaway-template/1\nname: stone\nunits: mm\nsymmetry: {type: cylindrical}\n"
         "resolution: {edge: 2}\nsurfaces:\n"
         "  - {name: flesh, kind: around, role: skin, profile: [[0, -40], [28.3, -28.3], "
         "[40, 0], [28.3, 28.3], [0, 40]], front: '#c03020', back: '#f0c040'}\n"
         "  - {name: stone, kind: around, profile: [[0, -20], [14.1, -14.1], [20, 0], "
         "[14.1, 14.1], [0, 20]], front: '#f0e0a0', back: '#704020'" +
         inner + "}\n" + more;
}

/// The error message of building `text`'s model (empty when it builds).
std::string build_error(const std::string& text) {
  try {
    build_model(parse_template(text, "stone.yaml", "."));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(RigidStones, TheTemplateRulesNameTheFieldAndTheSurface) {
  EXPECT_EQ(build_error(spheres(", rigid: true")), "");
  EXPECT_NE(build_error(spheres(", rigid: true, visible: {back: false}"))
                .find("rigid: a rigid surface is solid inside"),
            std::string::npos);
  const std::string skin =
      "format: cutaway-template/1\nname: s\nunits: mm\nsymmetry: {type: cylindrical}\n"
      "surfaces:\n  - {name: flesh, kind: around, role: skin, rigid: true, "
      "profile: [[0, -40], [40, 0], [0, 40]]}\n";
  EXPECT_NE(build_error(skin).find("the skin cannot be rigid"), std::string::npos);
  // A lens crossing the stone's equator.
  const std::string crossing = build_error(
      spheres(", rigid: true", "  - {name: lens, kind: around, profile: [[0, -5], [30, 0], "
                               "[0, 5]], front: '#ffffff', back: '#ffffff'}\n"));
  EXPECT_NE(crossing.find("surface \"lens\" touches or crosses the rigid surface \"stone\""),
            std::string::npos)
      << crossing;
  EXPECT_NE(crossing.find("surfaces[2]"), std::string::npos) << crossing;
  // Any two surfaces: the message names both and a point on the stone's equator (r = 20 mm).
  const std::string plain = build_error(
      spheres("", "  - {name: lens, kind: around, profile: [[0, -5], [30, 0], [0, 5]]}\n"));
  EXPECT_NE(plain.find("surface \"lens\" touches or crosses surface \"stone\" near ("),
            std::string::npos)
      << plain;
  const size_t at = plain.find(" near (");
  ASSERT_NE(at, std::string::npos);
  double x = 0, y = 0, z = 0;
  ASSERT_EQ(std::sscanf(plain.c_str() + at, " near (%lf, %lf, %lf)", &x, &y, &z), 3) << plain;
  EXPECT_NEAR(std::hypot(x, z), 20, 1.0) << plain;
  EXPECT_NEAR(y, 0, 4.0) << plain;
}

/// The pieces of the template at `file` (its own model, no variation) cut as `cut`.
struct Cut {
  DsModel model;
  PieceSet set;
  std::optional<StonePlan> plan;
};

Cut cut_template(const std::string& file, const std::string& cut, bool rigid = true) {
  Template tmpl = load_template(test::source_path(file).string());
  if (!rigid)
    for (SurfaceSpec& spec : tmpl.surfaces) spec.rigid = false;
  Cut out{build_model(tmpl), {}, std::nullopt};
  const auto diffusion = make_cpu_diffusion(out.model, {4, 0});
  PieceOptions options;
  options.section.edge_m = tmpl.edge_m;
  out.set = *cut_pieces(out.model, *parse_cut_spec(cut, tmpl.metres_per_unit), *diffusion, options);
  out.plan = plan_stones(out.model);
  return out;
}

bool holds_stone(const Piece& piece) {
  return std::any_of(piece.parts.begin(), piece.parts.end(),
                     [](const PiecePart& p) { return p.kind == PartKind::Stone; });
}

/// The object's volume as its pieces should add up to: inside the skin, less the hollows that
/// no stone encloses (what a stone encloses goes whole with it).
double solid_volume(const Cut& c) {
  double v = std::fabs(signed_volume(c.model.skin().mesh));
  for (const DsSurface& s : c.plan->hollowed.surfaces)
    if (s.role != SurfaceRole::Grain && !s.rigid && s.visible_front != s.visible_back &&
        s.mesh.n_faces() > 0)
      v -= std::fabs(signed_volume(s.mesh));
  return v;
}

class StoneCuts : public ::testing::TestWithParam<const char*> {};

// Halves and four wedges: one piece holds the stone; every piece is closed; the volumes add
// up. The halves differ by the stone's volume (within 5 %: the fruit is nearly symmetric about
// the cut); a wedge holding the stone exceeds the others' mean by about it (the wedges of a
// peach differ by its suture groove: within 10 %).
TEST_P(StoneCuts, OnePieceHoldsTheWholeStone) {
  for (const char* how : {"halves", "wedges:4"}) {
    const Cut c = cut_template(GetParam(), how);
    ASSERT_TRUE(c.plan);
    ASSERT_EQ(c.plan->stones.size(), 1u);
    const double stone = c.plan->stones[0].volume_m3;
    EXPECT_EQ(c.set.defective_pieces, 0u) << how;
    double holder = 0, others = 0, total = 0;
    int holders = 0, other_count = 0;
    for (const Piece& piece : c.set.pieces) {
      const ShadedMesh merged = merge_parts(piece);
      EXPECT_TRUE(check_manifold(merged, kMinVertexSeparation_m)) << how << " cell " << piece.cell;
      const double v = signed_volume(merged);
      total += v;
      if (holds_stone(piece)) {
        ++holders;
        holder = v;
      } else {
        ++other_count;
        others += v;
      }
    }
    ASSERT_EQ(holders, 1) << how;
    const double excess = holder - others / other_count;
    const double within = std::string(how) == "halves" ? 0.05 : 0.10;
    EXPECT_NEAR(excess, stone, within * stone)
        << how << ": holder " << holder * 1e6 << " cm3, others' mean " << others / other_count * 1e6
        << " cm3, stone " << stone * 1e6 << " cm3";
    EXPECT_NEAR(total, solid_volume(c), 0.005 * total) << how;
  }
}

/// For each of the stone's grid points, whether it lies in a hollow inside the stone (a peach
/// stone's cavity round its kernel): the innermost closed surface around it, the stone's own
/// included, is hollow on its inside.
std::vector<bool> hollow_samples(const DsModel& model, const RigidStone& stone) {
  std::vector<size_t> around;  // closed surfaces other than the skin and the grains
  std::vector<std::unique_ptr<InsideTest>> tests;
  std::vector<double> volume;
  for (size_t s = 1; s < model.surfaces.size(); ++s) {
    const DsSurface& surface = model.surfaces[s];
    if (surface.role == SurfaceRole::Grain || !closed_surface(surface.mesh)) continue;
    around.push_back(s);
    tests.push_back(std::make_unique<InsideTest>(surface.mesh));
    volume.push_back(std::fabs(signed_volume(surface.mesh)));
  }
  std::vector<bool> out;
  for (const glm::dvec3& p : stone.samples) {
    size_t innermost = around.size();
    for (size_t k = 0; k < around.size(); ++k)
      if (tests[k]->inside(p) && (innermost == around.size() || volume[k] < volume[innermost]))
        innermost = k;
    out.push_back(innermost < around.size() && !model.surfaces[around[innermost]].visible_back);
  }
  return out;
}

// Each piece differs from the same cell cut straight through the stone by the stone it gained
// or lost, counted by the stone's grid points: the holder gains the stone outside its cell and
// the hollows inside the stone within it (a stone is solid once whole), every other piece loses
// the stone's solid part inside its cell. Measured against the stone's volume: within 5 % for
// halves, four wedges and slices, whatever the fruit's asymmetry.
TEST_P(StoneCuts, EachPieceGainsOrLosesTheStoneItsCellDoesNotHold) {
  for (const char* how : {"halves", "wedges:4", "slices:8"}) {
    const Cut rigid = cut_template(GetParam(), how), through = cut_template(GetParam(), how, false);
    ASSERT_EQ(rigid.plan->stones.size(), 1u);
    const RigidStone& stone = rigid.plan->stones[0];
    const std::vector<bool> hollow = hollow_samples(rigid.model, stone);
    std::map<int, double> straight;  // cell -> volume cut through the stone
    for (const Piece& piece : through.set.pieces)
      straight[piece.cell] = signed_volume(merge_parts(piece));
    const double per_sample = stone.volume_m3 / static_cast<double>(stone.samples.size());
    double worst = 0;
    for (const Piece& piece : rigid.set.pieces) {
      ASSERT_TRUE(straight.count(piece.cell)) << how << " cell " << piece.cell;
      const Cell& cell = rigid.set.cells.cells[static_cast<size_t>(piece.cell)];
      double expected = 0;
      for (size_t k = 0; k < stone.samples.size(); ++k) {
        const bool here = in_cell(rigid.set.cells, cell, stone.samples[k]);
        if (holds_stone(piece)) expected += !here || hollow[k] ? per_sample : 0.0;
        else expected -= here && !hollow[k] ? per_sample : 0.0;
      }
      const double change = signed_volume(merge_parts(piece)) - straight[piece.cell];
      EXPECT_NEAR(change, expected, 0.05 * stone.volume_m3)
          << how << " cell " << piece.cell << (holds_stone(piece) ? " (holder)" : "");
      worst = std::max(worst, std::fabs(change - expected) / stone.volume_m3);
    }
    std::printf("%s %s: largest difference from the stone moved %.2f %% of the stone\n", GetParam(),
                how, 100 * worst);
  }
}

// Slices, dice and a slanted plane: one piece holds the stone; all closed; volumes add up.
TEST_P(StoneCuts, EveryCutKindKeepsPiecesClosed) {
  for (const char* how : {"slices:12", "dice:22", "plane:0,30,0/1,2,0.5"}) {
    const Cut c = cut_template(GetParam(), how);
    EXPECT_EQ(c.set.defective_pieces, 0u) << how;
    double total = 0;
    int holders = 0;
    for (const Piece& piece : c.set.pieces) {
      total += signed_volume(merge_parts(piece));
      holders += holds_stone(piece);
    }
    EXPECT_EQ(holders, 1) << how;
    EXPECT_NEAR(total, solid_volume(c), 0.005 * total) << how;
  }
}

INSTANTIATE_TEST_SUITE_P(Shipped, StoneCuts,
                         ::testing::Values("templates/avocado.yaml", "templates/peach.yaml"),
                         [](const auto& info) { return test::template_test_name(info.param); });

// The stone's surface outside the holder's cell shows the stone's own colour (its inside), and
// the cavity in the other half shows the flesh's colour against it (its outside).
TEST(RigidStones, TheStoneShowsItsColourAndTheCavityTheFleshs) {
  const Cut c = cut_template("templates/avocado.yaml", "halves");
  const DsSurface& pit = c.model.surfaces[static_cast<size_t>(c.plan->stones[0].surface)];
  const auto& data = pit.mesh.data(*pit.mesh.vertices_begin());
  const glm::dvec3 inside(data.back[0], data.back[1], data.back[2]);
  const glm::dvec3 outside(data.front[0], data.front[1], data.front[2]);
  int stones = 0, cavities = 0;
  for (const Piece& piece : c.set.pieces)
    for (const PiecePart& part : piece.parts) {
      if (part.surface != c.plan->stones[0].surface) continue;
      const glm::dvec3 expected = part.kind == PartKind::Stone ? inside : outside;
      (part.kind == PartKind::Stone ? stones : cavities) += 1;
      for (const glm::dvec3& colour : part.mesh.colour)
        ASSERT_LT(glm::distance(colour, expected), 1e-9);
    }
  EXPECT_GE(stones, 1);
  EXPECT_EQ(cavities, 1);
}

// An offset and a tilt move a part and what it encloses; a part moved into the skin is refused
// with both names.
TEST(PartPlacement, AnOffsetMovesThePartAndWhatItEnclosesAndIsChecked) {
  const std::string kernel =
      "  - {name: kernel, kind: around, profile: [[0, -8], [8, 0], [0, 8]], front: '#ffffff', "
      "back: '#ffffff'}\n";
  const Template plain = parse_template(spheres("", kernel), "stone.yaml", ".");
  const Template moved =
      parse_template(spheres(", offset: [6, -5, 2], tilt: [30, 0]", kernel), "stone.yaml", ".");
  const DsModel a = build_model(plain), b = build_model(moved);
  ASSERT_EQ(a.surfaces.size(), 3u);
  for (size_t s = 0; s < 3; ++s) {
    ASSERT_EQ(a.surfaces[s].mesh.n_vertices(), b.surfaces[s].mesh.n_vertices());
    glm::dvec3 shift(0.0);
    for (auto vh : a.surfaces[s].mesh.vertices())
      shift += to_glm(b.surfaces[s].mesh.point(vh)) - to_glm(a.surfaces[s].mesh.point(vh));
    shift /= static_cast<double>(a.surfaces[s].mesh.n_vertices());
    // The skin stays; the stone and the kernel inside it move by the offset (their centres
    // are the stone's centre, which the tilt keeps).
    const glm::dvec3 expected = s == 0 ? glm::dvec3(0.0) : glm::dvec3(6, -5, 2) * 1e-3;
    EXPECT_LT(glm::distance(shift, expected), 1e-4) << s;
  }
  const std::string out = build_error(spheres(", offset: [25, 0, 0]", kernel));
  EXPECT_NE(out.find("surface \"stone\" touches or crosses the skin"), std::string::npos) << out;
  EXPECT_NE(build_error(spheres(", offset: [1, 2]")).find("an offset is [x, y, z]"),
            std::string::npos);
  EXPECT_NE(build_error(spheres(", tilt: [95, 0]")).find("tilt"), std::string::npos);
}

/// The mean of the vertices of the surface named `name` in `model`, metres.
glm::dvec3 centroid(const DsModel& model, const std::string& name) {
  for (const DsSurface& s : model.surfaces) {
    if (s.name != name) continue;
    glm::dvec3 sum(0.0);
    for (auto vh : s.mesh.vertices()) sum += to_glm(s.mesh.point(vh));
    return sum / static_cast<double>(s.mesh.n_vertices());
  }
  ADD_FAILURE() << "no surface " << name;
  return glm::dvec3(0.0);
}

// The boiled egg's yolk wanders by up to 2.5 mm: each seed moves it (with its core) somewhere
// else, never further than that (plus what the variant's own section changes move its centre).
TEST(PartPlacement, AWanderingYolkSitsElsewhereInEachVariant) {
  const Template egg = load_template(test::source_path("templates/boiled_egg.yaml").string());
  const glm::dvec3 own = centroid(build_model(egg), "yolk");
  std::vector<glm::dvec3> moves;
  for (uint64_t seed = 0; seed < 6; ++seed) {
    const Variant v = make_variant(egg, seed);
    const glm::dvec3 move = centroid(v.model, "yolk") - own;
    EXPECT_LT(glm::length(move), 2.5e-3 + 0.3e-3) << seed;
    EXPECT_LT(glm::distance(centroid(v.model, "yolk-core") - centroid(v.model, "yolk"),
                            centroid(build_model(egg), "yolk-core") - own),
              0.3e-3)
        << seed;
    moves.push_back(move);
  }
  double spread = 0;
  for (const glm::dvec3& a : moves)
    for (const glm::dvec3& b : moves) spread = std::max(spread, glm::distance(a, b));
  EXPECT_GT(spread, 1e-3);
}

}  // namespace
}  // namespace cutaway
