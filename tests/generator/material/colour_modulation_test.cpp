// NPR Perlin colour modulation (generator/material/colour_modulation.h) and the template's `npr`
// block (template_parser.h, doc/npr.md): strength 0 is the identity, a point gets the same colour
// in whatever mesh it is (two caps sharing an edge agree along it), weights follow the documented
// closeness to a band's tint, results stay in 0..1; the parser's values, defaults and errors;
// the interior texture: bands stretched along the object's fields, cells with wall and centre
// colours, no seam where the angle wraps.
#include "material/colour_modulation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "base/colour.h"
#include "base/error.h"
#include "base/constants.h"
#include "base/random.h"
#include "io/template_parser.h"

namespace cutaway {
namespace {

glm::dvec3 srgb(double r, double g, double b) { return srgb_to_linear(glm::dvec3(r, g, b)); }

/// A tomato-like setting: fine speckle on red flesh, broad mottling on yellow gel, and a faint
/// untinted grain on everything.
NprSettings tomato_like() {
  NprSettings npr;
  PerlinBand fine;
  fine.frequency_per_m = 1.0 / 0.0015;
  fine.amplitude = 0.15;
  fine.tinted = true;
  fine.tint = srgb(0.9, 0.27, 0.18);
  fine.reach = 0.3;
  PerlinBand broad;
  broad.frequency_per_m = 1.0 / 0.008;
  broad.amplitude = 0.2;
  broad.tinted = true;
  broad.tint = srgb(0.94, 0.75, 0.38);
  broad.reach = 0.3;
  PerlinBand all;
  all.frequency_per_m = 1.0 / 0.02;
  all.amplitude = 0.05;
  npr.perlin_bands = {fine, broad, all};
  return npr;
}

/// A fan of triangles around `centre` in the plane spanned by `a` and `b` (object frame,
/// metres), with the vertices `shared` (their colours given) on its boundary and more vertices
/// of its own: one cap of a piece.
ShadedMesh make_cap(const std::vector<glm::dvec3>& shared, const std::vector<glm::dvec3>& colours,
                    const glm::dvec3& centre, const glm::dvec3& normal, bool shared_first) {
  ShadedMesh m;
  auto add = [&](const glm::dvec3& p, const glm::dvec3& c) {
    m.position.push_back(p);
    m.normal.push_back(normal);
    m.colour.push_back(c);
    return static_cast<unsigned>(m.position.size() - 1);
  };
  const unsigned c0 = add(centre, srgb(0.9, 0.3, 0.2));
  std::vector<unsigned> ring;
  if (!shared_first) {  // own vertices first, so that shared points have other indices
    ring.push_back(add(centre + (centre - shared.front()) * 0.5, srgb(0.8, 0.2, 0.1)));
  }
  for (size_t i = 0; i < shared.size(); ++i) ring.push_back(add(shared[i], colours[i]));
  ring.push_back(add(centre + (centre - shared.back()) * 0.7, srgb(0.95, 0.8, 0.4)));
  for (size_t i = 0; i + 1 < ring.size(); ++i) m.triangle.push_back({c0, ring[i], ring[i + 1]});
  return m;
}

TEST(ColourModulation, StrengthZeroIsTheIdentity) {
  ShadedMesh m;
  Rng rng(1);
  for (int i = 0; i < 100; ++i) {
    m.position.push_back({rng.uniform(-0.05, 0.05), rng.uniform(0, 0.1), rng.uniform(-0.05, 0.05)});
    m.normal.push_back({0, 1, 0});
    m.colour.push_back({rng.uniform(), rng.uniform(), rng.uniform()});
  }
  m.colour[0] = {1.5, -0.1, 0.5};  // not even clamped
  const ShadedMesh before = m;
  modulate_colours(m, tomato_like(), 0.0, 42);
  EXPECT_EQ(m.colour, before.colour);
  EXPECT_EQ(m.position, before.position);
  NprSettings none;  // no bands: identity at any strength
  modulate_colours(m, none, 3.0, 42);
  EXPECT_EQ(m.colour, before.colour);
  // And with bands and a strength, colours do change.
  modulate_colours(m, tomato_like(), 1.0, 42);
  int changed = 0;
  for (size_t i = 1; i < m.colour.size(); ++i) changed += m.colour[i] != before.colour[i];
  EXPECT_GT(changed, 80);
}

TEST(ColourModulation, CapsSharingAnEdgeAgreeAlongIt) {
  // Two caps of one object on perpendicular planes (z = 0.004 and x = 0.011, metres) meeting on
  // the line x = 0.011, z = 0.004: the points along it, with the colours the diffusion gives
  // both caps there, get the same modulated colours, whatever their indices and neighbours.
  std::vector<glm::dvec3> edge, colours;
  for (int i = 0; i <= 20; ++i) {
    const double t = i / 20.0;
    edge.push_back({0.011, -0.02 + 0.05 * t, 0.004});
    colours.push_back(glm::mix(srgb(0.9, 0.27, 0.18), srgb(0.94, 0.75, 0.38), t));
  }
  ShadedMesh a = make_cap(edge, colours, {0.03, 0.005, 0.004}, {0, 0, 1}, true);
  std::vector<glm::dvec3> edge_b(edge.rbegin(), edge.rend());  // the other cap runs backwards
  std::vector<glm::dvec3> colours_b(colours.rbegin(), colours.rend());
  ShadedMesh b = make_cap(edge_b, colours_b, {0.011, 0.005, 0.03}, {1, 0, 0}, false);
  const ShadedMesh a0 = a, b0 = b;

  const NprSettings npr = tomato_like();
  const uint64_t object_seed = derive_seed(7, {3, 1});
  modulate_colours(a, npr, 1.5, object_seed);
  modulate_colours(b, npr, 1.5, object_seed);
  int changed = 0;
  for (size_t i = 0; i < edge.size(); ++i) {
    const size_t ia = 1 + i, ib = 2 + (edge.size() - 1 - i);
    ASSERT_EQ(a.position[ia], b.position[ib]);
    EXPECT_EQ(a.colour[ia], b.colour[ib]) << "edge point " << i;
    changed += a.colour[ia] != a0.colour[ia];
  }
  EXPECT_GT(changed, 15);  // the modulation is not trivially the identity there
  // The off-edge vertices changed too (the caps are modulated, not just the edge).
  EXPECT_NE(b.colour[1], b0.colour[1]);

  // The same holds for parallel arrays (a cross-section's position and colour).
  std::vector<glm::dvec3> c = colours;
  modulate_colours(edge, c, npr, 1.5, object_seed);
  for (size_t i = 0; i < edge.size(); ++i) EXPECT_EQ(c[i], a.colour[1 + i]);
}

TEST(ColourModulation, ObjectsWithOtherSeedsDiffer) {
  const NprSettings npr = tomato_like();
  const ColourModulation m1(npr, 1), m1b(npr, 1), m2(npr, 2);
  Rng rng(9);
  int differ = 0;
  for (int i = 0; i < 200; ++i) {
    const glm::dvec3 p{rng.uniform(-0.03, 0.03), rng.uniform(0, 0.05), rng.uniform(-0.03, 0.03)};
    const glm::dvec3 c = srgb(0.9, 0.27, 0.18);
    EXPECT_EQ(m1(p, c, 1.0), m1b(p, c, 1.0));
    differ += m1(p, c, 1.0) != m2(p, c, 1.0);
  }
  EXPECT_GT(differ, 190);
}

TEST(ColourModulation, WeightsFollowClosenessToTheTint) {
  PerlinBand band;
  band.amplitude = 0.2;
  EXPECT_EQ(band_weight(band, srgb(0.1, 0.9, 0.3)), 0.2);  // untinted: every colour
  band.tinted = true;
  band.tint = srgb(0.8, 0.2, 0.1);
  band.reach = 0.3;
  EXPECT_NEAR(band_weight(band, band.tint), 0.2, 1e-12);
  // d = 0.15 in sRGB (0.15 along red): (1 - 0.25)^2 = 0.5625 of the amplitude.
  EXPECT_NEAR(band_weight(band, srgb(0.65, 0.2, 0.1)), 0.2 * 0.5625, 1e-9);
  // Decreasing with the distance, 0 at and beyond the reach.
  double last = 1;
  for (double d = 0; d <= 0.3; d += 0.01) {
    const double w = band_weight(band, srgb(0.8, 0.2 + d, 0.1));
    EXPECT_LE(w, last);
    last = w;
  }
  EXPECT_EQ(band_weight(band, srgb(0.8, 0.5, 0.1)), 0.0);
  EXPECT_EQ(band_weight(band, srgb(0.94, 0.75, 0.38)), 0.0);  // a yellow gel is far
  // Out-of-range colours are clamped before the distance.
  EXPECT_NEAR(band_weight(band, glm::dvec3(band.tint.r, band.tint.g, -0.5)),
              band_weight(band, glm::dvec3(band.tint.r, band.tint.g, 0.0)), 1e-15);
}

TEST(ColourModulation, FineSpeckleOnFleshAndBroadMottlingOnGel) {
  // With tomato_like(), red flesh varies on the fine band's scale and yellow gel only on the
  // broad ones: neighbouring points 0.4 mm apart differ much more on flesh than on gel.
  const ColourModulation m(tomato_like(), 5);
  const glm::dvec3 flesh = srgb(0.9, 0.27, 0.18), gel = srgb(0.94, 0.75, 0.38);
  Rng rng(2);
  double flesh_diff = 0, gel_diff = 0, gel_spread = 0;
  for (int i = 0; i < 2000; ++i) {
    const glm::dvec3 p{rng.uniform(-0.03, 0.03), rng.uniform(0, 0.05), rng.uniform(-0.03, 0.03)};
    const glm::dvec3 q = p + glm::dvec3(0.0004, 0, 0);
    flesh_diff += std::fabs(m.relative_change(p, flesh) - m.relative_change(q, flesh));
    gel_diff += std::fabs(m.relative_change(p, gel) - m.relative_change(q, gel));
    gel_spread += std::fabs(m.relative_change(p, gel));
  }
  EXPECT_GT(flesh_diff, 3 * gel_diff);
  EXPECT_GT(gel_spread / 2000, 0.01);  // the gel is modulated, just broadly
}

TEST(ColourModulation, StaysInRangeAndWithinTheDocumentedChange) {
  const NprSettings npr = tomato_like();
  double amplitudes = 0;
  for (const auto& b : npr.perlin_bands) amplitudes += b.amplitude;
  const ColourModulation m(npr, 77);
  Rng rng(8);
  for (int i = 0; i < 5000; ++i) {
    const glm::dvec3 p{rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1)};
    const glm::dvec3 c{rng.uniform(), rng.uniform(), rng.uniform()};
    const double rel = m.relative_change(p, c);
    ASSERT_LE(std::fabs(rel), amplitudes * PerlinNoise::kBound);
    const glm::dvec3 strong = m(p, c, 10.0);
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(strong[k], 0.0);
      EXPECT_LE(strong[k], 1.0);
    }
    // A brightness change: every component scaled by the same factor (unclamped here).
    const glm::dvec3 weak = m(p, c * 0.5, 1.0);
    const double f = 1 + m.relative_change(p, c * 0.5);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(weak[k], c[k] * 0.5 * f, 1e-15);
  }
}

