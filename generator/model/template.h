// The parsed template (doc/template-format.md): plain data, lengths in metres, colours in linear
// RGB, angles in radians. Parsing and validation live in template_parser.h; algorithms never see
// YAML.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "base/error.h"
#include "model/pbr_material.h"

namespace cutaway {

enum class Symmetry { Cylindrical, NFold, None };
enum class SurfaceKind { Around, Within, Mesh };

/// What a gradient's parameter t runs along (doc/template-format.md, GRADIENT): the profile's or
/// the section's normalised arc length, or the variant's ripeness (Template::ripeness).
enum class GradientAxis { Constant, Profile, Section, Ripeness };

/// The value at t of stops (t_k, v_k) with increasing t_k: blended linearly between the two
/// stops around t, clamped to the first and last; `value` turns a stop's v into a T.
template <class T, class Stop, class Value>
T blend_stops(const std::vector<std::pair<double, Stop>>& stops, double t, Value value) {
  if (stops.size() == 1 || t <= stops.front().first) return value(stops.front().second);
  if (t >= stops.back().first) return value(stops.back().second);
  for (size_t i = 1; i < stops.size(); ++i) {
    if (t <= stops[i].first) {
      const double t0 = stops[i - 1].first, t1 = stops[i].first;
      const double a = t1 > t0 ? (t - t0) / (t1 - t0) : 1.0;
      const T v0 = value(stops[i - 1].second), v1 = value(stops[i].second);
      return v0 + (v1 - v0) * a;
    }
  }
  return value(stops.back().second);
}

/// A value that is constant or varies linearly between stops along the profile or the section:
/// one stop of a gradient along the ripeness (below).
template <class T>
struct CurveGradient {
  GradientAxis along = GradientAxis::Constant;  ///< Constant, Profile or Section
  std::vector<std::pair<double, T>> stops;      ///< increasing t in 0..1 with their values

  /// The value at t_profile or t_section (whichever the gradient runs along), clamped.
  T at(double t_profile, double t_section) const {
    return value_at(along, stops, t_profile, t_section);
  }

  /// The value of `stops` along `along` (Constant, Profile or Section) at the two parameters.
  static T value_at(GradientAxis along, const std::vector<std::pair<double, T>>& stops,
                    double t_profile, double t_section) {
    const double t = along == GradientAxis::Profile ? t_profile : t_section;
    return blend_stops<T>(stops, t, [](const T& v) { return v; });
  }
};

/// A value that is constant or varies linearly between stops along the profile, the section or
/// the ripeness (doc/template-format.md: COLOR, LENGTH, GRADIENT). T is glm::dvec3 (linear RGB)
/// or double (metres). Along the ripeness each stop holds a whole field (constant, or itself
/// along the profile or the section), so a banana's skin can be brown at the tip and green at
/// the stalk, and greener or yellower as a whole.
template <class T>
struct Gradient {
  GradientAxis along = GradientAxis::Constant;
  /// Constant, Profile, Section: increasing t in 0..1 with their values; one stop when constant.
  std::vector<std::pair<double, T>> stops;
  /// Ripeness: increasing ripeness in 0..1 with the field at it.
  std::vector<std::pair<double, CurveGradient<T>>> by_ripeness;

  /// A constant field.
  static Gradient constant(T value) {
    Gradient g;
    g.stops.emplace_back(0.0, value);
    return g;
  }

