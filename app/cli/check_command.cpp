// `cutaway check`: validates templates, scenes and batches without writing anything.
#include <cstdio>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "app/cli/commands.h"
#include "base/error.h"
#include "io/batch_parser.h"
#include "io/scene_parser.h"
#include "io/template_parser.h"
#include "io/yaml_reader.h"
#include "model/model_builder.h"
#include "scene/scene_budget.h"
#include "variation/grains.h"

namespace cutaway::cli {

namespace {

/// Builds the model of each template in `paths` once, so that its geometric rules are checked
/// too (a scene's or batch's templates).
void check_models(const std::vector<std::string>& paths) {
  for (const std::string& path : std::set<std::string>(paths.begin(), paths.end())) {
    const cutaway::Template t = cutaway::load_template(path);
    cutaway::check_grain_limits(t, cutaway::build_model(t));
  }
}

/// `cutaway check FILE...`: each template, scene or batch file read and checked (its templates'
/// models built), "FILE: ok (...)" on stdout or the error on stderr; 2 when any failed
///.
int run_check(const std::vector<std::string>& files) {
  int failed = 0;
  for (const auto& f : files) {
    try {
      // A scene or batch says so in its `format` (cutaway-scene/..., cutaway-batch/...);
      // anything else is a template.
      const auto format = cutaway::load_yaml_file(f).get("format");
      const std::string kind = format && format->is_scalar() ? format->string() : "";
      if (kind.rfind("cutaway-batch/", 0) == 0) {
        const cutaway::Batch batch = cutaway::load_batch(f);
        int variants = 0, assets = 0;
        std::vector<std::string> templates;
        for (const auto& item : batch.items) {
          variants += item.count;
          assets += item.count * static_cast<int>(item.cuts.size());
          templates.push_back(item.template_path);
        }
        check_models(templates);
        std::printf("%s: ok (batch '%s', %zu items, %d variants, %d assets)\n", f.c_str(),
                    batch.name.c_str(), batch.items.size(), variants, assets);
        continue;
      }
      if (kind.rfind("cutaway-scene/", 0) == 0) {
        const cutaway::Scene scene = cutaway::load_scene(f);
        // Each template's model is built once: for the scene's total and its grain limits.
        const long long vertices = cutaway::check_scene_model_vertices(
            scene, [](const cutaway::Template& t, const cutaway::DsModel& m) {
              cutaway::check_grain_limits(t, m);
            });
        int objects = 0;
        for (const auto& item : scene.items) objects += item.count;
        std::printf("%s: ok (scene '%s', %zu items, %d objects, %.2f M model vertices, at most "
                    "%.1f M cap texels)\n",
                    f.c_str(), scene.name.c_str(), scene.items.size(), objects, vertices / 1e6,
                    // m^2 x (texels per mm)^2 = millions of texels
                    cutaway::scene_cut_area(scene) * scene.render.texels_per_mm *
                        scene.render.texels_per_mm);
        if (const std::string fitted = cutaway::texel_fit_note(scene); !fitted.empty())
          std::fprintf(stderr, "%s: warning: %s\n", f.c_str(), fitted.c_str());
        continue;
      }
      const cutaway::Template tmpl = cutaway::load_template(f);
      const cutaway::DsModel model = cutaway::build_model(tmpl);
      cutaway::check_grain_limits(tmpl, model);
      std::printf("%s: ok (template '%s', %zu surfaces, %zu DS faces)\n", f.c_str(),
                  tmpl.name.c_str(), model.surfaces.size(), model.face_count());
    } catch (const cutaway::InputError& e) {
      std::fprintf(stderr, "%s\n", e.what());
      ++failed;
    }
  }
  return failed ? 2 : 0;
}

}  // namespace

Command add_check_command(CLI::App& app) {
  auto files = std::make_shared<std::vector<std::string>>();
  CLI::App* check = app.add_subcommand(
      "check", "validate templates, scenes and batches without writing anything");
  check->add_option("FILE", *files, "template, scene and batch files")->required();
  return {check, [files](const Common&, OutputSet&) { return run_check(*files); }};
}

}  // namespace cutaway::cli