TEST(ColourModulation, RefusesBadArguments) {
  std::vector<glm::dvec3> pos(3), col(2);
  EXPECT_THROW(modulate_colours(pos, col, tomato_like(), 1.0, 1), InternalError);
  col.resize(3);
  EXPECT_THROW(modulate_colours(pos, col, tomato_like(), -1.0, 1), InternalError);
  EXPECT_THROW(modulate_colours(pos, col, tomato_like(), NAN, 1), InternalError);
  EXPECT_NO_THROW(modulate_colours(pos, col, tomato_like(), 1.0, 1));
}

// The template's `npr` block (template_parser.h; doc/npr.md).

const char* const kModulationTemplateHead = R"(format: cutaway-template/1
name: npr
units: cm
symmetry: {type: cylindrical}
surfaces:
  - name: skin
    kind: around
    role: skin
    profile: [[0, 0], [2, 1], [2.5, 2], [2, 3], [0, 4]]
)";

Template parse_npr(const std::string& npr) {
  return parse_template(kModulationTemplateHead + npr, "t.yaml", ".");
}

InputError npr_error_of(const std::string& npr) {
  try {
    parse_npr(npr);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "expected an InputError for:\n" << npr;
  return InputError(FileLoc{}, "", "");
}

TEST(NprBlock, ParsesBandsInTemplateUnits) {
  const Template t = parse_npr(R"(npr:
  perlin:
    bands:
      - {period: 0.2, amplitude: 0.12, tint: "#c8281e", reach: 0.35}
      - {period: 1, amplitude: 0.08}
)");
  ASSERT_EQ(t.npr.perlin_bands.size(), 2u);
  EXPECT_TRUE(t.npr.perlin_from_file);
  const PerlinBand& a = t.npr.perlin_bands[0];
  EXPECT_NEAR(a.frequency_per_m, 1 / 0.002, 1e-9);  // 0.2 cm
  EXPECT_DOUBLE_EQ(a.amplitude, 0.12);
  EXPECT_TRUE(a.tinted);
  EXPECT_NEAR(a.tint.r, srgb_to_linear(0xc8 / 255.0), 1e-12);  // linear RGB
  EXPECT_DOUBLE_EQ(a.reach, 0.35);
  const PerlinBand& b = t.npr.perlin_bands[1];
  EXPECT_NEAR(b.frequency_per_m, 1 / 0.01, 1e-9);
  EXPECT_FALSE(b.tinted);
  EXPECT_DOUBLE_EQ(b.reach, 0.25);  // the default (unused without a tint)
}

TEST(NprBlock, DefaultsFromTheSkinHeightAndAnEmptyListTurnsItOff) {
  for (const std::string& npr : {std::string(), std::string("npr: {}\n")}) {
    const Template t = parse_npr(npr);
    EXPECT_FALSE(t.npr.perlin_from_file);
    ASSERT_EQ(t.npr.perlin_bands.size(), 2u);  // skin height 4 cm
    EXPECT_NEAR(t.npr.perlin_bands[0].frequency_per_m, 16 / 0.04, 1e-9);
    EXPECT_NEAR(t.npr.perlin_bands[1].frequency_per_m, 5 / 0.04, 1e-9);
    EXPECT_GT(t.npr.perlin_bands[0].amplitude, 0);
    EXPECT_FALSE(t.npr.perlin_bands[0].tinted);
  }
  const Template off = parse_npr("npr: {perlin: {bands: []}}\n");
  EXPECT_TRUE(off.npr.perlin_from_file);
  EXPECT_TRUE(off.npr.perlin_bands.empty());
}

TEST(NprBlock, RefusesBadValuesWithTheirLocation) {
  struct Case {
    std::string npr;
    int line, column;
    std::string field, rule;
  };
  const Case cases[] = {
      {"npr: {silhouettes: 1}\n", 10, 7, "npr.silhouettes", "unknown field \"silhouettes\""},
      {"npr: {perlin: {}}\n", 10, 15, "npr.perlin", "missing required field 'bands'"},
      {"npr: {perlin: {bands: [{amplitude: 0.1}]}}\n", 10, 24, "npr.perlin.bands[0]",
       "missing required field 'period'"},
      {"npr: {perlin: {bands: [{period: -1, amplitude: 0.1}]}}\n", 10, 33,
       "npr.perlin.bands[0].period", "must not be negative"},
      {"npr: {perlin: {bands: [{period: 1, amplitude: -0.1}]}}\n", 10, 47,
       "npr.perlin.bands[0].amplitude", "must be between 0 and 1"},
      {"npr: {perlin: {bands: [{period: 1, amplitude: 0.1, tint: '#fff'}]}}\n", 10, 58,
       "npr.perlin.bands[0].tint", "not \"#fff\""},
      {"npr: {perlin: {bands: [{period: 1, amplitude: 0.1, tint: '#ffffff', reach: 0}]}}\n", 10, 76,
       "npr.perlin.bands[0].reach", "must be positive"},
      {"npr: {perlin: {bands: [{period: 1, amplitude: 0.1, tint: '#ffffff', reach: 2}]}}\n", 10, 76,
       "npr.perlin.bands[0].reach", "must be between 0 and 1.75"},
  };
  for (const Case& c : cases) {
    const InputError e = npr_error_of(c.npr);
    EXPECT_EQ(e.loc().file, "t.yaml");
    EXPECT_EQ(e.loc().line, c.line) << c.npr << e.what();
    EXPECT_EQ(e.loc().column, c.column) << c.npr << e.what();
    EXPECT_EQ(e.field(), c.field) << e.what();
    EXPECT_NE(e.rule().find(c.rule), std::string::npos) << e.what();
  }
  // More than 8 bands.
  std::string many = "npr: {perlin: {bands: [";
  for (int i = 0; i < 9; ++i) many += std::string(i ? ", " : "") + "{period: 1, amplitude: 0.1}";
  const InputError e = npr_error_of(many + "]}}\n");
  EXPECT_EQ(e.field(), "npr.perlin.bands");
  EXPECT_NE(e.rule().find("at most 8 bands, not 9"), std::string::npos) << e.what();
}

TEST(NprBlock, ParsesFieldsAndCellsAndCountsCellsRoundTheWidestRadius) {
  // The head's skin is 2.5 cm at its widest: 2 pi 25 mm / 1 mm = 157 cells around.
  const Template t = parse_npr(R"(npr:
  perlin:
    bands:
      - {period: 0.1, amplitude: 0.3, along: radial, stretch: 8}
      - {period: 0.1, amplitude: 0.3, along: around, stretch: 4}
      - {period: 0.1, amplitude: 0.3, along: axial, stretch: 3}
  cells:
    - {size: 0.2, amplitude: 0.5, wall: "#ffffff", wall_width: 0.3, along: radial, stretch: 2}
    - {size: 0.5, amplitude: 0.4, centre: "#ff8000", centre_roughness: 0.1, tint: "#ffa000", reach: 0.3}
)");
  ASSERT_EQ(t.npr.perlin_bands.size(), 3u);
  EXPECT_EQ(t.npr.perlin_bands[0].along, TextureField::Radial);
  EXPECT_DOUBLE_EQ(t.npr.perlin_bands[0].stretch, 8);
  EXPECT_EQ(t.npr.perlin_bands[0].around_cells, 157u);
  EXPECT_EQ(t.npr.perlin_bands[1].along, TextureField::Around);
  EXPECT_EQ(t.npr.perlin_bands[1].around_cells, 39u);  // 157 / 4, rounded
  EXPECT_EQ(t.npr.perlin_bands[2].along, TextureField::Axial);
  EXPECT_EQ(t.npr.perlin_bands[2].around_cells, 0u);
  ASSERT_EQ(t.npr.cell_bands.size(), 2u);
  const CellBand& a = t.npr.cell_bands[0];
  EXPECT_TRUE(a.has_wall);
  EXPECT_FALSE(a.has_centre);
  EXPECT_DOUBLE_EQ(a.wall_width, 0.3);
  EXPECT_NEAR(a.frequency_per_m, 1 / 0.002, 1e-9);
  EXPECT_EQ(a.around_cells, 79u);  // 2 pi 25 / 2, rounded
  const CellBand& b = t.npr.cell_bands[1];
  EXPECT_TRUE(b.has_centre && b.tinted);
  EXPECT_DOUBLE_EQ(b.wall_width, 0.15);  // the default
  EXPECT_EQ(b.along, TextureField::None);
  EXPECT_DOUBLE_EQ(b.centre_roughness, 0.1);
  EXPECT_LT(b.wall_roughness, 0);  // none
  EXPECT_LT(a.centre_roughness, 0);
}

TEST(NprBlock, RefusesBadFieldsAndCellsWithTheirLocation) {
  struct Case {
    std::string npr;
    std::string field, rule;
  };
  const Case cases[] = {
      {"npr: {perlin: {bands: [{period: 1, amplitude: 0.1, along: sideways}]}}\n",
       "npr.perlin.bands[0].along", "must be none, radial, around or axial, not \"sideways\""},
      {"npr: {perlin: {bands: [{period: 1, amplitude: 0.1, stretch: 2}]}}\n",
       "npr.perlin.bands[0].stretch", "needs a field to stretch along"},
      {"npr: {perlin: {bands: [{period: 1, amplitude: 0.1, along: axial, stretch: 0.5}]}}\n",
       "npr.perlin.bands[0].stretch", "must be between 1 and 64"},
      {"npr: {perlin: {bands: [{period: 0.001, amplitude: 0.1, along: radial}]}}\n",
       "npr.perlin.bands[0].period", "too fine for a field around the axis: 15708 cells"},
      {"npr: {cells: [{size: 0.001, amplitude: 0.1, wall: '#ffffff', along: around}]}\n",
       "npr.cells[0].size", "at most 256"},
      {"npr: {cells: [{size: 1, amplitude: 0.1}]}\n", "npr.cells[0]",
       "needs a wall or a centre colour"},
      {"npr: {cells: [{size: 1, amplitude: 0.1, centre: '#ffffff', wall_width: 0.2}]}\n",
       "npr.cells[0].wall_width", "needs a wall colour"},
      {"npr: {cells: [{size: 1, amplitude: 0.1, centre: '#ffffff', wall_roughness: 0.2}]}\n",
       "npr.cells[0].wall_roughness", "needs a wall colour"},
      {"npr: {cells: [{size: 1, amplitude: 0.1, wall: '#ffffff', centre_roughness: 0.2}]}\n",
       "npr.cells[0].centre_roughness", "needs a centre colour"},
      {"npr: {cells: [{size: 1, amplitude: 0.1, centre: '#ffffff', centre_roughness: 1.5}]}\n",
       "npr.cells[0].centre_roughness", "between 0 and 1"},
      {"npr: {cells: [{amplitude: 0.1, wall: '#ffffff'}]}\n", "npr.cells[0]",
       "missing required field 'size'"},
      {"npr: {cells: [{size: 1, amplitude: 0.1, wall: '#ffffff', colour: 1}]}\n",
       "npr.cells[0].colour", "unknown field"},
  };
  for (const Case& c : cases) {
    const InputError e = npr_error_of(c.npr);
    EXPECT_EQ(e.loc().line, 10) << c.npr << e.what();
    EXPECT_EQ(e.field(), c.field) << e.what();
    EXPECT_NE(e.rule().find(c.rule), std::string::npos) << e.what();
  }
}

/// One untinted band of `period_m` stretched along `along`, its around_cells as the parser
/// would set them for a skin 25 mm at its widest.
NprSettings one_field_band(TextureField along, double stretch, double period_m) {
  NprSettings npr;
  PerlinBand b;
  b.frequency_per_m = 1 / period_m;
  b.amplitude = 0.5;
  b.along = along;
  b.stretch = stretch;
  if (along == TextureField::Radial || along == TextureField::Around)
    b.around_cells = static_cast<unsigned>(
        std::round(2 * kPi * 0.025 / period_m / (along == TextureField::Around ? stretch : 1)));
  npr.perlin_bands.push_back(b);
  return npr;
}

/// The mean squared difference of the band's noise between points `step` apart along `dir(p)`,
/// over points scattered in a ring 5 to 20 mm from the axis.
double mean_square_step(const ColourModulation& m, glm::dvec3 (*dir)(const glm::dvec3&),
                        double step) {
  Rng rng(17);
  double sum = 0;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    const double r = rng.uniform(0.005, 0.02), a = rng.uniform(0, 2 * kPi);
    const glm::dvec3 p(r * std::cos(a), rng.uniform(0, 0.04), r * std::sin(a));
    const glm::dvec3 q = p + step * dir(p);
    const glm::dvec3 grey(0.5);
    const double d = m.relative_change(p, grey) - m.relative_change(q, grey);
    sum += d * d;
  }
  return sum / n;
}