  /// The value at normalised arc length t_profile along the profile and t_section along the
  /// section (both 0..1), for a variant of the given ripeness (0..1); the parameters the
  /// gradient does not run along are ignored. Values beyond the first and last stops are clamped.
  T at(double t_profile, double t_section, double ripeness) const {
    if (along == GradientAxis::Ripeness) {
      return blend_stops<T>(by_ripeness, ripeness,
                            [&](const CurveGradient<T>& g) { return g.at(t_profile, t_section); });
    }
    return CurveGradient<T>::value_at(along, stops, t_profile, t_section);
  }
};

using ColourField = Gradient<glm::dvec3>;  ///< linear RGB
using LengthField = Gradient<double>;      ///< metres

/// A horizontal curve: `circle`, or closed loops of [x, z] points (metres) in the XZ plane seen
/// from +Y. `around`: one loop. `within`: one loop (fold 0, repeated) or one loop per fold.
struct SectionSpec {
  bool circle = false;
  std::vector<std::vector<glm::dvec2>> loops;
  FileLoc loc;
};

/// A `mesh` surface's triangle mesh as its PLY file holds it (read by io/mesh_file.h; turned
/// into a DS surface by model/mesh_surface.h). Lengths in the template's units.
struct MeshData {
  /// #V points, every vertex the file declares (those no triangle uses too), template units
  std::vector<glm::dvec3> points;
  /// #F by 3 vertex indices, each triangle's corners in the order OpenMesh walks them
  std::vector<std::array<int, 3>> triangles;
  /// #V per-vertex colours, linear RGB (the file's front_* and back_* properties), or empty
  std::vector<glm::dvec3> front, back;
  std::vector<double> blur;   ///< #V per-vertex blur, template units (`blur`), or empty
  bool closed = false;        ///< no edge has a triangle on one side only
  double signed_volume6 = 0;  ///< six times the signed volume: negative when wound inwards
};

/// An `around` section written for one height of its profile (`sections`): `at` is the
/// normalised arc length along the profile, 0 at its first point, 1 at its last.
struct HeightSection {
  double at = 0;
  SectionSpec section;
};

/// One diffusion surface of the template (doc/template-format.md, Surfaces).
struct SurfaceSpec {
  std::string name;
  SurfaceKind kind = SurfaceKind::Around;
  bool is_skin = false;
  /// around: open curve bottom to top, [r, y] in metres, r >= 0. within: closed curve, r > 0.
  std::vector<glm::dvec2> profile;
  SectionSpec section;
  /// around, cylindrical: sections at several heights, `at` increasing (at least two), blended
  /// between them (sweep.h); empty: `section` at every height. When set, `section` is the
  /// first of them.
  std::vector<HeightSection> sections;
  /// around: the angles (radians, from +X towards -Z, first < second, less than a turn apart)
  /// between which the surface covers the way round (`span`: a leaf, a membrane); equal: all
  /// the way round, closed.
  glm::dvec2 span_rad{0.0};
  /// true: centripetal Catmull-Rom spline through the points; false: polyline.
  bool smooth = true;
  ColourField front = ColourField::constant({0.5, 0.5, 0.5});
  ColourField back = ColourField::constant({0.5, 0.5, 0.5});
  LengthField blur = LengthField::constant(0.0);
  /// Material channels (roughness, translucency) of each side, 0..1 (doc/template-format.md,
  /// Materials: `roughness`, `translucency`); absent: the template's cut material.
  glm::dvec2 material_front{0.6, 0.0}, material_back{0.6, 0.0};
  bool visible_front = true;
  bool visible_back = true;
  /// A closed inner surface that a knife does not cross (a stone, a pit, a shell): cuts leave
  /// it whole in one piece and an imprint of it in the others (doc/template-format.md, Rigid
  /// surfaces; algorithms.md §4).
  bool rigid = false;
  /// An inner surface moved off the axis (part_placement.h): turned by `tilt_rad` (about +X,
  /// then about +Z, through the centre of its bounding box), then moved by `offset_m`
  /// (metres), together with every surface it encloses. Zero: where it was swept.
  glm::dvec3 offset_m{0.0};
  glm::dvec2 tilt_rad{0.0};
  /// How far a variant may move the surface from its offset, metres (`wander`): each variant
  /// adds a seeded offset within a ball of this radius times its amount (draw_variant).
  double wander_m = 0;
  /// mesh: the PLY file, resolved relative to the template's directory, and what it holds
  /// (shared by the copies of the template, e.g. its variants)
  std::string mesh_file;
  std::shared_ptr<const MeshData> mesh;
  /// Where the surface, its profile and its section are written (for geometric errors).
  FileLoc loc, profile_loc, mesh_loc;
  /// Field path prefix for errors, e.g. "surfaces[2]".
  std::string path;
};

/// Grains scattered over a surface by Poisson-disc dart throwing (doc/template-format.md, Grains).
struct GrainSpec {
  std::string name;
  std::string on;       ///< name of the surface they are scattered over, or
                        ///< empty for grains through a region (`inside`)
  std::string inside;   ///< grains through a region: the closed surface they lie inside
  std::string outside;  ///< and, optionally, the closed surface they lie outside of
  glm::dvec2 region_profile{0.0, 1.0};  ///< normalised arc-length range along the profile
  glm::dvec2 region_section{0.0, 1.0};  ///< normalised arc-length range along the section
  double spacing = 0.0;                 ///< Poisson-disc radius, metres
  bool on_front = false;                ///< side of `on` they sit on (default back)
  double depth = 0.0;                   ///< centre distance from `on` towards the side, metres
  glm::dvec3 semi_axes{0.0};            ///< ellipsoid semi-axes (profile tangent, section
                                        ///< tangent, normal), metres
  glm::dvec3 front{0.0}, back{0.0};     ///< linear RGB
  double blur = 0.0;                    ///< metres
  glm::dvec2 material_front{0.6, 0.0}, material_back{0.6, 0.0};  ///< (roughness, translucency)
  double jitter = 0.0;  ///< relative variation of size and orientation, 0..1
  /// A smaller grain inside each grain (a seed in its aril): the same centre and frame, the
  /// semi-axes times `scale`, a surface of its own (grain_core_name) with its own colours.
  struct Core {
    double scale = 0.5;                ///< 0 < scale < 1
    glm::dvec3 front{0.0}, back{0.0};  ///< linear RGB: its outside, its inside
    glm::dvec2 material_front{0.6, 0.0}, material_back{0.6, 0.0};  ///< (roughness, translucency)
  };
  std::optional<Core> core;
  FileLoc loc, spacing_loc, shape_loc;  ///< the item, its `spacing` and its `shape`
  std::string path;
};

/// The name of the surface that holds the cores of grain set `spec` (GrainSpec::core):
/// "<name>-core".
inline std::string grain_core_name(const GrainSpec& spec) { return spec.name + "-core"; }

/// The direction field a texture band is stretched along (doc/algorithms.md §6, Interior
/// texture; doc/npr.md). Fields are about the object's axis (the object frame's y axis through
/// x = z = 0) and use cylindrical coordinates, so they cut consistently at any plane.
enum class TextureField {
  None,    ///< isotropic: the band's period in every direction
  Radial,  ///< along rays from the axis (kiwi rays, pineapple and mango fibres, vesicles)
  Around,  ///< around the axis, along the section (rings, wall cells of a melon's rind)
  Axial,   ///< along the axis (celery's strands, a banana's or a leek's fibres)
};

/// What every texture band shares: its lattice, its weight and its direction field.
/// Its weight for an unmodulated colour c is amplitude * closeness(c), where closeness is 1 for
/// an untinted band and otherwise falls smoothly from 1 at the tint to 0 at `reach` (distance
/// in sRGB 0..1 components): (1 - (d / reach)^2)^2 for d < reach.
struct TextureBand {
  double frequency_per_m = 1.0;  ///< lattice cells per metre (1 / the file's `period` or `size`)
  double amplitude = 0.0;        ///< 0..1; see PerlinBand and CellBand for its effect
  bool tinted = false;           ///< false: the band acts on every colour with weight 1
  glm::dvec3 tint{0.0};          ///< linear RGB; the colour the band acts on most
  double reach = 0.25;           ///< sRGB distance at which the weight reaches 0, > 0
  TextureField along = TextureField::None;
  double stretch = 1.0;  ///< >= 1: the lattice spacing along the field is stretch times longer
  /// Radial and Around: lattice cells round a whole turn (1..256), the around coordinate's
  /// period: 2 pi R / period for Radial, 2 pi R / (period * stretch) for Around, R the skin's
  /// widest radius, rounded (at least 1). 0 for None and Axial.
  unsigned around_cells = 0;
};

/// One frequency band of the Perlin colour modulation (doc/algorithms.md §6; doc/npr.md): a
/// relative brightness change of amplitude * closeness per unit of noise at strength 1.
struct PerlinBand : TextureBand {};

/// One layer of cells (Worley 1996) in the colour (doc/algorithms.md §6, Interior texture):
/// walls between cells drawn towards `wall`, cell centres towards `centre`, each by
/// min(1, strength * amplitude * closeness) times its mask.
struct CellBand : TextureBand {
  bool has_wall = false, has_centre = false;
  glm::dvec3 wall{0.0}, centre{0.0};  ///< linear RGB
  double wall_width = 0.15;           ///< 0..1, of a cell's spacing (lattice units)
  /// The walls' and centres' own perceptual roughness (0..1; -1: none), blended into the cut
  /// faces' material map as the colours are into their colour: a juice vesicle's wet centre
  /// glossier than its wall.
  double wall_roughness = -1, centre_roughness = -1;
};

/// Non-photorealistic rendering parameters of a template (doc/template-format.md, NPR;
/// doc/npr.md). A scene scales the modulation with its render.perlin strength.
struct NprSettings {
  /// The Perlin bands. When the template has no `npr.perlin`, two untinted bands derived from
  /// the skin's height h: fine grain (period h / 16, amplitude 0.2) and broad mottling (period
  /// h / 5, amplitude 0.3). An empty list turns the modulation off for the template.
  std::vector<PerlinBand> perlin_bands;
  bool perlin_from_file = false;     ///< whether the bands were written in the file
  std::vector<CellBand> cell_bands;  ///< `npr.cells`; none unless written
};

/// One layer of the skin's pattern (doc/template-format.md, Skin patterns): a colour laid over
/// the skin's outside where the pattern is, baked into the skin texture, and a relief, baked
/// into the skin's normal map.
struct SkinPatternLayer {
  enum class Kind { Stripes, Speckles, Net, Grains };
  Kind kind = Kind::Stripes;
  glm::dvec3 colour{0.0};  ///< linear RGB
  double opacity = 1.0;    ///< 0..1: how much of `colour` covers the skin inside the pattern
  double softness = 0.2;   ///< 0..1: the blended share of the edge (of a stripe's half width
                           ///< or a speckle's radius)
  // Stripes: bands along the profile, `count` around the section.
  int count = 0;        ///< stripes around the section, 1..256
  double width = 0.5;   ///< share of each period a stripe covers, 0..1 exclusive
  double wobble = 0.0;  ///< sideways waviness, in periods (0..1): Perlin noise along the skin
  // Speckles: spots where spheres about jittered lattice points meet the skin. Net: lines
  // where the skin meets the walls between the cells of those points (a cantaloupe's netting).
  double spacing_m = 0.0;  ///< lattice spacing, metres
  double size_m = 0.0;     ///< speckles, grains: spot radius; net: line width; metres
  double jitter = 0.0;     ///< speckles: 0..1, relative variation of the radius
  /// Grains: spots of radius size_m about the sites of the grain set of this name (which lies
  /// on the skin), where its grains sit under the skin (a strawberry's achenes in dimples).
  std::string grain_set;
  /// Skin relief: the height of the skin inside the pattern, metres, raised (> 0: a net's
  /// ridges, pebbling) or sunken (< 0: pores, dimples); 0: flat. Baked into a normal map.
  double relief_m = 0.0;
  FileLoc loc;
};

/// The bent axis of a template (doc/template-format.md, `spine`): the curve in the profile
/// plane (z = 0) that the straight +Y axis is bent onto after sweeping. Empty: a straight axis.
struct SpineSpec {
  /// [x, y] points in metres, bottom to top; the smooth spline through them is the axis
  std::vector<glm::dvec2> points;
  FileLoc loc;  ///< where `spine` is written
};

/// The organic deformation a template's variants get (doc/template-format.md, `variation`:
/// lumps, lopsided, lean; variation/organic_deformation.h): the largest values a variant draws
/// at variation amount 1. All zero: variants are pure sweeps.
struct OrganicSpec {
  double lump_amplitude_m = 0.0;  ///< the lumps' largest displacement, metres (0: no lumps)
  double lump_size_m = 0.0;       ///< their wavelength, metres (> 0 where there are lumps)
  double lopsided = 0.0;          ///< one side fuller by up to this fraction, 0..0.5
  double lean_rad = 0.0;          ///< the axis leans by up to this angle, radians, 0..30 degrees
  FileLoc loc;                    ///< where `variation` is written

