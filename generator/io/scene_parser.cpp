#include "io/scene_parser.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>
#include <vector>

#include "base/colour.h"
#include "base/error.h"
#include "io/format_fields.h"
#include "io/template_parser.h"
#include "io/text_rules.h"
#include "io/yaml_reader.h"
#include "placement/container_mesh.h"
#include "placement/scene_layout.h"

namespace cutaway {

namespace {

namespace fs = std::filesystem;

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

/// `arrange`: pile, fan, scatter or together.
Arrangement parse_arrangement(const YamlField& f) {
  const std::string v = f.string();
  if (v == "pile") return Arrangement::Pile;
  if (v == "fan") return Arrangement::Fan;
  if (v == "scatter") return Arrangement::Scatter;
  if (v == "together") return Arrangement::Together;
  f.fail("must be pile, fan, scatter or together, not " + quoted(v));
}

/// `camera`: eye and target (different points, in the file's units, `metres_per_unit` metres
/// each) and the vertical field of view, 1..170 degrees.
SceneCamera parse_camera(const YamlField& c, double metres_per_unit) {
  c.allow_only({"eye", "target", "fov"});
  SceneCamera cam;
  cam.eye = parse_point(c.require("eye"), metres_per_unit);
  const YamlField target = c.require("target");
  cam.target = parse_point(target, metres_per_unit);
  if (cam.eye == cam.target) target.fail("the camera's target must differ from its eye");
  if (auto x = c.get("fov")) cam.fov_deg = x->number_in(1, 170);
  return cam;
}

/// `render`: the picture's size (at most kMaxRenderPixels), the style, the NPR strengths (the
/// silhouettes' default following the style) and the texel density of the baked cut faces.
RenderSettings parse_render(const YamlField& r) {
  RenderSettings out;
  r.allow_only({"width", "height", "perlin", "style", "silhouettes", "texels_per_mm"});
  if (auto x = r.get("width")) out.width = parse_int_in(*x, 16, 8192);
  if (auto x = r.get("height")) out.height = parse_int_in(*x, 16, 8192);
  if (auto x = r.get("perlin")) out.perlin = x->number_in(0, 10);
  if (auto x = r.get("style")) {
    const std::string style = x->string();
    if (style == "illustration") out.style = RenderStyle::Illustration;
    else if (style != "realistic")
      x->fail("must be realistic or illustration, not " + quoted(style));
  }
  out.silhouettes = default_silhouettes(out.style);
  if (auto x = r.get("silhouettes")) {
    out.silhouettes = x->number_in(0, 10);
    out.silhouettes_given = true;
  }
  if (auto x = r.get("texels_per_mm")) {
    out.texels_per_mm = x->number_in(0.1, 100);
    out.texels_per_mm_given = true;
  }
  if (static_cast<long long>(out.width) * out.height > kMaxRenderPixels)
    r.fail("width x height is " + std::to_string(out.width * out.height) + " pixels (at most " +
           std::to_string(kMaxRenderPixels) + ", e.g. 3840 x 2160)");
  return out;
}

/// `backdrop`: its type (sweep or none; the default follows the scene's `style`) and colour.
Backdrop parse_backdrop(const std::optional<YamlField>& f, RenderStyle style) {
  Backdrop b;
  b.sweep = style == RenderStyle::Realistic;
  if (!f) return b;
  f->allow_only({"type", "color"});
  if (auto x = f->get("type")) {
    const std::string type = x->string();
    if (type != "sweep" && type != "none") x->fail("must be sweep or none, not " + quoted(type));
    b.sweep = type == "sweep";
  }
  if (auto x = f->get("color")) b.colour = parse_colour(*x);
  return b;
}

/// The rule a scene breaks whose pieces, heaped, fill `heap_m3` where the container holds
/// `holds_m3` (heap_capacity), with both volumes in litres.
std::string volume_rule(double heap_m3, double holds_m3, ContainerType type) {
  const char* what = type == ContainerType::Bowl    ? "the bowl"
                     : type == ContainerType::Plate ? "the plate"
                     : type == ContainerType::Board ? "the board"
                                                    : "the floor (no container)";
  char text[300];
  std::snprintf(text, sizeof text,
                "the items up to here make a heap of about %.3g litres (the objects' volume over "
                "%.2f packing) and %s holds about %.3g litres heaped: fewer or smaller objects, "
                "a lower keep, or a larger container",
                1000 * heap_m3, kHeapPacking, what, 1000 * holds_m3);
  return text;
}

Scene parse(std::string_view text, const std::string& file, bool load_templates) {
  const YamlField root = parse_yaml(text, file);
  Scene s;
  s.file = file;

  require_format(root, "cutaway-scene/1");
  root.allow_only({"format", "name", "seed", "units", "container", "arrange", "items", "camera",
                   "render", "backdrop"});

  s.name = parse_name(root);
  if (auto seed = root.get("seed")) {
    const int64_t v = seed->integer();
    if (v < 0) seed->fail("must not be negative");
    s.seed = static_cast<uint64_t>(v);
  }
  if (auto u = root.get("units")) s.metres_per_unit = parse_units(*u);
  const double m = s.metres_per_unit;

  if (auto c = root.get("container")) s.container = parse_container(*c, m);
  Arrangement arrange =
      s.container.type == ContainerType::Board || s.container.type == ContainerType::None
          ? Arrangement::Scatter
          : Arrangement::Pile;
  if (auto a = root.get("arrange")) arrange = parse_arrangement(*a);

  fs::path scene_dir = fs::path(file).parent_path();
  if (scene_dir.empty()) scene_dir = ".";
  TemplateCheck templates;
  long long objects = 0, pieces = 0;  // totals of the items so far
  double heap_m3 = 0;                 // the heap the pieces kept so far make (kHeapPacking)
  const double holds_m3 = heap_capacity(s.container, LayoutOptions{}.none_radius_m);
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
    item.template_path = resolve_template(tmpl, scene_dir, "scene");
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
    const YamlField count_field = f.get("count").value_or(f);
    objects += item.count;
    if (objects > kMaxSceneObjects)
      count_field.fail("the items up to here make " + std::to_string(objects) +
                       " objects (at most " + std::to_string(kMaxSceneObjects) + " in a scene)");
    if (load_templates) {
      const LoadedTemplate& loaded = templates.check(item.template_path, item.cut, length_field);
      item.tmpl = loaded.tmpl;
      check_item_variation(f, *item.tmpl, item.variation);
      const ObjectExtents& extents = loaded.extents;
      pieces += item.count * estimate_piece_count(item.cut, extents);
      if (pieces > kMaxScenePieces)
        count_field.fail("the items up to here make about " + std::to_string(pieces) +
                         " pieces (at most " + std::to_string(kMaxScenePieces) + " in a scene)");
      item.cut_area_m2 = estimate_cut_area(item.cut, extents);
      heap_m3 += item.count * item.keep * estimate_object_volume(extents) / kHeapPacking;
      if (heap_m3 > holds_m3) count_field.fail(volume_rule(heap_m3, holds_m3, s.container.type));
    }
    s.items.push_back(std::move(item));
  }