glm::dvec3 radial_dir(const glm::dvec3& p) { return glm::normalize(glm::dvec3(p.x, 0, p.z)); }
glm::dvec3 around_dir(const glm::dvec3& p) { return glm::normalize(glm::dvec3(-p.z, 0, p.x)); }
glm::dvec3 axial_dir(const glm::dvec3&) { return {0, 1, 0}; }

TEST(InteriorTexture, StretchedNoiseVariesSlowlyAlongItsFieldAndFastAcrossIt) {
  // Along the field the noise changes over stretch times the distance it does across it: the
  // mean squared change over one step along is far smaller than over the same step across.
  struct Case {
    TextureField along;
    glm::dvec3 (*with)(const glm::dvec3&);
    glm::dvec3 (*across)(const glm::dvec3&);
  };
  const Case cases[] = {{TextureField::Radial, radial_dir, axial_dir},
                        {TextureField::Around, around_dir, axial_dir},
                        {TextureField::Axial, axial_dir, radial_dir}};
  for (const Case& c : cases) {
    const ColourModulation m(one_field_band(c.along, 8, 0.001), 3);
    const double along = mean_square_step(m, c.with, 0.0004);
    const double across = mean_square_step(m, c.across, 0.0004);
    // Around the axis the lattice spacing is an angle, stretched exactly at the skin's widest
    // radius (25 mm) and less nearer the axis: these points lie 5 to 20 mm from it.
    EXPECT_LT(along, 0.25 * across) << static_cast<int>(c.along);
    // Unstretched, the same field reads alike both ways (within sampling noise).
    const ColourModulation iso(one_field_band(c.along, 1, 0.001), 3);
    const double a1 = mean_square_step(iso, c.with, 0.0002);
    const double c1 = mean_square_step(iso, c.across, 0.0002);
    EXPECT_GT(a1, 0.2 * c1) << static_cast<int>(c.along);
  }
}