  /// True when any part is asked for.
  bool any() const { return lump_amplitude_m > 0 || lopsided > 0 || lean_rad > 0; }
};

/// A whole parsed, validated template.
struct Template {
  std::string name;
  std::string description;
  std::string file;  ///< path it was read from
  /// fnv1a64 of the file's bytes followed by each mesh surface's data (template_source_hash):
  /// what cut cache keys and batch fingerprints name the template by.
  uint64_t source_hash = 0;
  double metres_per_unit = 1e-3;
  Symmetry symmetry = Symmetry::Cylindrical;
  int folds = 1;                    ///< N of an N-fold template; 1 otherwise
  std::vector<double> fold_angles;  ///< radians, increasing, one per fold (nfold)
  double edge_m = 0.0;              ///< target edge length of the surface meshes, metres
  FileLoc edge_loc;                 ///< where `resolution.edge` is (the file start if absent)
  double variation_amount = 1.0;
  int variation_folds_min = 1, variation_folds_max = 1;
  /// `variation.fold_widths` (nfold, 0..0.5): each variant's folds are drawn this much wider
  /// or narrower than the mean, times the amount (variation.h, draw_fold_angles); 0: even.
  double variation_fold_widths = 0.0;
  /// The range variants draw their ripeness from (`variation.ripeness`, 0 <= x <= y <= 1), and
  /// the ripeness this template's colours are taken at (gradients `along: ripeness`): the
  /// range's middle as parsed; a variant's own draw (variation.h, draw_ripeness).
  glm::dvec2 ripeness_range{0.0, 1.0};
  double ripeness = 0.5;
  OrganicSpec organic;  ///< lumps, lopsidedness and lean of the variants
  std::vector<SurfaceSpec> surfaces;
  std::vector<GrainSpec> grains;
  SpineSpec spine;  ///< the bent axis; no points: straight
  /// `halves: across`: a halves cut runs across the axis at mid-height (citrus, persimmon: the
  /// cut that shows their segments or star) instead of along it.
  bool halves_across = false;
  /// The skin's pattern layers, in the order they are laid (the skin surface's `patterns`).
  std::vector<SkinPatternLayer> skin_patterns;
  int skin = -1;    ///< index of the surface with role skin (-1: none, only
                    ///< for symmetry none)
  NprSettings npr;  ///< NPR parameters (doc/template-format.md, NPR)
  /// Materials (README, Templates: `materials`): the skin's outside (and the walls of
  /// hollows), and the cut faces. Absent: PbrMaterial{} for both, the look of templates
  /// written before them.
  PbrMaterial skin_material, cut_material;
  /// Mass per volume of the object (kg/m^3; `density`, default that of water), for settling
  /// its pieces in scenes (physics_settle.h).
  double density_kg_m3 = 1000;
};

}  // namespace cutaway
