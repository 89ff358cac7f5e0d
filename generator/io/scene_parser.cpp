#include "io/scene_parser.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>
#include <vector>

#include "base/colour.h"
#include "base/error.h"
#include "io/template_parser.h"
#include "io/text_rules.h"
#include "io/yaml_reader.h"

#ifndef CUTAWAY_TEMPLATES_DIR
#define CUTAWAY_TEMPLATES_DIR "templates"
#endif

namespace cutaway {

namespace {

namespace fs = std::filesystem;

/// The largest length or coordinate a scene may use, metres: far beyond any table top.
constexpr double kMaxSceneMetres = 1000;

/// A number in scene units, |value| <= 1 km once in metres. Returns metres.
double parse_coordinate(const YamlField& f, double metres_per_unit) {
  const double m = f.number() * metres_per_unit;
  if (std::fabs(m) > kMaxSceneMetres) f.fail("must be at most 1 km in size (|value| <= 1000 m)");
  return m;
}

/// A positive LENGTH in scene units. Returns metres.
double parse_positive_length(const YamlField& f, double metres_per_unit) {
  const double m = parse_coordinate(f, metres_per_unit);
  if (!(m > 0)) f.fail("must be positive");
  return m;
}

/// A point [x, y, z] in scene units. Returns metres.
glm::dvec3 parse_point(const YamlField& f, double metres_per_unit) {
  if (!f.is_sequence() || f.size() != 3) f.fail("a point must be [x, y, z]");
  glm::dvec3 p;
  for (int k = 0; k < 3; ++k) p[k] = parse_coordinate(f[k], metres_per_unit);
  return p;
}

/// "#rrggbb" (a default colour) to linear RGB.
glm::dvec3 hex_colour(const char* hex) {
  glm::dvec3 c;
  for (int k = 0; k < 3; ++k) {
    c[k] = std::stoi(std::string(hex + 1 + 2 * k, 2), nullptr, 16) / 255.0;
  }
  return srgb_to_linear(c);
}

/// An integer in [lo, hi] ("must be a whole number from LO to HI").
int parse_int_in(const YamlField& f, int lo, int hi) {
  const int64_t v = f.integer();
  if (v < lo || v > hi) {
    f.fail("must be a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) +
           ", not " + std::to_string(v));
  }
  return static_cast<int>(v);
}

Container parse_container(const YamlField& f, double m) {
  Container c;
  const YamlField type = f.require("type");
  const std::string t = type.string();
  std::vector<std::string_view> own;  // the fields of this type besides `type`
  if (t == "bowl" || t == "plate") {
    const bool bowl = t == "bowl";
    c.type = bowl ? ContainerType::Bowl : ContainerType::Plate;
    c.diameter_m = bowl ? 0.240 : 0.260;
    c.height_m = bowl ? 0.080 : 0.020;
    c.colour = hex_colour(bowl ? "#f3efe6" : "#fafafa");
    own = {"diameter", "height", "color"};
  } else if (t == "board") {
    c.type = ContainerType::Board;
    c.width_m = 0.360;
    c.depth_m = 0.240;
    c.height_m = 0.020;
    c.colour = hex_colour("#c49a6c");
    own = {"width", "depth", "height", "color"};
  } else if (t != "none") {
    type.fail("must be bowl, plate, board or none, not " + quoted(t));
  }
  // A field of another container type gets a message that says so, before unknown fields.
  for (const char* key : {"diameter", "width", "depth", "height", "color"}) {
    if (auto x = f.get(key); x && std::find(own.begin(), own.end(), key) == own.end()) {
      x->fail("a " + quoted(t) + " container has no " + key);
    }
  }
  if (c.type == ContainerType::Board) f.allow_only({"type", "width", "depth", "height", "color"});
  else if (c.type == ContainerType::None) f.allow_only({"type"});
  else f.allow_only({"type", "diameter", "height", "color"});
  if (auto x = f.get("diameter")) c.diameter_m = parse_positive_length(*x, m);
  if (auto x = f.get("width")) c.width_m = parse_positive_length(*x, m);
  if (auto x = f.get("depth")) c.depth_m = parse_positive_length(*x, m);
  if (auto x = f.get("height")) c.height_m = parse_positive_length(*x, m);
  if (auto x = f.get("color")) c.colour = parse_colour(*x);
  return c;
}

/// The cut's length field (slices.thickness, dice.size) for later checks, if any.
CutSpec parse_cut(const YamlField& f, double m, std::optional<YamlField>& length_field) {
  CutSpec cut;
  const YamlField type = f.require("type");
  const std::string t = type.string();
  const char* own = nullptr;  // the one field besides `type`
  if (t == "whole") cut.type = CutType::Whole;
  else if (t == "halves") cut.type = CutType::Halves;
  else if (t == "slices") cut.type = CutType::Slices, own = "thickness";
  else if (t == "wedges") cut.type = CutType::Wedges, own = "count";
  else if (t == "dice") cut.type = CutType::Dice, own = "size";
  else
    type.fail("must be whole, halves, slices, wedges or dice, not " + quoted(t));
  for (const char* key : {"thickness", "count", "size"}) {
    if (auto x = f.get(key); x && (!own || std::string_view(own) != key)) {
      x->fail("a " + quoted(t) + " cut has no " + key);
    }
  }
  if (own) {
    f.allow_only({"type", own});
  } else {
    f.allow_only({"type"});
  }
  if (!own) return cut;
  const YamlField value = f.require(own);
  if (cut.type == CutType::Wedges) {
    cut.count = parse_int_in(value, 2, 64);
    return cut;
  }
  const double len = parse_positive_length(value, m);
  if (len < kMinCutLength_m * (1 - 1e-9)) value.fail("must be at least 0.5 mm");
  (cut.type == CutType::Slices ? cut.thickness_m : cut.size_m) = len;
  length_field = value;
  return cut;
}

/// The template file an item's `template` value names (see parse_scene).
std::string resolve_template(const YamlField& f, const fs::path& scene_dir) {
  const std::string v = f.string();
  if (v.empty()) f.fail("must not be empty (a template name or a path ending in .yaml)");
  std::error_code ec;
  const bool is_path = v.find('/') != std::string::npos ||
                       (v.size() >= 5 && v.compare(v.size() - 5, 5, ".yaml") == 0);
  if (is_path) {
    const fs::path p = fs::path(v).is_absolute() ? fs::path(v) : (scene_dir / v).lexically_normal();
    if (!fs::is_regular_file(p, ec)) {
      f.fail("the template file " + quoted(p.string(), 4096) +
             " does not exist (a path is relative to the "
             "scene's folder)");
    }
    return p.string();
  }
  if (const std::string rule = name_rule(v); !rule.empty()) {
    f.fail("a template is a name or a path ending in .yaml; " + rule);
  }
  std::vector<fs::path> dirs{(scene_dir / ".." / "templates").lexically_normal()};
  if (const char* env = std::getenv("CUTAWAY_TEMPLATES"); env && *env) dirs.emplace_back(env);
  dirs.emplace_back(CUTAWAY_TEMPLATES_DIR);
  std::string looked;
  for (const auto& d : dirs) {
    const fs::path p = d / (v + ".yaml");
    if (fs::is_regular_file(p, ec)) return p.string();
    looked += (looked.empty() ? "" : ", ") + quoted(d.string(), 4096);  // paths whole (PATH_MAX)
  }
  f.fail("no template named " + quoted(v) + " (looked for " + v + ".yaml in " + looked + ")");
}

/// `arrange`: pile, fan or scatter.
Arrangement parse_arrangement(const YamlField& f) {
  const std::string v = f.string();
  if (v == "pile") return Arrangement::Pile;
  if (v == "fan") return Arrangement::Fan;
  if (v == "scatter") return Arrangement::Scatter;
  f.fail("must be pile, fan or scatter, not " + quoted(v));
}

/// Reads every item's template once; refuses cuts that make too many pieces.
class TemplateCheck {
 public:
  void check(const SceneItem& item, const std::optional<YamlField>& length_field) {
    auto it = extents_.find(item.template_path);
    if (it == extents_.end()) {
      const Template t = load_template(item.template_path);
      it = extents_.emplace(item.template_path, Entry{t.name, template_extents(t)}).first;
    }
    const long long n = estimate_piece_count(item.cut, it->second.extents);
    if (n > kMaxPiecesPerCut && length_field) {
      std::ostringstream s;
      s << "too small: would make " << n << " pieces of template " << quoted(it->second.name)
        << " (at most " << kMaxPiecesPerCut << " per object)";
      length_field->fail(s.str());
    }
  }

