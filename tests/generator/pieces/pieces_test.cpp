// Cut pieces (doc/algorithms.md §4) against the properties every piece must have: a piece of an
// object without hollows is a closed, consistently oriented 2-manifold; the pieces' volumes add
// up to the object's; the two caps on either side of one cut are mirror images with equal
// colours. Over several templates and every kind of cut.
#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "base/constants.h"
#include "cut/piece_views.h"
#include "io/cut_notation.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "pieces/clip_mesh.h"
#include "pieces/cut_cells.h"
#include "pieces/pieces.h"
#include "scene/scene_builder.h"
#include "test_support.h"

namespace cutaway {
namespace {

using Key = std::tuple<double, double, double>;
Key key(const glm::dvec3& p) { return {p.x, p.y, p.z}; }

/// Welds the piece's vertices by exact position and checks that every directed edge has
/// exactly one opposite twin and that the triangles around every vertex form one cycle.
::testing::AssertionResult closed_oriented_manifold(const ShadedMesh& mesh) {
  std::map<Key, unsigned> id;
  std::vector<glm::dvec3> where;
  std::vector<glm::uvec3> tris;
  for (const glm::uvec3& t : mesh.triangle) {
    glm::uvec3 w;
    for (int k = 0; k < 3; ++k) {
      auto [it, added] = id.emplace(key(mesh.position[t[k]]), id.size());
      if (added) where.push_back(mesh.position[t[k]]);
      w[k] = it->second;
    }
    if (w[0] == w[1] || w[1] == w[2] || w[0] == w[2])
      return ::testing::AssertionFailure() << "a degenerate triangle (two corners at one point)";
    tris.push_back(w);
  }
  std::map<std::pair<unsigned, unsigned>, int> directed;
  for (const glm::uvec3& t : tris)
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  for (const auto& [e, n] : directed) {
    if (n != 1) return ::testing::AssertionFailure() << "edge used " << n << " times one way";
    auto twin = directed.find({e.second, e.first});
    if (twin == directed.end())
      return ::testing::AssertionFailure()
             << "an open edge from (" << where[e.first].x << ", " << where[e.first].y << ", "
             << where[e.first].z << ") to (" << where[e.second].x << ", " << where[e.second].y
             << ", " << where[e.second].z << ")";
  }
  // Vertex links: around v, triangle (v, a, b) links a -> b; one cycle per vertex.
  std::map<unsigned, std::map<unsigned, unsigned>> link;
  for (const glm::uvec3& t : tris)
    for (int k = 0; k < 3; ++k) link[t[k]][t[(k + 1) % 3]] = t[(k + 2) % 3];
  for (const auto& [v, next] : link) {
    size_t steps = 0;
    unsigned start = next.begin()->first, a = start;
    do {
      a = next.at(a);
      ++steps;
    } while (a != start && steps <= next.size());
    if (steps != next.size())
      return ::testing::AssertionFailure()
             << "a non-manifold vertex (" << next.size() << " triangles in more than one fan)";
  }
  return ::testing::AssertionSuccess();
}

struct Case {
  const char* file;
  const char* cut;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.file << " cut " << c.cut; }

class PiecesTest : public ::testing::TestWithParam<Case> {};

TEST_P(PiecesTest, ClosedManifoldsWhoseVolumesAddUp) {
  const Template tmpl = load_template(test::source_path(GetParam().file).string());
  const DsModel model = build_model(tmpl);
  const auto diffusion = make_cpu_diffusion(model, {8, 0});
  PieceOptions options;
  options.section.edge_m = tmpl.edge_m;
  const PieceSet set = *cut_pieces(model, *parse_cut_spec(GetParam().cut, tmpl.metres_per_unit),
                                   *diffusion, options);
  ASSERT_GE(set.pieces.size(), 2u);
  for (const CrossSection& cs : set.sections) EXPECT_FALSE(cs.refinement_capped);
  double volume = 0;
  bool hollow = false;
  for (const DsSurface& s : model.surfaces) hollow = hollow || s.visible_front != s.visible_back;
  for (const Piece& piece : set.pieces) {
    const ShadedMesh mesh = merge_parts(piece);
    EXPECT_TRUE(closed_oriented_manifold(mesh)) << "piece of cell " << piece.cell;
    const double v = signed_volume(mesh);
    EXPECT_GT(v, 0) << "piece of cell " << piece.cell;
    volume += v;
  }
  double expected = signed_volume(model.skin().mesh);
  for (const DsSurface& s : model.surfaces)
    if (s.role != SurfaceRole::Grain && s.visible_front != s.visible_back)
      expected -= std::fabs(signed_volume(s.mesh));
  EXPECT_NEAR(volume, expected, 0.005 * expected) << (hollow ? "with hollows" : "");
}

INSTANTIATE_TEST_SUITE_P(Templates, PiecesTest,
                         ::testing::Values(Case{"templates/tomato.yaml", "halves"},
                                           Case{"templates/tomato.yaml", "wedges:5"},
                                           Case{"templates/tomato.yaml", "wedges:6"},
                                           Case{"templates/onion.yaml", "slices:12"},
                                           Case{"templates/banana.yaml", "slices:15"},
                                           Case{"templates/cucumber.yaml", "dice:25"},
                                           Case{"tests/data/section_hollow.yaml", "dice:20"},
                                           Case{"tests/data/section_hollow.yaml",
                                                "plane:3,4,5/1,2,3"}),
                         [](const auto& info) {
                           std::string name = std::string(info.param.file) + "_" + info.param.cut;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

namespace {

/// `tmpl` cut as `cut` for a picture (piece_assets), vertex colours, the cpu backend.
SceneAssets exploded(const Template& tmpl, const std::string& cut, CutObject& object) {
  SceneAssets assets;
  const PieceMaterials materials =
      add_piece_materials(assets, tmpl.name, tmpl.skin_material, tmpl.cut_material);
  ObjectCutOptions options;
  options.cut = *parse_cut_spec(cut, tmpl.metres_per_unit);
  options.cap_colours = CapColours::Vertex;
  ObjectCutStats stats;
  const Variant variant{tmpl, build_model(tmpl)};
  object = *cut_object(assets, variant, 0, materials, tmpl.name,
                       *make_cpu_diffusion(variant.model, {8, 0}), options, stats);
  return piece_assets(std::move(assets), object, 0.3, 64, 48);
}

}  // namespace

TEST(Pieces, ExportAsSkinAndCapPrimitivesWithTheTemplatesMaterials) {
  const Template tmpl = load_template(test::source_path("templates/tomato.yaml").string());
  ASSERT_NE(tmpl.skin_material, tmpl.cut_material);
  CutObject object;
  const SceneAssets assets = exploded(tmpl, "wedges:4", object);
  const PieceSet& set = object.set;
  ASSERT_EQ(assets.materials.size(), 3u);
  EXPECT_EQ(assets.materials[1].name, "tomato_skin");
  EXPECT_EQ(assets.materials[1].pbr, tmpl.skin_material);
  EXPECT_EQ(assets.materials[2].name, "tomato_cut");
  EXPECT_EQ(assets.materials[2].pbr, tmpl.cut_material);
  ASSERT_EQ(assets.meshes.size(), set.pieces.size());
  for (size_t k = 0; k < set.pieces.size(); ++k) {
    const AssetMesh& mesh = assets.meshes[k];
    ASSERT_EQ(mesh.primitives.size(), 2u);
    const AssetPrimitive& skin = mesh.primitives[0];
    const AssetPrimitive& cut = mesh.primitives[1];
    EXPECT_EQ(skin.material, 1);
    EXPECT_EQ(cut.material, 2);
    EXPECT_EQ(skin.first, 0u);
    EXPECT_EQ(skin.count, surface_triangle_count(set.pieces[k]));
    EXPECT_EQ(cut.first, skin.count);
    EXPECT_EQ(cut.first + cut.count, mesh.triangle.size());
    // Every cut triangle lies on a cutting plane: its vertices' shading normals are a plane's.
    for (size_t f = cut.first; f < cut.first + cut.count; ++f)
      for (int c = 0; c < 3; ++c) {
        const glm::dvec3 n = mesh.normal[mesh.triangle[f][c]];
        bool on_plane = false;
        for (const Plane& plane : set.cells.planes)
          on_plane = on_plane || std::fabs(std::fabs(glm::dot(n, plane.normal)) - 1) < 1e-9;
        ASSERT_TRUE(on_plane) << "piece " << k << " triangle " << f;
      }
  }
  // A template without materials: one primitive of the plain material, as before them.
  Template plain = tmpl;
  plain.skin_material = plain.cut_material = PbrMaterial{};
  CutObject plain_object;
  const SceneAssets plain_assets = exploded(plain, "wedges:4", plain_object);
  EXPECT_EQ(plain_assets.materials.size(), 1u);
  for (const AssetMesh& mesh : plain_assets.meshes) EXPECT_TRUE(mesh.primitives.empty());
}

// A whole stone is a primitive of its own, after the walls and before the caps, with a
// material "<object>_stone" whose roughness is the stone's (the mango's husk: 0.9), not the
// skin's, and bare: none of the skin's clear coat (0.5) or sheen; the halves without the
// stone have no such primitive.
TEST(Pieces, AWholeStoneHasAMaterialOfItsOwn) {
  const Template tmpl = load_template(test::source_path("templates/mango.yaml").string());
  CutObject object;
  const SceneAssets assets = exploded(tmpl, "halves", object);
  int stone = -1;
  for (size_t m = 0; m < assets.materials.size(); ++m)
    if (assets.materials[m].name == "mango_stone") stone = static_cast<int>(m);
  ASSERT_GE(stone, 0);
  EXPECT_NEAR(assets.materials[static_cast<size_t>(stone)].pbr.roughness, 0.9, 1e-9);
  EXPECT_NE(assets.materials[static_cast<size_t>(stone)].pbr.roughness,
            tmpl.skin_material.roughness);
  ASSERT_GT(tmpl.skin_material.clearcoat, 0);
  EXPECT_EQ(assets.materials[static_cast<size_t>(stone)].pbr.clearcoat, 0);
  EXPECT_EQ(assets.materials[static_cast<size_t>(stone)].pbr.sheen, glm::dvec3(0.0));
  int holders = 0;
  for (size_t k = 0; k < object.set.pieces.size(); ++k) {
    const Piece& piece = object.set.pieces[k];
    size_t stone_triangles = 0;
    for (const PiecePart& part : piece.parts)
      if (part.kind == PartKind::Stone) stone_triangles += part.mesh.triangle.size();
    size_t drawn = 0, caps_at = 0;
    for (const AssetPrimitive& primitive : assets.meshes[k].primitives) {
      if (primitive.material == stone) {
        drawn += primitive.count;
        EXPECT_EQ(primitive.first + primitive.count, surface_triangle_count(piece));
      }
      if (primitive.first >= surface_triangle_count(piece)) caps_at = primitive.first;
    }
    EXPECT_EQ(drawn, stone_triangles) << "piece " << k;
    EXPECT_EQ(caps_at, surface_triangle_count(piece)) << "piece " << k;
    holders += stone_triangles > 0;
  }
  EXPECT_EQ(holders, 1);
}

// A cut whose planes all miss: scenes keep the object whole, `piece` hears why.
TEST(Pieces, ACutThatMissesKeepsTheObjectWholeOrSaysWhy) {
  const Template tmpl = load_template(test::source_path("templates/tomato.yaml").string());
  const Variant whole{tmpl, build_model(tmpl)};
  SceneAssets assets;
  const PieceMaterials materials =
      add_piece_materials(assets, tmpl.name, tmpl.skin_material, tmpl.cut_material);
  ObjectCutOptions options;
  options.cut = *parse_cut_spec("plane:y=5000", tmpl.metres_per_unit);  // far above
  options.cap_colours = CapColours::Vertex;
  const std::unique_ptr<DiffusionBackend> cpu = make_cpu_diffusion(whole.model, {4, 0});
  ObjectCutStats stats;
  const Outcome<CutObject> kept =
      cut_object(assets, whole, 0, materials, "tomato", *cpu, options, stats);
  ASSERT_TRUE(kept);
  EXPECT_EQ(kept->set.pieces.size(), 1u);
  EXPECT_EQ(kept->meshes.size(), 1u);
  EXPECT_FALSE(kept->backend.empty());
  options.whole_when_missed = false;
  const Outcome<CutObject> refused =
      cut_object(assets, whole, 0, materials, "tomato", *cpu, options, stats);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.reason(), "");
}

TEST(Pieces, CoarseCapsKeepPiecesClosedWithTheSameArea) {
  for (const auto& [file, cut] : std::vector<std::pair<const char*, const char*>>{
           {"templates/tomato.yaml", "wedges:4"}, {"templates/pepper.yaml", "slices:20"}}) {
    SCOPED_TRACE(file);
    const Template tmpl = load_template(test::source_path(file).string());
    const DsModel model = build_model(tmpl);
    const auto diffusion = make_cpu_diffusion(model, {4, 0});
    PieceOptions options;
    options.section.edge_m = tmpl.edge_m;
    const PieceSet set = *cut_pieces(model, *parse_cut_spec(cut, 1e-3), *diffusion, options);
    size_t fine = 0, coarse = 0;
    for (const Piece& piece : set.pieces) {
      ShadedMesh mesh = merge_parts(piece);
      const std::vector<glm::uvec3> caps = coarse_caps(piece, set.sections);
      const size_t surface = surface_triangle_count(piece);
      auto area = [&mesh](auto first, auto last) {
        double a = 0;
        for (auto t = first; t != last; ++t)
          a += 0.5 * glm::length(glm::cross(mesh.position[t->y] - mesh.position[t->x],
                                            mesh.position[t->z] - mesh.position[t->x]));
        return a;
      };
      const double fine_area = area(mesh.triangle.begin() + surface, mesh.triangle.end());
      EXPECT_NEAR(area(caps.begin(), caps.end()), fine_area, 1e-9 * fine_area + 1e-12);
      fine += mesh.triangle.size() - surface;
      coarse += caps.size();
      mesh.triangle.resize(surface);
      mesh.triangle.insert(mesh.triangle.end(), caps.begin(), caps.end());
      EXPECT_TRUE(closed_oriented_manifold(mesh)) << "piece of cell " << piece.cell;
    }
    EXPECT_LT(3 * coarse, fine) << "cap triangles: fine " << fine << ", coarse " << coarse;
  }
}

/// Per section of `set`, the area of its caps on both sides together, square metres.
std::vector<double> section_cap_areas(const PieceSet& set) {
  std::vector<double> area(set.sections.size(), 0.0);
  for (const Piece& piece : set.pieces)
    for (const PiecePart& part : piece.parts) {
      if (part.kind != PartKind::Cap) continue;
      const ShadedMesh& m = part.mesh;
      for (const glm::uvec3& t : m.triangle)
        area[static_cast<size_t>(part.plane)] +=
            0.5 * glm::length(glm::cross(m.position[t.y] - m.position[t.x],
                                         m.position[t.z] - m.position[t.x]));
    }
  return area;
}

TEST(Pieces, SlicesOfABentObjectAreCutAcrossItsSpine) {
  // The bend carries each straight plane y = c onto the plane across the spine there, and a
  // section onto a congruent one: the bent banana's slices have the straight banana's cut
  // faces, one for one. Planes across +Y would cut its curved ends obliquely, larger.
  const Template bent = load_template(test::source_path("templates/banana.yaml").string());
  Template straight = bent;
  straight.spine = {};
  std::vector<double> areas[2];
  std::vector<glm::dvec3> normals;
  for (const Template* t : {static_cast<const Template*>(&straight), &bent}) {
    const DsModel model = build_model(*t);
    const auto diffusion = make_cpu_diffusion(model, {4, 0});
    PieceOptions options;
    options.section.edge_m = t->edge_m;
    const PieceSet set =
        *cut_pieces(model, *parse_cut_spec("slices:15", 1e-3), *diffusion, options);
    areas[t == &bent] = section_cap_areas(set);
    if (t == &bent)
      for (const CrossSection& cs : set.sections) normals.push_back(cs.plane.normal);
  }
  ASSERT_EQ(areas[0].size(), areas[1].size());
  ASSERT_GE(areas[0].size(), 10u);
  for (size_t k = 0; k < areas[0].size(); ++k)
    EXPECT_NEAR(areas[1][k], areas[0][k], 0.01 * areas[0][k]) << "section " << k;
  // The first and last planes lean apart as the spine turns (about 40 degrees).
  EXPECT_LT(glm::dot(normals.front(), normals.back()), std::cos(0.5));
}

TEST(Pieces, CapsOnEitherSideOfACutAreMirrorImagesWithEqualColours) {
  const Template tmpl = load_template(test::source_path("templates/tomato.yaml").string());
  const DsModel model = build_model(tmpl);
  const auto diffusion = make_cpu_diffusion(model, {8, 0});
  PieceOptions options;
  options.section.edge_m = tmpl.edge_m;
  const PieceSet set = *cut_pieces(model, *parse_cut_spec("slices:15", 1e-3), *diffusion, options);
  ASSERT_GE(set.pieces.size(), 3u);
  // Piece k's upper cap and piece k+1's lower cap lie on the same plane.
  for (size_t k = 0; k + 1 < set.pieces.size(); ++k) {
    const PiecePart* below = nullptr;
    const PiecePart* above = nullptr;
    for (const PiecePart& p : set.pieces[k].parts)
      if (p.kind == PartKind::Cap && p.mesh.normal[0].y > 0) below = &p;
    for (const PiecePart& p : set.pieces[k + 1].parts)
      if (p.kind == PartKind::Cap && p.mesh.normal[0].y < 0) above = &p;
    ASSERT_TRUE(below && above);
    ASSERT_EQ(below->plane, above->plane);
    // Same triangles, reversed, before stitching adds seam vertices: compare the vertex sets
    // with colours, and the triangle counts up to the seams' fans.
    std::map<Key, glm::dvec3> a, b;
    for (size_t i = 0; i < below->mesh.position.size(); ++i)
      a[key(below->mesh.position[i])] = below->mesh.colour[i];
    for (size_t i = 0; i < above->mesh.position.size(); ++i)
      b[key(above->mesh.position[i])] = above->mesh.colour[i];
    EXPECT_EQ(a.size(), b.size());
    size_t compared = 0;
    for (const auto& [p, c] : a) {
      auto it = b.find(p);
      if (it == b.end()) continue;
      EXPECT_LT(glm::distance(c, it->second), 1e-12);
      ++compared;
    }
    EXPECT_GT(compared, 0.95 * a.size());
    // Mirror images: opposite normals, areas equal.
    EXPECT_NEAR(below->mesh.normal[0].y, -above->mesh.normal[0].y, 1e-12);
    auto area = [](const ShadedMesh& m) {
      double s = 0;
      for (const glm::uvec3& t : m.triangle)
        s += 0.5 * glm::length(glm::cross(m.position[t[1]] - m.position[t[0]],
                                          m.position[t[2]] - m.position[t[0]]));
      return s;
    };
    EXPECT_NEAR(area(below->mesh), area(above->mesh), 1e-9 * area(below->mesh) + 1e-12);
  }
}

TEST(CutCells, AKnifeWobbleLeansAndMovesOnlyTheHalvesPlane) {
  const CutSpec halves = *parse_cut_spec("halves", 1e-3);
  const glm::dvec3 lo(-0.03, 0.0, -0.03), hi(0.03, 0.06, 0.03);
  const Plane exact = make_cut_cells(halves, lo, hi).planes.at(0);
  const KnifeWobble knife{0.05, 0.002};
  const Plane p = make_cut_cells(halves, lo, hi, nullptr, nullptr, knife).planes.at(0);
  // Leaned by 0.05 rad, about the plane's line across the axis (x here: the normal stays in
  // the y-z plane), and 2 mm from the axis at mid-height.
  EXPECT_NEAR(std::acos(glm::dot(p.normal, exact.normal)), 0.05, 1e-12);
  EXPECT_NEAR(p.normal.x, 0.0, 1e-15);
  EXPECT_NEAR(glm::dot(glm::dvec3(0, 0.03, 0) - p.point, p.normal), -0.002, 1e-12);
  // The other cuts do not use it.
  for (const char* other : {"wedges:4", "slices:10"}) {
    const CutSpec c = *parse_cut_spec(other, 1e-3);
    const CutCells a = make_cut_cells(c, lo, hi),
                   b = make_cut_cells(c, lo, hi, nullptr, nullptr, knife);
    ASSERT_EQ(a.planes.size(), b.planes.size()) << other;
    for (size_t k = 0; k < a.planes.size(); ++k) {
      EXPECT_EQ(a.planes[k].point, b.planes[k].point) << other;
      EXPECT_EQ(a.planes[k].normal, b.planes[k].normal) << other;
    }
  }
}

// `halves: across`: the halves' plane runs across the axis at mid-height; the knife leans it
// about a line through the axis and moves it along its normal; a leaned axis turns it with it.
TEST(CutCells, HalvesAcrossCutTheAxisAtMidHeight) {
  const CutSpec halves = *parse_cut_spec("halves", 1e-3);
  const glm::dvec3 lo(-0.03, 0.0, -0.03), hi(0.03, 0.06, 0.03);
  const Plane p = make_cut_cells(halves, lo, hi, nullptr, nullptr, {}, true).planes.at(0);
  EXPECT_NEAR(std::abs(p.normal.y), 1.0, 1e-15);
  EXPECT_NEAR(p.point.y, 0.03, 1e-15);
  EXPECT_NEAR(glm::length(glm::dvec2(p.point.x, p.point.z)), 0.0, 1e-15);
  const KnifeWobble knife{0.05, 0.002};
  const Plane w = make_cut_cells(halves, lo, hi, nullptr, nullptr, knife, true).planes.at(0);
  EXPECT_NEAR(std::acos(glm::dot(w.normal, p.normal)), 0.05, 1e-12);
  EXPECT_NEAR(glm::dot(glm::dvec3(0, 0.03, 0) - w.point, w.normal), -0.002, 1e-12);
  const CutAxis leaned{{0.0, 0.0, 0.0}, glm::normalize(glm::dvec3(0.1, 1.0, 0.0))};
  const Plane l = make_cut_cells(halves, lo, hi, nullptr, &leaned, {}, true).planes.at(0);
  EXPECT_NEAR(std::abs(glm::dot(l.normal, leaned.direction)), 1.0, 1e-12);
  EXPECT_NEAR(glm::length(glm::cross(l.point - leaned.point, leaned.direction)), 0.0, 1e-12);
  // The two cells are the halves above and below.
  const CutCells cells = make_cut_cells(halves, lo, hi, nullptr, nullptr, {}, true);
  ASSERT_EQ(cells.cells.size(), 2u);
  EXPECT_NE(in_cell(cells, cells.cells[0], {0, 0.01, 0}),
            in_cell(cells, cells.cells[0], {0, 0.05, 0}));
}

TEST(CutCells, SlicesAreCentredAndWedgesPartitionSpace) {
  const CutCells slices =
      make_cut_cells(*parse_cut_spec("slices:10", 1e-3), {-0.03, 0, -0.03}, {0.03, 0.052, 0.03});
  // 52 mm in 10 mm slices: 4 planes, end pieces 11 mm thick.
  ASSERT_EQ(slices.planes.size(), 4u);
  EXPECT_NEAR(slices.planes.front().point.y, 0.011, 1e-12);
  EXPECT_NEAR(slices.planes.back().point.y, 0.041, 1e-12);
  EXPECT_EQ(slices.cells.size(), 5u);
  for (int n : {2, 3, 5, 6}) {
    const CutCells wedges = make_cut_cells(*parse_cut_spec("wedges:" + std::to_string(n), 1e-3),
                                           glm::dvec3(-1), glm::dvec3(1));
    EXPECT_EQ(wedges.planes.size(), n % 2 ? size_t(n) : size_t(n / 2));
    ASSERT_EQ(wedges.cells.size(), size_t(n));
    // Every direction about the axis lies in exactly one wedge, the wedge of its angle.
    for (int k = 0; k < 72; ++k) {
      const double t = 2 * kPi * (k + 0.5) / 72;
      const glm::dvec3 x(std::cos(t), 0.3, -std::sin(t));
      int inside = 0, which = -1;
      for (size_t c = 0; c < wedges.cells.size(); ++c)
        if (in_cell(wedges, wedges.cells[c], x)) ++inside, which = static_cast<int>(c);
      EXPECT_EQ(inside, 1) << n << " wedges, angle " << t;
      EXPECT_EQ(which, static_cast<int>(t / (2 * kPi / n))) << n << " wedges, angle " << t;
    }
  }
}

TEST(ClipMesh, ClosedBoundaryAndVerticesOnThePlane) {
  // A unit square of two triangles in z = 0, clipped by x <= 0.5 and by x <= 1 (on its edge).
  ShadedMesh sq;
  sq.position = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  sq.normal.assign(4, {0, 0, 1});
  sq.colour = {{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {0, 0, 0}};
  sq.material = {{0, 1}, {1, 0}, {1, 0}, {0, 1}};
  sq.triangle = {{0, 1, 2}, {0, 2, 3}};
  const ShadedMesh half = clip_to_half_space(sq, {{0.5, 0, 0}, {1, 0, 0}}, false);
  double area = 0;
  for (const glm::uvec3& t : half.triangle)
    area += 0.5 * glm::length(glm::cross(half.position[t[1]] - half.position[t[0]],
                                         half.position[t[2]] - half.position[t[0]]));
  EXPECT_NEAR(area, 0.5, 1e-12);
  for (size_t i = 0; i < half.position.size(); ++i) {  // interpolated linearly
    EXPECT_NEAR(half.colour[i].x, half.position[i].x, 1e-12);
    EXPECT_NEAR(half.material[i].x, half.position[i].x, 1e-12);
    EXPECT_NEAR(half.material[i].y, 1 - half.position[i].x, 1e-12);
  }
  // The diagonal's crossing is shared: 3 + 2 crossings = 5 vertices...
  // (0,0),(0,1),(.5,0),(.5,.5),(.5,1)
  EXPECT_EQ(half.position.size(), 5u);
  // x <= 1: vertices at x = 1 count as positive, the boundary passes through them, no slivers.
  const ShadedMesh all = clip_to_half_space(sq, {{1, 0, 0}, {1, 0, 0}}, false);
  for (const glm::uvec3& t : all.triangle)
    EXPECT_GT(glm::length(glm::cross(all.position[t[1]] - all.position[t[0]],
                                     all.position[t[2]] - all.position[t[0]])),
              1e-12);
}

}  // namespace
}  // namespace cutaway