TEST(InteriorTexture, FieldsAroundTheAxisHaveNoSeamWhereTheAngleWraps) {
  // atan2 jumps from pi to -pi on the -X side: the periodic lattice must make the colour
  // continuous there, for noise and for cells.
  NprSettings npr = one_field_band(TextureField::Radial, 4, 0.001);
  CellBand cells;
  cells.frequency_per_m = 1 / 0.0015;
  cells.amplitude = 1;
  cells.has_wall = cells.has_centre = true;
  cells.wall = glm::dvec3(1);
  cells.centre = glm::dvec3(0.2, 0.1, 0);
  cells.along = TextureField::Around;
  cells.stretch = 2;
  cells.around_cells = 52;
  npr.cell_bands.push_back(cells);
  const ColourModulation m(npr, 9);
  const glm::dvec3 grey(0.4);
  double worst_seam = 0, worst_elsewhere = 0;
  for (int i = 0; i < 200; ++i) {
    const double r = 0.004 + i * 0.00008, y = 0.001 * i;
    const double e = 1e-7;  // angles just either side of the wrap, and of an ordinary point
    const glm::dvec3 a = m(glm::dvec3(-r, y, e * r), grey, 1),
                     b = m(glm::dvec3(-r, y, -e * r), grey, 1);
    const glm::dvec3 c = m(glm::dvec3(r, y, e * r), grey, 1),
                     d = m(glm::dvec3(r, y, -e * r), grey, 1);
    worst_seam = std::max(worst_seam, glm::length(a - b));
    worst_elsewhere = std::max(worst_elsewhere, glm::length(c - d));
  }
  EXPECT_LT(worst_seam, 1e-4);
  EXPECT_LT(worst_elsewhere, 1e-4);
}