 private:
  struct Entry {
    std::string name;
    ObjectExtents extents;
  };
  std::map<std::string, Entry> extents_;
};

Scene parse(std::string_view text, const std::string& file, bool load_templates) {
  const YamlField root = parse_yaml(text, file);
  Scene s;
  s.file = file;

  const YamlField format = root.require("format");
  if (format.string() != "cutaway-scene/1") {
    format.fail("unsupported format " + quoted(format.string()) +
                " (this version of cutaway reads cutaway-scene/1)");
  }
  root.allow_only(
      {"format", "name", "seed", "units", "container", "arrange", "items", "camera", "render"});

  const YamlField name = root.require("name");
  s.name = name.string();
  if (const std::string rule = name_rule(s.name); !rule.empty()) name.fail(rule);
  if (auto seed = root.get("seed")) {
    const int64_t v = seed->integer();
    if (v < 0) seed->fail("must not be negative");
    s.seed = static_cast<uint64_t>(v);
  }
  if (auto u = root.get("units")) {
    const std::string v = u->string();
    if (v == "mm") s.metres_per_unit = 1e-3;
    else if (v == "cm") s.metres_per_unit = 1e-2;
    else if (v == "m") s.metres_per_unit = 1.0;
    else
      u->fail("must be mm, cm or m, not " + quoted(v));
  }
  const double m = s.metres_per_unit;

  if (auto c = root.get("container")) s.container = parse_container(*c, m);
  Arrangement arrange = s.container.type == ContainerType::Board ||
                                s.container.type == ContainerType::None
                            ? Arrangement::Scatter
                            : Arrangement::Pile;
  if (auto a = root.get("arrange")) arrange = parse_arrangement(*a);

  fs::path scene_dir = fs::path(file).parent_path();
  if (scene_dir.empty()) scene_dir = ".";
  TemplateCheck templates;
  const YamlField items = root.require("items");
  if (items.size() == 0) items.fail("a scene needs at least one item");
  for (size_t i = 0; i < items.size(); ++i) {
    const YamlField f = items[i];
    f.allow_only({"template", "count", "cut", "keep", "variation", "arrange"});
    SceneItem item;
    item.loc = f.loc();
    item.path = f.path();
    const YamlField tmpl = f.require("template");
    item.template_name = tmpl.string();
    item.template_path = resolve_template(tmpl, scene_dir);
    if (auto x = f.get("count")) item.count = parse_int_in(*x, 1, 64);
    std::optional<YamlField> length_field;
    if (auto x = f.get("cut")) item.cut = parse_cut(*x, m, length_field);
    if (auto x = f.get("keep")) {
      item.keep = x->number();
      if (!(item.keep > 0 && item.keep <= 1)) {
        x->fail("must be more than 0 and at most 1 (the fraction of the pieces placed)");
      }
    }
    if (auto x = f.get("variation")) item.variation = x->number_in(0, 10);
    item.arrange = arrange;
    if (auto x = f.get("arrange")) item.arrange = parse_arrangement(*x);
    if (load_templates) templates.check(item, length_field);
    s.items.push_back(std::move(item));
  }

  if (auto c = root.get("camera")) {
    c->allow_only({"eye", "target", "fov"});
    SceneCamera cam;
    cam.eye = parse_point(c->require("eye"), m);
    const YamlField target = c->require("target");
    cam.target = parse_point(target, m);
    if (cam.eye == cam.target) target.fail("the camera's target must differ from its eye");
    if (auto x = c->get("fov")) cam.fov_deg = x->number_in(1, 170);
    s.camera = cam;
  }

  if (auto r = root.get("render")) {
    r->allow_only({"width", "height", "perlin", "silhouettes", "texels_per_mm"});
    if (auto x = r->get("width")) s.render.width = parse_int_in(*x, 16, 8192);
    if (auto x = r->get("height")) s.render.height = parse_int_in(*x, 16, 8192);
    if (auto x = r->get("perlin")) s.render.perlin = x->number_in(0, 10);
    if (auto x = r->get("silhouettes")) s.render.silhouettes = x->number_in(0, 10);
    if (auto x = r->get("texels_per_mm")) s.render.texels_per_mm = x->number_in(0.1, 100);
  }
  return s;
}

}  // namespace

Scene parse_scene(std::string_view text, const std::string& file) {
  return parse(text, file, false);
}

Scene load_scene(const std::string& path) { return parse(read_input_file(path), path, true); }

}  // namespace cutaway