  if (auto c = root.get("camera")) s.camera = parse_camera(*c, m);
  if (auto r = root.get("render")) s.render = parse_render(*r);
  s.backdrop = parse_backdrop(root.get("backdrop"), s.render.style);
  const double area = scene_cut_area(s);
  if (const Check texels = check_cap_texels(area, s.render.texels_per_mm); !texels) {
    const double fits = fitting_texels_per_mm(area, s.render.texels_per_mm);
    if (!s.render.texels_per_mm_given && fits > 0) {
      s.render.fitted_from_texels_per_mm = s.render.texels_per_mm;
      s.render.texels_per_mm = fits;
    } else {
      const auto density = root.get("render") ? root.get("render")->get("texels_per_mm")
                                              : std::optional<YamlField>();
      const YamlField last = items[items.size() - 1];
      (density ? *density : last.get("count").value_or(last)).fail(texels.reason());
    }
  }
  return s;
}

}  // namespace

double scene_cut_area(const Scene& scene) {
  double area = 0;
  for (const SceneItem& item : scene.items) area += item.count * item.cut_area_m2;
  return area;
}

std::string texel_fit_note(const Scene& scene) {
  const double from = scene.render.fitted_from_texels_per_mm;
  if (from <= 0) return {};
  char text[320];
  std::snprintf(text, sizeof text,
                "at %g texels per mm the cut faces would need about %.3g M texels (at most %g M): "
                "baked at %g texels per mm instead (render.texels_per_mm or --texels-per-mm "
                "sets the density; one that does not fit is refused)",
                from, scene_cut_area(scene) * from * from, kMaxCapTexels / 1e6,
                scene.render.texels_per_mm);
  return text;
}

Scene parse_scene(std::string_view text, const std::string& file) {
  return parse(text, file, false);
}

Scene parse_scene_and_templates(std::string_view text, const std::string& file) {
  return parse(text, file, true);
}

Scene load_scene(const std::string& path) { return parse(read_input_file(path), path, true); }

}  // namespace cutaway