/// A layer of cells 2 mm apart at full amplitude, pale walls 0.2 wide and red centres, acting
/// on an orange flesh (srgb(0.9, 0.5, 0.1)) within a reach of 0.3.
CellBand orange_cells() {
  CellBand cells;
  cells.frequency_per_m = 1 / 0.002;
  cells.amplitude = 1;
  cells.has_wall = cells.has_centre = true;
  cells.wall = glm::dvec3(0.9, 0.9, 0.8);
  cells.centre = glm::dvec3(0.6, 0.1, 0.0);
  cells.wall_width = 0.2;
  cells.tinted = true;
  cells.tint = srgb(0.9, 0.5, 0.1);
  cells.reach = 0.3;
  return cells;
}

TEST(InteriorTexture, CellWallsAndCentresTakeTheirColoursWhereTheMasksSayAndOnlyThere) {
  NprSettings npr;
  const CellBand cells = orange_cells();
  npr.cell_bands.push_back(cells);
  npr.perlin_bands.clear();
  const uint64_t seed = 21;
  const ColourModulation m(npr, seed);
  const glm::dvec3 flesh = srgb(0.9, 0.5, 0.1), far = srgb(0.1, 0.6, 0.1);
  Rng rng(5);
  int walls = 0, centres = 0;
  for (int i = 0; i < 3000; ++i) {
    const glm::dvec3 p(rng.uniform(-0.01, 0.01), rng.uniform(0, 0.02), rng.uniform(-0.01, 0.01));
    // The same masks ColourModulation reads: its lattice is derive_seed(seed, {"cell", 0}).
    const CellMasks k = cell_masks(cells, derive_seed(seed, {0x63656c6c, 0}), p);
    ASSERT_GE(k.wall, 0);
    ASSERT_LE(k.wall, 1);
    ASSERT_GE(k.centre, 0);
    ASSERT_LE(k.centre, 1);
    // At the tint the weight is 1: the centre's colour by its mask, then the wall's by its.
    const glm::dvec3 c = m(p, flesh, 1);
    const glm::dvec3 centred = flesh + (cells.centre - flesh) * k.centre;
    EXPECT_LT(glm::length(c - (centred + (cells.wall - centred) * k.wall)), 1e-12);
    if (k.wall == 1) {
      ++walls;
      EXPECT_LT(glm::length(c - cells.wall), 1e-12);  // full strength: the wall's own colour
    }
    if (k.wall == 0 && k.centre > 0.5) ++centres;
    EXPECT_EQ(m(p, far, 1), far);      // beyond the reach: untouched
    EXPECT_EQ(m(p, flesh, 0), flesh);  // strength 0: untouched
  }
  EXPECT_GT(walls, 50);
  EXPECT_GT(centres, 10);
}

