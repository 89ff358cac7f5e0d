#include "io/format_fields.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "io/template_parser.h"
#include "io/text_rules.h"
#include "model/template.h"
#include "variation/organic_deformation.h"

#ifndef CUTAWAY_TEMPLATES_DIR
#define CUTAWAY_TEMPLATES_DIR "templates"
#endif

namespace cutaway {

namespace fs = std::filesystem;

void require_format(const YamlField& root, const std::string& expected) {
  const YamlField format = root.require("format");
  if (format.string() != expected) {
    format.fail("unsupported format " + quoted(format.string()) +
                " (this version of cutaway reads " + expected + ")");
  }
}

std::string parse_name(const YamlField& root) {
  const YamlField name = root.require("name");
  std::string value = name.string();
  if (const Check plain = check_name(value); !plain) name.fail(plain.reason());
  return value;
}

double parse_units(const YamlField& f) {
  const std::string v = f.string();
  if (v == "mm") return 1e-3;
  if (v == "cm") return 1e-2;
  if (v == "m") return 1.0;
  f.fail("must be mm, cm or m, not " + quoted(v));
}

double parse_coordinate(const YamlField& f, double metres_per_unit) {
  const double m = f.number() * metres_per_unit;
  if (std::fabs(m) > kMaxSceneMetres) f.fail("must be at most 1 km in size (|value| <= 1000 m)");
  return m;
}

double parse_positive_length(const YamlField& f, double metres_per_unit) {
  const double m = parse_coordinate(f, metres_per_unit);
  if (!(m > 0)) f.fail("must be positive");
  return m;
}

int parse_int_in(const YamlField& f, int lo, int hi) {
  const int64_t v = f.integer();
  if (v < lo || v > hi) {
    f.fail("must be a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) +
           ", not " + std::to_string(v));
  }
  return static_cast<int>(v);
}

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
  else type.fail("must be whole, halves, slices, wedges or dice, not " + quoted(t));
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

std::string resolve_template(const YamlField& f, const fs::path& scene_dir, const char* kind) {
  const std::string v = f.string();
  if (v.empty()) f.fail("must not be empty (a template name or a path ending in .yaml)");
  std::error_code ec;
  const bool is_path = v.find('/') != std::string::npos ||
                       (v.size() >= 5 && v.compare(v.size() - 5, 5, ".yaml") == 0);
  if (is_path) {
    const fs::path p = fs::path(v).is_absolute() ? fs::path(v) : (scene_dir / v).lexically_normal();
    if (!fs::is_regular_file(p, ec)) {
      f.fail("the template file " + quoted(p.string(), 4096) +
             " does not exist (a path is relative to the " + std::string(kind) + "'s folder)");
    }
    return p.string();
  }
  if (const Check plain = check_name(v); !plain) {
    f.fail("a template is a name or a path ending in .yaml; " + plain.reason());
  }
  std::vector<fs::path> dirs{(scene_dir / ".." / "templates").lexically_normal()};
  const auto add = [&](const fs::path& d) {  // each folder once (messages list them)
    if (std::find(dirs.begin(), dirs.end(), d.lexically_normal()) == dirs.end())
      dirs.push_back(d.lexically_normal());
  };
  if (const char* env = std::getenv("CUTAWAY_TEMPLATES"); env && *env) add(env);
  add(CUTAWAY_TEMPLATES_DIR);
  std::string looked;
  for (const auto& d : dirs) {
    const fs::path p = d / (v + ".yaml");
    if (fs::is_regular_file(p, ec)) return p.string();
    looked += (looked.empty() ? "" : ", ") + quoted(d.string(), 4096);  // paths whole (PATH_MAX)
  }
  f.fail("no template named " + quoted(v) + " (looked for " + v + ".yaml in " + looked + ")");
}

const LoadedTemplate& TemplateCheck::check(const std::string& template_path, const CutSpec& cut,
                                           const std::optional<YamlField>& length_field) {
  auto it = loaded_.find(template_path);
  if (it == loaded_.end()) {
    auto t = std::make_shared<const Template>(load_template(template_path));
    const ObjectExtents extents = template_extents(*t);
    it = loaded_.emplace(template_path, LoadedTemplate{std::move(t), extents}).first;
  }
  const LoadedTemplate& loaded = it->second;
  const long long n = estimate_piece_count(cut, loaded.extents);
  if (n > kMaxPiecesPerCut && length_field) {
    std::ostringstream s;
    s << "too small: would make " << n << " pieces of template " << quoted(loaded.tmpl->name)
      << " (at most " << kMaxPiecesPerCut << " per object)";
    length_field->fail(s.str());
  }
  return loaded;
}

void check_item_variation(const YamlField& item, const Template& tmpl, double variation) {
  const auto field = item.get("variation");
  if (!field) return;
  const Check c =
      check_organic(tmpl.organic, tmpl.variation_amount * variation, tmpl.metres_per_unit);
  if (!c) field->fail("template " + tmpl.name + ": " + c.reason());
}

}  // namespace cutaway
