#include "io/template_parser.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <set>
#include <sstream>

#include <glm/geometric.hpp>

#include "base/byte_stream.h"
#include "base/colour.h"
#include "base/constants.h"
#include "base/error.h"
#include "base/hash.h"
#include "io/format_fields.h"
#include "io/mesh_file.h"
#include "io/text_rules.h"
#include "io/yaml_reader.h"
#include "model/mesh_surface.h"
#include "model/subsurface_scatter.h"
#include "model/template_checks.h"
#include "variation/organic_deformation.h"

namespace cutaway {

namespace {

constexpr double kDeg = kPi / 180.0;
/// The largest coordinate or length a template may use, metres: far beyond any object cutaway
/// models, and small enough that differences and squares of lengths stay finite.
constexpr double kMaxMetres = 1e6;
/// The most edges the skin's height may span (resolution.edge >= height / this): keeps the
/// surface meshes within memory (the default is 64).
constexpr double kMaxEdgesPerHeight = 4096;
/// The fewest edges the skin's height must span (resolution.edge <= height / this): coarser
/// meshes no longer follow the curves well enough for the cut's caps and walls to meet.
constexpr double kMinEdgesPerHeight = 8;
/// The largest skin relief either way, metres: relief is the skin's surface texture (pores,
/// netting), shown by shading, not a change of its shape.
constexpr double kMaxReliefM = 2e-3;

/// `v` (in units of `scale` metres) when |v * scale| <= kMaxMetres; fails at `f` otherwise.
double within_limit(const YamlField& f, double v, double scale) {
  if (std::fabs(v * scale) > kMaxMetres)
    f.fail("must be at most 1000 km in size (|value| <= 1e6 m)");
  return v;
}

/// A LENGTH: a number >= 0 in template units. Returns metres.
double parse_length(const YamlField& f, double metres_per_unit) {
  const double v = within_limit(f, f.number(), metres_per_unit);
  if (v < 0) f.fail("must not be negative");
  return v * metres_per_unit;
}

/// COLOR or GRADIENT / LENGTH or GRADIENT (doc/template-format.md, GRADIENT). Along the
/// ripeness each stop's value is itself a value or a gradient along the profile or the section.
template <class T, class ParseValue>
Gradient<T> parse_gradient(const YamlField& f, ParseValue parse_value,
                           bool ripeness_allowed = true) {
  if (!f.is_map()) return Gradient<T>::constant(parse_value(f));
  f.allow_only({"along", "stops"});
  Gradient<T> g;
  const YamlField along = f.require("along");
  const std::string a = along.string();
  if (a == "profile") g.along = GradientAxis::Profile;
  else if (a == "section") g.along = GradientAxis::Section;
  else if (a == "ripeness" && ripeness_allowed) g.along = GradientAxis::Ripeness;
  else if (a == "ripeness")
    along.fail("a stop of a gradient along ripeness may run along the profile or the section, "
               "not along ripeness again");
  else along.fail("must be 'profile', 'section' or 'ripeness', not " + quoted(a));
  const YamlField stops = f.require("stops");
  if (stops.size() < 1) stops.fail("a gradient needs at least one stop [t, value]");
  double last = -1;
  for (size_t i = 0; i < stops.size(); ++i) {
    const YamlField stop = stops[i];
    if (!stop.is_sequence() || stop.size() != 2) stop.fail("a stop must be [t, value]");
    const double t = stop[0].number_in(0.0, 1.0);
    if (t <= last) stop[0].fail("stops must be in increasing t");
    last = t;
    if (g.along == GradientAxis::Ripeness) {
      Gradient<T> field = parse_gradient<T>(stop[1], parse_value, false);
      g.by_ripeness.emplace_back(t, CurveGradient<T>{field.along, std::move(field.stops)});
    } else g.stops.emplace_back(t, parse_value(stop[1]));
  }
  return g;
}

/// A point [a, b]; each coordinate within kMaxMetres once multiplied by `scale`.
glm::dvec2 parse_pair(const YamlField& f, const char* what, double scale) {
  if (!f.is_sequence() || f.size() != 2) f.fail(std::string("a point must be ") + what);
  return {within_limit(f[0], f[0].number(), scale), within_limit(f[1], f[1].number(), scale)};
}

/// A list of [a, b] points, scaled by `scale` (1: checked against kMaxMetres as metres).
std::vector<glm::dvec2> parse_points(const YamlField& f, double scale, const char* what) {
  if (!f.is_sequence()) f.fail(std::string("must be a list of points ") + what);
  std::vector<glm::dvec2> pts;
  for (size_t i = 0; i < f.size(); ++i) pts.push_back(parse_pair(f[i], what, scale) * scale);
  if (pts.size() < 3) f.fail("a curve needs at least 3 points, not " + std::to_string(pts.size()));
  return pts;
}

/// One loop: [[x, z], ...] or {polar: [[deg, radius], ...]}; returns [x, z] in metres.
std::vector<glm::dvec2> parse_loop(const YamlField& f, double m) {
  if (f.is_map()) {
    f.allow_only({"polar"});
    const YamlField polar = f.require("polar");
    std::vector<glm::dvec2> pts = parse_points(polar, 1.0, "[deg, radius]");
    for (size_t i = 0; i < pts.size(); ++i) {
      if (pts[i].y <= 0) polar[i][1].fail("a polar radius must be positive");
      within_limit(polar[i][1], pts[i].y, m);
      const double a = pts[i].x * kDeg, r = pts[i].y * m;
      pts[i] = {r * std::cos(a), -r * std::sin(a)};  // angle from +X towards -Z
    }
    return pts;
  }
  return parse_points(f, m, "[x, z]");
}

bool looks_like_loop_list(const YamlField& f) {
  // A list of loops: its first element is itself a loop (a list of points or {polar: ...}).
  if (!f.is_sequence() || f.size() == 0) return false;
  const YamlField first = f[0];
  if (first.is_map()) return true;
  return first.is_sequence() && first.size() > 0 && !first[0].is_scalar();
}

SectionSpec parse_section(const YamlField& f, double m) {
  SectionSpec s;
  s.loc = f.loc();
  if (f.is_scalar()) {
    if (f.string() != "circle") {
      f.fail("must be 'circle', a loop [[x, z], ...], {polar: [[deg, radius], ...]} or a list "
             "of loops, not " +
             quoted(f.string()));
    }
    s.circle = true;
    return s;
  }
  if (looks_like_loop_list(f)) {
    for (size_t i = 0; i < f.size(); ++i) s.loops.push_back(parse_loop(f[i], m));
  } else {
    s.loops.push_back(parse_loop(f, m));
  }
  return s;
}

/// The material channels of a surface's or grain's two sides (doc/template-format.md,
/// Materials: `roughness`, `translucency`): each field is a number in 0..1 for both sides or
/// {front: x, back: y} (either may be left out); what is not written takes the cut material's
/// value.
void parse_material_channels(const YamlField& f, const PbrMaterial& cut, glm::dvec2& front,
                             glm::dvec2& back) {
  front = back = {cut.roughness, cut.translucency};
  auto channel = [&](const char* key, int k) {
    const auto x = f.get(key);
    if (!x) return;
    if (!x->is_map()) {
      front[k] = back[k] = x->number_in(0, 1);
      return;
    }
    x->allow_only({"front", "back"});
    if (auto v = x->get("front")) front[k] = v->number_in(0, 1);
    if (auto v = x->get("back")) back[k] = v->number_in(0, 1);
  };
  channel("roughness", 0);
  channel("translucency", 1);
}

SurfaceSpec parse_surface(const YamlField& f, const Template& t, const std::string& base_dir) {
  f.allow_only({"name", "kind",   "role",      "profile",      "section", "smooth",  "front",
                "back", "blur",   "roughness", "translucency", "visible", "rigid",   "offset",
                "tilt", "wander", "sections",  "span",         "file",    "patterns"});
  SurfaceSpec s;
  s.path = f.path();
  s.loc = f.loc();
  const YamlField name = f.require("name");
  s.name = name.string();
  if (s.name.empty()) name.fail("must not be empty");

  const YamlField kind = f.require("kind");
  const std::string k = kind.string();
  if (k == "around") s.kind = SurfaceKind::Around;
  else if (k == "within") s.kind = SurfaceKind::Within;
  else if (k == "mesh") s.kind = SurfaceKind::Mesh;
  else kind.fail("must be 'around', 'within' or 'mesh', not " + quoted(k));

  if (t.symmetry == Symmetry::Cylindrical && s.kind != SurfaceKind::Around) {
    kind.fail("a cylindrical template has only 'around' surfaces (" + quoted(k) +
              " needs symmetry nfold" + (s.kind == SurfaceKind::Mesh ? " or none)" : ")"));
  }
  if (t.symmetry == Symmetry::None && s.kind != SurfaceKind::Mesh) {
    kind.fail("a template with symmetry none has only 'mesh' surfaces");
  }

  if (auto role = f.get("role")) {
    if (role->string() != "skin") role->fail("the only role is 'skin' (or leave it out)");
    s.is_skin = true;
  }

  const double m = t.metres_per_unit;
  if (s.kind == SurfaceKind::Mesh) {
    for (const char* key : {"profile", "section", "sections", "smooth"}) {
      if (auto x = f.get(key)) x->fail(std::string("a 'mesh' surface has no ") + key);
    }
    const YamlField file = f.require("file");
    s.mesh_loc = file.loc();
    const std::filesystem::path p(file.string());
    s.mesh_file = (p.is_absolute() ? p : std::filesystem::path(base_dir) / p).string();
  } else {
    if (auto x = f.get("file")) x->fail("only a 'mesh' surface has a file");
    const YamlField profile = f.require("profile");
    s.profile_loc = profile.loc();
    s.profile = parse_points(profile, m, "[r, y]");
    for (size_t i = 0; i < s.profile.size(); ++i) {
      const double r = s.profile[i].x;
      if (s.kind == SurfaceKind::Around) {
        if (r < 0) profile[i][0].fail("r must be >= 0 (the profile lies right of the axis)");
        if (r == 0 && i > 0 && i + 1 < s.profile.size()) {
          profile[i][0].fail("only the end points of an 'around' profile may lie on the axis");
        }
      } else if (r <= 0) {
        profile[i][0].fail("a 'within' profile must stay off the axis (r > 0)");
      }
    }
    if (s.kind == SurfaceKind::Within) {
      if (glm::distance(s.profile.front(), s.profile.back()) < 1e-12) s.profile.pop_back();
    } else if (s.profile.back().y <= s.profile.front().y) {
      profile.fail("an 'around' profile is ordered bottom to top (its last point must be higher "
                   "than its first)");
    }
    // The rules one section of this surface follows (its loops; the geometry is checked by
    // check_template_curves).
    auto check_section_loops = [&](const YamlField& field, const SectionSpec& section) {
      if (s.kind == SurfaceKind::Around && section.loops.size() > 1)
        field.fail("an 'around' section is 'circle' or one loop around the axis");
      if (s.kind == SurfaceKind::Within) {
        if (section.circle) field.fail("a 'within' section is a loop inside fold 0, or N loops");
        if (section.loops.size() != 1 && static_cast<int>(section.loops.size()) != t.folds) {
          field.fail("a 'within' section is one loop or exactly " + std::to_string(t.folds) +
                     " loops (one per fold), not " + std::to_string(section.loops.size()));
        }
      }
    };
    if (auto sections = f.get("sections")) {
      if (f.get("section")) sections->fail("give 'section' or 'sections', not both");
      if (!sections->is_sequence() || sections->size() < 2)
        sections->fail("'sections' lists at least two {at, section}, from the lowest height up");
      for (size_t i = 0; i < sections->size(); ++i) {
        const YamlField e = (*sections)[i];
        e.allow_only({"at", "section"});
        const YamlField at = e.require("at");
        HeightSection h{at.number_in(0, 1), parse_section(e.require("section"), m)};
        if (!s.sections.empty() && !(h.at > s.sections.back().at))
          at.fail("the heights 'at' must increase from one section to the next");
        check_section_loops(e.require("section"), h.section);
        s.sections.push_back(std::move(h));
      }
      s.section = s.sections.front().section;
    } else if (auto section = f.get("section")) {
      s.section = parse_section(*section, m);
      check_section_loops(*section, s.section);
    } else if (s.kind == SurfaceKind::Around) {
      s.section.circle = true;
      s.section.loc = f.loc();
    } else {
      f.fail("missing required field 'section' (a 'within' surface needs its loop)");
    }
    if (auto smooth = f.get("smooth")) s.smooth = smooth->boolean();
  }

  auto colour = [](const YamlField& x) { return parse_colour(x); };
  if (auto x = f.get("front")) s.front = parse_gradient<glm::dvec3>(*x, colour);
  if (auto x = f.get("back")) s.back = parse_gradient<glm::dvec3>(*x, colour);
  if (auto x = f.get("blur")) {
    s.blur = parse_gradient<double>(*x, [m](const YamlField& v) { return parse_length(v, m); });
  }
  parse_material_channels(f, t.cut_material, s.material_front, s.material_back);
  if (auto vis = f.get("visible")) {
    vis->allow_only({"front", "back"});
    if (auto x = vis->get("front")) s.visible_front = x->boolean();
    if (auto x = vis->get("back")) s.visible_back = x->boolean();
  }
  if (auto x = f.get("span")) {
    if (s.kind != SurfaceKind::Around)
      x->fail("only an 'around' surface covers part of the way round");
    if (s.is_skin) x->fail("the skin is closed: it goes all the way round");
    if (!x->is_sequence() || x->size() != 2)
      x->fail("a span is [from, to] in degrees, counter-clockwise seen from above");
    s.span_rad = {(*x)[0].number_in(-360, 360) * kDeg, (*x)[1].number_in(-360, 720) * kDeg};
    const double turn = s.span_rad.y - s.span_rad.x;
    if (!(turn > 0) || !(turn < 2 * kPi - 1e-9))
      x->fail("'to' must lie above 'from' by less than a whole turn (360 degrees); leave "
              "'span' out for a surface all the way round");
  }
  if (auto x = f.get("tilt")) {
    if (s.is_skin) x->fail("the skin is the object's frame: tilt the surfaces inside it");
    if (!x->is_sequence() || x->size() != 2)
      x->fail("a tilt is [about x, about z] in degrees, each in -90..90");
    s.tilt_rad = {(*x)[0].number_in(-90, 90) * kDeg, (*x)[1].number_in(-90, 90) * kDeg};
  }
  if (auto x = f.get("offset")) {
    if (s.is_skin) x->fail("the skin is the object's frame: offset the surfaces inside it");
    if (!x->is_sequence() || x->size() != 3) x->fail("an offset is [x, y, z] in template units");
    for (int k = 0; k < 3; ++k) s.offset_m[k] = within_limit((*x)[k], (*x)[k].number(), m) * m;
  }
  if (auto x = f.get("wander")) {
    if (s.is_skin) x->fail("the skin is the object's frame: let the surfaces inside it wander");
    s.wander_m = parse_length(*x, m);
  }
  if (auto x = f.get("rigid")) {
    s.rigid = x->boolean();
    if (s.rigid && s.is_skin) x->fail("the skin cannot be rigid (a rigid surface lies inside it)");
    if (s.rigid && s.span_rad.y > s.span_rad.x)
      x->fail("a rigid surface is closed: it cannot cover only a 'span'");
    if (s.rigid && (!s.visible_front || !s.visible_back)) {
      x->fail("a rigid surface is solid inside and has flesh outside: neither side may be hollow "
              "('visible')");
    }
  }
  return s;
}

glm::dvec2 parse_range(const YamlField& f) {
  if (!f.is_sequence() || f.size() != 2) f.fail("a range must be [from, to] in 0..1");
  const glm::dvec2 r{f[0].number_in(0, 1), f[1].number_in(0, 1)};
  if (r.x >= r.y) f.fail("a range [from, to] needs from < to");
  return r;
}

GrainSpec parse_grain(const YamlField& f, const Template& t) {
  f.allow_only({"name", "on", "inside", "outside", "region", "spacing", "side", "depth", "shape",
                "front", "back", "blur", "roughness", "translucency", "jitter", "core"});
  GrainSpec g;
  g.path = f.path();
  g.loc = f.loc();
  const double m = t.metres_per_unit;
  g.name = f.require("name").string();
  const auto surface_named = [&](const YamlField& field) {
    const std::string name = field.string();
    bool found = false;
    for (const auto& s : t.surfaces) found = found || s.name == name;
    if (!found) field.fail("no surface is named " + quoted(name));
    return name;
  };
  if (auto inside = f.get("inside")) {  // grains through a region
    if (auto on = f.get("on"))
      on->fail("a grain set lies either on a surface or inside one, not both");
    g.inside = surface_named(*inside);
    if (auto outside = f.get("outside")) {
      g.outside = surface_named(*outside);
      if (g.outside == g.inside) outside->fail("must name another surface than `inside`");
    }
    for (const char* key : {"region", "side", "depth"})
      if (auto x = f.get(key)) x->fail("only grains `on` a surface have a " + std::string(key));
  } else {
    if (auto outside = f.get("outside")) outside->fail("an outside needs an inside");
    g.on = surface_named(f.require("on"));
  }
  if (auto region = f.get("region")) {
    region->allow_only({"profile", "section"});
    if (auto x = region->get("profile")) g.region_profile = parse_range(*x);
    if (auto x = region->get("section")) g.region_section = parse_range(*x);
  }
  const YamlField spacing = f.require("spacing");
  g.spacing = parse_length(spacing, m);
  g.spacing_loc = spacing.loc();
  if (g.spacing <= 0) spacing.fail("the Poisson-disc spacing must be positive");
  if (auto side = f.get("side")) {
    const std::string v = side->string();
    if (v != "front" && v != "back") side->fail("must be 'front' or 'back', not " + quoted(v));
    g.on_front = v == "front";
  }
  if (auto x = f.get("depth")) g.depth = parse_length(*x, m);
  const YamlField shape = f.require("shape");
  g.shape_loc = shape.loc();
  shape.allow_only({"ellipsoid"});
  const YamlField ell = shape.require("ellipsoid");
  if (!ell.is_sequence() || ell.size() != 3) ell.fail("must be three semi-axes [a, b, c]");
  for (int k = 0; k < 3; ++k) {
    g.semi_axes[k] = parse_length(ell[k], m);
    if (g.semi_axes[k] <= 0) ell[k].fail("a semi-axis must be positive");
  }
  g.front = parse_colour(f.require("front"));
  g.back = parse_colour(f.require("back"));
  if (auto x = f.get("blur")) g.blur = parse_length(*x, m);
  if (auto x = f.get("jitter")) g.jitter = x->number_in(0, 1);
  parse_material_channels(f, t.cut_material, g.material_front, g.material_back);
  if (auto core = f.get("core")) {
    core->allow_only({"scale", "front", "back", "roughness", "translucency"});
    GrainSpec::Core c;
    const YamlField scale = core->require("scale");
    c.scale = scale.number_in(0, 1);
    if (c.scale <= 0 || c.scale >= 1)
      scale.fail("a core lies inside its grain: the scale must lie strictly between 0 and 1");
    c.front = parse_colour(core->require("front"));
    c.back = parse_colour(core->require("back"));
    parse_material_channels(*core, t.cut_material, c.material_front, c.material_back);
    for (const auto& s : t.surfaces)
      if (s.name == grain_core_name(g))
        core->fail("the cores make a surface named " + quoted(grain_core_name(g)) +
                   ", and a surface has that name");
    g.core = c;
  }
  return g;
}

/// The most Perlin bands a template may have (each costs one noise evaluation per vertex).
constexpr size_t kMaxPerlinBands = 8;

/// The most cell layers a template may have (each costs 27 feature points per texel).
constexpr size_t kMaxCellBands = 4;

/// What Perlin bands and cell layers share (doc/npr.md): the lattice spacing under
/// `length_key` (`period` or `size`, at least 1 micrometre), `amplitude`, `tint`, `reach`,
/// `along` and `stretch`.
void parse_texture_band(const YamlField& band, const std::string& length_key,
                        double metres_per_unit, TextureBand& b) {
  const YamlField length = band.require(length_key);
  const double length_m = parse_length(length, metres_per_unit);
  if (!(length_m >= 1e-6)) length.fail("the " + length_key + " must be at least 1 micrometre");
  b.frequency_per_m = 1.0 / length_m;
  b.amplitude = band.require("amplitude").number_in(0.0, 1.0);
  if (auto tint = band.get("tint")) {
    b.tinted = true;
    b.tint = parse_colour(*tint);
  }
  if (auto reach = band.get("reach")) {
    if (!b.tinted) reach->fail("a reach needs a tint (an untinted band acts on every colour)");
    b.reach = reach->number_in(0.0, 1.75);
    if (b.reach <= 0) reach->fail("must be positive");
  }
  if (auto along = band.get("along")) {
    const std::string a = along->string();
    if (a == "radial") b.along = TextureField::Radial;
    else if (a == "around") b.along = TextureField::Around;
    else if (a == "axial") b.along = TextureField::Axial;
    else if (a != "none") along->fail("must be none, radial, around or axial, not " + quoted(a));
  }
  if (auto stretch = band.get("stretch")) {
    if (b.along == TextureField::None)
      stretch->fail("a stretch needs a field to stretch along (`along`)");
    b.stretch = stretch->number_in(1.0, 64.0);
  }
}

/// `npr` (doc/template-format.md, NPR; doc/npr.md): {perlin: {bands: [{period, amplitude,
/// tint, reach, along, stretch}, ...]}, cells: [{size, amplitude, wall, centre, wall_width,
/// wall_roughness, centre_roughness, tint, reach, along, stretch}, ...]}.
NprSettings parse_npr(const YamlField& f, double metres_per_unit) {
  f.allow_only({"perlin", "cells"});
  NprSettings npr;
  if (const auto perlin = f.get("perlin")) {
    perlin->allow_only({"bands"});
    const YamlField bands = perlin->require("bands");
    if (bands.size() > kMaxPerlinBands) {
      bands.fail("at most " + std::to_string(kMaxPerlinBands) + " bands, not " +
                 std::to_string(bands.size()));
    }
    npr.perlin_from_file = true;
    for (size_t i = 0; i < bands.size(); ++i) {
      const YamlField band = bands[i];
      band.allow_only({"period", "amplitude", "tint", "reach", "along", "stretch"});
      PerlinBand b;
      parse_texture_band(band, "period", metres_per_unit, b);
      npr.perlin_bands.push_back(b);
    }
  }
  if (const auto cells = f.get("cells")) {
    if (cells->size() > kMaxCellBands) {
      cells->fail("at most " + std::to_string(kMaxCellBands) + " layers of cells, not " +
                  std::to_string(cells->size()));
    }
    for (size_t i = 0; i < cells->size(); ++i) {
      const YamlField layer = (*cells)[i];
      layer.allow_only({"size", "amplitude", "wall", "centre", "wall_width", "wall_roughness",
                        "centre_roughness", "tint", "reach", "along", "stretch"});
      CellBand c;
      parse_texture_band(layer, "size", metres_per_unit, c);
      if (auto wall = layer.get("wall")) {
        c.has_wall = true;
        c.wall = parse_colour(*wall);
      }
      if (auto centre = layer.get("centre")) {
        c.has_centre = true;
        c.centre = parse_colour(*centre);
      }
      if (!c.has_wall && !c.has_centre)
        layer.fail("a layer of cells needs a wall or a centre colour");
      if (auto width = layer.get("wall_width")) {
        if (!c.has_wall) width->fail("a wall_width needs a wall colour");
        c.wall_width = width->number_in(0.0, 1.0);
      }
      if (auto roughness = layer.get("wall_roughness")) {
        if (!c.has_wall) roughness->fail("a wall_roughness needs a wall colour");
        c.wall_roughness = roughness->number_in(0.0, 1.0);
      }
      if (auto roughness = layer.get("centre_roughness")) {
        if (!c.has_centre) roughness->fail("a centre_roughness needs a centre colour");
        c.centre_roughness = roughness->number_in(0.0, 1.0);
      }
      npr.cell_bands.push_back(c);
    }
  }
  return npr;
}

/// One material of `materials` (README, Templates): {roughness, translucency, clearcoat,
/// clearcoat_roughness, sheen, sheen_roughness}, each optional (PbrMaterial's defaults), the
/// numbers in 0..1, `sheen` a colour.
PbrMaterial parse_material(const YamlField& f) {
  f.allow_only({"roughness", "translucency", "clearcoat", "clearcoat_roughness", "sheen",
                "sheen_roughness"});
  PbrMaterial m;
  if (auto x = f.get("roughness")) m.roughness = x->number_in(0, 1);
  if (auto x = f.get("translucency")) m.translucency = x->number_in(0, 1);
  if (auto x = f.get("clearcoat")) m.clearcoat = x->number_in(0, 1);
  if (auto x = f.get("clearcoat_roughness")) {
    if (!f.get("clearcoat")) x->fail("a clearcoat_roughness needs a clearcoat");
    m.clearcoat_roughness = x->number_in(0, 1);
  }
  if (auto x = f.get("sheen")) m.sheen = parse_colour(*x);
  if (auto x = f.get("sheen_roughness")) {
    if (!f.get("sheen")) x->fail("a sheen_roughness needs a sheen colour");
    m.sheen_roughness = x->number_in(0, 1);
  }
  return m;
}

/// The bands a template without `npr.perlin` gets (template.h, NprSettings): untinted fine
/// grain and broad mottling, their periods fractions of the skin's height (metres).
std::vector<PerlinBand> default_perlin_bands(double height_m) {
  PerlinBand fine, broad;
  fine.frequency_per_m = 16.0 / height_m;
  fine.amplitude = 0.2;
  broad.frequency_per_m = 5.0 / height_m;
  broad.amplitude = 0.3;
  return {fine, broad};
}

const char* units_name(const Template& t) {
  return t.metres_per_unit == 1.0 ? "m" : (t.metres_per_unit == 1e-2 ? "cm" : "mm");
}

/// fnv1a64 of `text` (the template file) followed by the data of each mesh surface of `t`, as
/// ByteWriter encodes it: the file and the meshes it names, by content.
uint64_t template_source_hash(std::string_view text, const Template& t) {
  ByteWriter w;
  w.put_string(text);
  for (const SurfaceSpec& s : t.surfaces) {
    if (!s.mesh) continue;
    w.put_vector(s.mesh->points);
    w.put_vector(s.mesh->triangles);
    w.put_vector(s.mesh->front);
    w.put_vector(s.mesh->back);
    w.put_vector(s.mesh->blur);
  }
  return fnv1a64(w.bytes());
}

/// Reads the PLY file of a `mesh` surface into it (read_mesh_file), once.
void read_surface_mesh(SurfaceSpec& s) {
  if (s.kind != SurfaceKind::Mesh || s.mesh) return;
  s.mesh =
      std::make_shared<const MeshData>(read_mesh_file(s.mesh_file, s.mesh_loc, s.path + ".file"));
}

/// Skin height (metres) for the default edge length: the y range of the skin's profile or mesh
/// (whose file is read here).
double skin_height(Template& t) {
  SurfaceSpec& skin = t.surfaces[t.skin];
  if (skin.kind == SurfaceKind::Mesh) {
    read_surface_mesh(skin);
    const MeshBounds b = mesh_bounds(*skin.mesh, t.metres_per_unit);
    return b.max.y - b.min.y;
  }
  double lo = skin.profile.front().y, hi = lo;
  for (const auto& p : skin.profile) {
    lo = std::min(lo, p.y);
    hi = std::max(hi, p.y);
  }
  return hi - lo;
}

/// The skin's widest radius from the axis (metres): its profile's largest |x|, or a mesh skin's
/// largest |x| or |z| of its bounds. The reference radius of texture fields around the axis.
double skin_widest_radius(Template& t) {
  SurfaceSpec& skin = t.surfaces[t.skin];
  if (skin.kind == SurfaceKind::Mesh) {
    read_surface_mesh(skin);
    const MeshBounds b = mesh_bounds(*skin.mesh, t.metres_per_unit);
    return std::max(
        {std::fabs(b.min.x), std::fabs(b.max.x), std::fabs(b.min.z), std::fabs(b.max.z)});
  }
  double widest = 0;
  for (const auto& p : skin.profile) widest = std::max(widest, std::fabs(p.x));
  return widest;
}

/// Sets around_cells of every band stretched along a field around the axis (TextureBand): 2 pi R
/// over the band's spacing across the field, R the skin's widest radius, rounded, at least 1;
/// refused at the band's period (size) when it exceeds 256 cells.
void resolve_texture_fields(const YamlField& root, Template& t, double widest_radius_m) {
  const auto resolve = [&](TextureBand& b, const char* list, size_t i, const char* length) {
    if (b.along != TextureField::Radial && b.along != TextureField::Around) return;
    const double across = b.along == TextureField::Around ? b.stretch : 1.0;
    const double cells = std::round(2 * kPi * widest_radius_m * b.frequency_per_m / across);
    if (!(cells <= 256)) {
      const YamlField npr = root.require("npr");
      const YamlField item = std::string(list) == "cells"
                                 ? npr.require("cells")[i]
                                 : npr.require("perlin").require("bands")[i];
      item.require(length).fail(
          "too fine for a field around the axis: " + std::to_string(static_cast<long long>(cells)) +
          " cells round the skin's widest radius, at most 256 (a longer " + length + ")");
    }
    b.around_cells = static_cast<unsigned>(std::max(1.0, cells));
  };
  for (size_t i = 0; i < t.npr.perlin_bands.size(); ++i)
    if (t.npr.perlin_from_file) resolve(t.npr.perlin_bands[i], "bands", i, "period");
  for (size_t i = 0; i < t.npr.cell_bands.size(); ++i)
    resolve(t.npr.cell_bands[i], "cells", i, "size");
}

/// `symmetry`: the type, and for nfold the folds and their angles (radians); the variation's
/// fold range starts at the fold count.
void parse_symmetry(const YamlField& root, Template& t) {
  const YamlField sym = root.require("symmetry");
  sym.allow_only({"type", "folds", "fold_angles"});
  const YamlField type = sym.require("type");
  const std::string ty = type.string();
  if (ty == "cylindrical") t.symmetry = Symmetry::Cylindrical;
  else if (ty == "nfold") t.symmetry = Symmetry::NFold;
  else if (ty == "none") t.symmetry = Symmetry::None;
  else type.fail("must be cylindrical, nfold or none, not " + quoted(ty));
  if (t.symmetry == Symmetry::NFold) {
    const YamlField folds = sym.require("folds");
    const int64_t n = folds.integer();
    if (n < 2) folds.fail("an nfold template needs folds >= 2, not " + std::to_string(n));
    if (n > 64) folds.fail("at most 64 folds");
    t.folds = static_cast<int>(n);
    if (auto fa = sym.get("fold_angles")) {
      if (fa->size() != static_cast<size_t>(t.folds)) {
        fa->fail("needs exactly " + std::to_string(t.folds) + " angles, one per fold");
      }
      for (size_t i = 0; i < fa->size(); ++i) {
        const double a = (*fa)[i].number();
        if (i > 0 && a <= t.fold_angles.back() / kDeg) (*fa)[i].fail("fold angles must increase");
        t.fold_angles.push_back(a * kDeg);
      }
      if (t.fold_angles.back() - t.fold_angles.front() >= 2 * kPi) {
        fa->fail("fold angles must span less than 360 degrees");
      }
    } else {
      for (int k = 0; k < t.folds; ++k) t.fold_angles.push_back(2 * kPi * k / t.folds);
    }
  } else {
    for (const char* key : {"folds", "fold_angles"}) {
      if (auto x = sym.get(key)) x->fail(std::string(key) + " is only for symmetry type nfold");
    }
  }
  t.variation_folds_min = t.variation_folds_max = t.folds;
}

/// `variation`: its amount (>= 0), for nfold the range of fold counts variants draw, and the
/// range of ripeness they draw (the template's own ripeness is its middle).
void parse_variation(const YamlField& root, Template& t) {
  const auto var = root.get("variation");
  if (!var) return;
  var->allow_only({"amount", "folds", "fold_widths", "ripeness", "lumps", "lopsided", "lean"});
  if (auto a = var->get("amount")) {
    t.variation_amount = a->number();
    if (t.variation_amount < 0) a->fail("must not be negative");
  }
  t.organic.loc = var->loc();
  if (auto lumps = var->get("lumps")) {
    lumps->allow_only({"amplitude", "size"});
    t.organic.lump_amplitude_m =
        parse_positive_length(lumps->require("amplitude"), t.metres_per_unit);
    t.organic.lump_size_m = parse_positive_length(lumps->require("size"), t.metres_per_unit);
  }
  if (auto l = var->get("lopsided")) t.organic.lopsided = l->number_in(0.0, 0.5);
  if (auto l = var->get("lean")) t.organic.lean_rad = l->number_in(0.0, 30.0) * kDeg;
  if (const Check c = check_organic(t.organic, t.variation_amount, t.metres_per_unit); !c)
    var->fail(c.reason());
  if (auto vf = var->get("folds")) {
    if (t.symmetry != Symmetry::NFold) vf->fail("variation.folds is only for symmetry nfold");
    if (!vf->is_sequence() || vf->size() != 2) vf->fail("must be [min, max] fold counts");
    const int64_t lo = (*vf)[0].integer(), hi = (*vf)[1].integer();
    if (lo < 2 || hi > 64 || lo > hi) vf->fail("needs 2 <= min <= max <= 64");
    t.variation_folds_min = static_cast<int>(lo);
    t.variation_folds_max = static_cast<int>(hi);
  }
  if (auto fw = var->get("fold_widths")) {
    if (t.symmetry != Symmetry::NFold) fw->fail("variation.fold_widths is only for symmetry nfold");
    t.variation_fold_widths = fw->number_in(0.0, 0.5);
  }
  if (auto vr = var->get("ripeness")) {
    if (!vr->is_sequence() || vr->size() != 2) vr->fail("must be [min, max] ripeness in 0..1");
    const double lo = (*vr)[0].number_in(0.0, 1.0), hi = (*vr)[1].number_in(0.0, 1.0);
    if (lo > hi) vr->fail("needs min <= max");
    t.ripeness_range = {lo, hi};
    t.ripeness = 0.5 * (lo + hi);
  }
}

/// One layer of the skin's `patterns`: {stripes: {...}}, {speckles: {...}}, {net: {...}} or
/// {grains: {...}} (doc/template-format.md, Skin patterns). A grains layer's set is checked
/// once the grains are read (check_grain_layers).
SkinPatternLayer parse_pattern_layer(const YamlField& f, double m) {
  SkinPatternLayer p;
  p.loc = f.loc();
  const char* kinds =
      "a pattern layer is {stripes: {...}}, {speckles: {...}}, {net: {...}} or {grains: {...}}";
  if (!f.is_map()) f.fail(kinds);
  f.allow_only({"stripes", "speckles", "net", "grains"});
  const auto stripes = f.get("stripes"), speckles = f.get("speckles"), net = f.get("net"),
             grains = f.get("grains");
  if (stripes.has_value() + speckles.has_value() + net.has_value() + grains.has_value() != 1)
    f.fail(std::string(kinds) + ": exactly one of them");
  const YamlField b = stripes ? *stripes : speckles ? *speckles : net ? *net : *grains;
  p.kind = stripes    ? SkinPatternLayer::Kind::Stripes
           : speckles ? SkinPatternLayer::Kind::Speckles
           : net      ? SkinPatternLayer::Kind::Net
                      : SkinPatternLayer::Kind::Grains;
  if (grains) {
    b.allow_only({"set", "size", "colour", "opacity", "softness", "relief"});
    p.grain_set = b.require("set").string();
    const YamlField size = b.require("size");
    p.size_m = parse_length(size, m);
    if (p.size_m < 1e-5) size.fail("must be at least 0.01 mm");
  } else if (stripes) {
    b.allow_only({"count", "width", "colour", "opacity", "softness", "wobble", "relief"});
    const int64_t count = b.require("count").integer();
    if (count < 1 || count > 256) b.require("count").fail("must be a whole number 1 to 256");
    p.count = static_cast<int>(count);
    if (auto x = b.get("width")) p.width = x->number_in(0.0, 1.0);
    if (!(p.width > 0 && p.width < 1)) b.require("width").fail("must lie strictly between 0 and 1");
    if (auto x = b.get("wobble")) p.wobble = x->number_in(0.0, 1.0);
  } else {
    // speckles: spot radius `size`; net: line `width`; both at least 0.01 mm
    const char* size_key = speckles ? "size" : "width";
    if (speckles)
      b.allow_only({"spacing", "size", "jitter", "colour", "opacity", "softness", "relief"});
    else b.allow_only({"spacing", "width", "colour", "opacity", "softness", "relief"});
    const YamlField spacing = b.require("spacing"), size = b.require(size_key);
    p.spacing_m = parse_length(spacing, m);
    p.size_m = parse_length(size, m);
    if (p.size_m < 1e-5) size.fail("must be at least 0.01 mm");
    if (auto x = b.get("jitter")) p.jitter = x->number_in(0.0, 1.0);
    if (speckles && p.size_m * (1 + p.jitter) > p.spacing_m)
      spacing.fail("must be at least size x (1 + jitter): a speckle may not reach past the "
                   "cells next to its own");
    if (net && p.size_m > 0.5 * p.spacing_m)
      spacing.fail("must be at least twice the net's width: wider lines would fill the cells");
  }
  if (auto x = b.get("opacity")) p.opacity = x->number_in(0.0, 1.0);
  if (auto x = b.get("softness")) p.softness = x->number_in(0.0, 1.0);
  if (auto x = b.get("relief")) {
    // Signed, unlike a LENGTH: raised or sunken.
    p.relief_m = x->number_in(-kMaxReliefM / m, kMaxReliefM / m) * m;
  }
  if (p.opacity > 0) p.colour = parse_colour(b.require("colour"));
  else if (auto x = b.get("colour")) p.colour = parse_colour(*x);
  else if (p.relief_m == 0)
    b.fail("a layer of opacity 0 without a relief changes nothing: give it a relief, or an "
           "opacity and a colour");
  return p;
}

/// The `set` of each grains layer of the skin's patterns names a grain set scattered over the
/// skin (its spots are where those grains sit).
void check_grain_layers(const Template& t) {
  for (size_t k = 0; k < t.skin_patterns.size(); ++k) {
    const SkinPatternLayer& p = t.skin_patterns[k];
    if (p.kind != SkinPatternLayer::Kind::Grains) continue;
    const SurfaceSpec& skin = t.surfaces[static_cast<size_t>(t.skin)];
    const std::string field = skin.path + ".patterns[" + std::to_string(k) + "].grains.set";
    const auto g = std::find_if(t.grains.begin(), t.grains.end(),
                                [&](const GrainSpec& s) { return s.name == p.grain_set; });
    if (g == t.grains.end())
      throw InputError(p.loc, field, "no grain set is named " + quoted(p.grain_set));
    if (g->on != skin.name)
      throw InputError(p.loc, field,
                       "grain set " + quoted(p.grain_set) + " lies on " + quoted(g->on) +
                           ", not on the skin " + quoted(skin.name) +
                           ": only grains under the skin show on it");
  }
}

/// The skin's `patterns` (a list of layers): only on the skin, and only a swept one (its
/// texture coordinates are the sweep's parameters).
void parse_skin_patterns(const YamlField& f, const SurfaceSpec& s, Template& t) {
  const auto patterns = f.get("patterns");
  if (!patterns) return;
  if (!s.is_skin) patterns->fail("only the skin (role: skin) has patterns");
  if (s.kind != SurfaceKind::Around)
    patterns->fail("patterns need a swept skin (kind: around): they follow its sweep");
  if (!patterns->is_sequence() || patterns->size() < 1 || patterns->size() > 8)
    patterns->fail("must be a list of 1 to 8 pattern layers");
  for (size_t k = 0; k < patterns->size(); ++k)
    t.skin_patterns.push_back(parse_pattern_layer((*patterns)[k], t.metres_per_unit));
}

/// `surfaces`: each surface (parse_surface), names unique, exactly one of role skin.
void parse_surfaces(const YamlField& root, Template& t, const std::string& base_dir) {
  const YamlField surfaces = root.require("surfaces");
  if (surfaces.size() == 0) surfaces.fail("a template needs at least one surface");
  std::set<std::string> names;
  for (size_t i = 0; i < surfaces.size(); ++i) {
    SurfaceSpec s = parse_surface(surfaces[i], t, base_dir);
    parse_skin_patterns(surfaces[i], s, t);
    if (!names.insert(s.name).second) {
      surfaces[i].require("name").fail("surface names must be unique: " + quoted(s.name) +
                                       " is used twice");
    }
    if (s.is_skin) {
      if (t.skin >= 0) {
        surfaces[i].require("role").fail("only one surface may have role skin (" +
                                         quoted(t.surfaces[t.skin].name) + " has it already)");
      }
      t.skin = static_cast<int>(i);
    }
    t.surfaces.push_back(std::move(s));
  }
  if (t.skin < 0) {
    surfaces.fail("no surface has role skin: exactly one surface must be the object's closed "
                  "outer boundary");
  }
}

/// `resolution.edge`, metres (0 when not given), and where it is written.
void parse_edge(const YamlField& root, Template& t) {
  t.edge_loc = FileLoc{t.file, 1, 1};
  if (auto res = root.get("resolution")) {
    res->allow_only({"edge"});
    t.edge_loc = res->loc();
    if (auto e = res->get("edge")) {
      t.edge_loc = e->loc();
      t.edge_m = parse_length(*e, t.metres_per_unit);
      if (t.edge_m <= 0) e->fail("the edge length must be positive");
    }
  }
}

/// The edge length for the skin's height `h` (metres): 1/64 of it when not given, else held
/// between 1/kMaxEdgesPerHeight and 1/kMinEdgesPerHeight of it.
void resolve_edge(const YamlField& root, Template& t, double h) {
  if (!(h > 0)) root.require("surfaces").fail("the skin has no height");
  if (t.edge_m == 0) {
    t.edge_m = h / 64;
  } else if (h / t.edge_m > kMaxEdgesPerHeight) {
    std::ostringstream rule;
    rule << "the edge length must be at least 1/" << kMaxEdgesPerHeight << " of the skin's height ("
         << h / t.metres_per_unit << " " << units_name(t)
         << "): the meshes would not fit in memory";
    throw InputError(t.edge_loc, "resolution.edge", rule.str());
  } else if (h / t.edge_m < kMinEdgesPerHeight) {
    std::ostringstream rule;
    rule << "the edge length must be at most 1/" << kMinEdgesPerHeight << " of the skin's height ("
         << h / t.metres_per_unit << " " << units_name(t)
         << "): coarser meshes do not follow the curves closely enough to cut";
    throw InputError(t.edge_loc, "resolution.edge", rule.str());
  }
}

/// `spine`: a list of [x, y] points in template units (doc/template-format.md, Spine).
SpineSpec parse_spine(const YamlField& f, double m) {
  return {parse_points(f, m, "[x, y]"), f.loc()};
}

}  // namespace

Template parse_template(std::string_view text, const std::string& file,
                        const std::string& base_dir) {
  const YamlField root = parse_yaml(text, file);
  root.allow_only({"format", "name", "description", "units", "symmetry", "resolution", "variation",
                   "surfaces", "grains", "npr", "materials", "density", "spine", "halves"});
  Template t;
  t.file = file;

  require_format(root, "cutaway-template/1");
  t.name = parse_name(root);
  if (auto d = root.get("description")) t.description = d->string();
  if (auto u = root.get("units")) t.metres_per_unit = parse_units(*u);

  parse_symmetry(root, t);
  parse_variation(root, t);

  // Materials first: the cut material is the default of every surface's material channels.
  if (auto d = root.get("density")) t.density_kg_m3 = d->number_in(50, 5000);
  if (auto halves = root.get("halves")) {
    const std::string v = halves->string();
    if (v != "along" && v != "across")
      halves->fail("must be 'along' or 'across', not " + quoted(v));
    t.halves_across = v == "across";
  }
  if (auto materials = root.get("materials")) {
    materials->allow_only({"skin", "cut"});
    if (auto skin = materials->get("skin")) t.skin_material = parse_material(*skin);
    if (auto cut = materials->get("cut")) t.cut_material = parse_material(*cut);
  }

  parse_surfaces(root, t, base_dir);
  if (auto grains = root.get("grains")) {
    for (size_t i = 0; i < grains->size(); ++i) t.grains.push_back(parse_grain((*grains)[i], t));
  }
  check_grain_layers(t);

  if (auto npr = root.get("npr")) t.npr = parse_npr(*npr, t.metres_per_unit);
  if (auto spine = root.get("spine")) {
    t.spine = parse_spine(*spine, t.metres_per_unit);
    // A lean is a shear of the straight axis; slices of a bent object follow the spine.
    if (t.organic.lean_rad > 0)
      root.require("variation")
          .require("lean")
          .fail("a template with a spine cannot lean: the spine already sets where its axis goes");
  }

  parse_edge(root, t);
  check_template_curves(t);
  const double h = skin_height(t);
  resolve_edge(root, t, h);
  if (!t.npr.perlin_from_file) t.npr.perlin_bands = default_perlin_bands(h);
  const double widest = skin_widest_radius(t);
  resolve_texture_fields(root, t, widest);
  // How far light scatters under each material follows its translucency, the skin's smallest
  // extent and the dark grains.
  for (PbrMaterial* m : {&t.skin_material, &t.cut_material})
    m->scatter_m = subsurface_scatter_m(t, m->translucency, std::min(h, 2 * widest));
  for (SurfaceSpec& s : t.surfaces) read_surface_mesh(s);
  t.source_hash = template_source_hash(text, t);
  return t;
}

Template load_template(const std::string& path, std::string* text) {
  const std::filesystem::path p(path);
  const std::string bytes = read_input_file(path);
  if (text) *text = bytes;
  return parse_template(bytes, path, p.has_parent_path() ? p.parent_path().string() : ".");
}

}  // namespace cutaway