TEST(InteriorTexture, CellsWithARoughnessMoveTheMaterialChannelsAsTheColour) {
  NprSettings npr;
  CellBand cells = orange_cells();
  cells.wall_roughness = 0.7;
  cells.centre_roughness = 0.1;
  npr.cell_bands.push_back(cells);
  const uint64_t seed = 21;
  const ColourModulation m(npr, seed);
  CellBand plain = cells;  // the same layer without roughness
  plain.wall_roughness = plain.centre_roughness = -1;
  NprSettings plain_npr = npr;
  plain_npr.cell_bands = {plain};
  const ColourModulation without(plain_npr, seed);
  const glm::dvec3 flesh = srgb(0.9, 0.5, 0.1), far = srgb(0.1, 0.6, 0.1);
  const glm::dvec2 before(0.3, 0.4);
  Rng rng(6);
  int glossy = 0, dull = 0;
  for (int i = 0; i < 3000; ++i) {
    const glm::dvec3 p(rng.uniform(-0.01, 0.01), rng.uniform(0, 0.02), rng.uniform(-0.01, 0.01));
    const CellMasks k = cell_masks(cells, derive_seed(seed, {0x63656c6c, 0}), p);
    glm::dvec2 material = before;
    // The colour is the one without the material channels.
    EXPECT_EQ(m(p, flesh, 1, material), m(p, flesh, 1));
    const double centred = before.x + (0.1 - before.x) * k.centre;
    EXPECT_NEAR(material.x, centred + (0.7 - centred) * k.wall, 1e-12);
    EXPECT_EQ(material.y, before.y);  // translucency stays
    if (material.x < 0.15) ++glossy;
    if (material.x > 0.65) ++dull;
    glm::dvec2 untouched = before;
    without(p, flesh, 1, untouched);
    EXPECT_EQ(untouched, before);  // a layer without roughness leaves the channels
    untouched = before;
    m(p, far, 1, untouched);
    EXPECT_EQ(untouched, before);  // beyond the reach
  }
  EXPECT_GT(glossy, 10);
  EXPECT_GT(dull, 50);
}

}  // namespace
}  // namespace cutaway
