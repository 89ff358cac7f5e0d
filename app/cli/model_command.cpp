// `cutaway model`: the DS model of a template (or of a seeded variant) as glTF and a PNG.
#include <chrono>
#include <filesystem>
#include <memory>

#include <spdlog/spdlog.h>

#include "app/cli/commands.h"
#include "base/timer.h"
#include "export/gltf_export.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "render/image/image.h"
#include "render/model_preview.h"
#include "variation/variation.h"

namespace cutaway::cli {

namespace {

using Clock = std::chrono::steady_clock;

/// `cutaway model TEMPLATE [-o model.glb] [--png view.png] [--size PX] [--seed S]`
///.
struct ModelArgs {
  std::string template_path;
  std::string output;
  std::string png;
  int width = 800;
  int64_t seed = -1;  ///< >= 0: build the variant of this seed instead of the template
};

int run_model(const ModelArgs& a, const Common& common, OutputSet& outputs) {
  const auto t0 = Clock::now();
  const cutaway::Template tmpl = cutaway::load_template(a.template_path);
  const std::string glb = a.output.empty() && a.png.empty() ? tmpl.name + ".glb" : a.output;
  const std::filesystem::path glb_file = glb.empty() ? "" : outputs.add("-o", glb);
  const std::filesystem::path png_file = a.png.empty() ? "" : outputs.add("--png", a.png);
  const double t_parse = seconds_since(t0);
  const auto t1 = Clock::now();
  const cutaway::DsModel model =
      a.seed >= 0 ? cutaway::make_variant(tmpl, static_cast<uint64_t>(a.seed)).model
                  : cutaway::build_model(tmpl);
  const double t_sweep = seconds_since(t1);
  spdlog::info("{}: {} surfaces, {} vertices, {} faces", tmpl.name, model.surfaces.size(),
               model.vertex_count(), model.face_count());

  double t_render = 0, t_export = 0;
  cutaway::Image image;
  if (!a.png.empty()) {
    const auto t2 = Clock::now();
    cutaway::PreviewOptions opt;
    opt.width = opt.height = a.width;
    image = cutaway::render_model_preview(model, opt);
    t_render = seconds_since(t2);
  }
  if (!glb.empty()) {
    const auto t3 = Clock::now();
    cutaway::write_model_glb(glb_file, model, cutaway::GltfModelOptions{});
    t_export = seconds_since(t3);
    spdlog::info("wrote {}", glb);
  }
  if (!a.png.empty()) {
    cutaway::write_png(png_file, image);
    spdlog::info("wrote {}", a.png);
  }
  if (common.stats) {
    *common.stats = {
        {"template", tmpl.name},
        {"surfaces", model.surfaces.size()},
        {"vertices", model.vertex_count()},
        {"faces", model.face_count()},
        {"seconds",
         {{"parse", t_parse}, {"sweep", t_sweep}, {"render", t_render}, {"export", t_export}}}};
  }
  return 0;
}

}  // namespace

Command add_model_command(CLI::App& app) {
  auto args = std::make_shared<ModelArgs>();
  CLI::App* model = app.add_subcommand("model", "build the DS model of a template (glb, PNG)");
  model->add_option("TEMPLATE", args->template_path, "template file (.yaml)")->required();
  model->add_option("-o,--output", args->output,
                    "glTF binary to write (.glb); default NAME.glb when no --png is given");
  model->add_option("--png", args->png, "PNG picture of the see-through model");
  model->add_option("--size", args->width, "PNG width and height in pixels")
      ->check(number_rule(16, 2880));
  model->add_option("--seed", args->seed, "build the random variant of this seed")
      ->check(seed_rule());
  return {model, [args](const Common& common, OutputSet& outputs) {
            if (!args->output.empty()) require_extension("-o", args->output, ".glb");
            if (!args->png.empty()) require_extension("--png", args->png, ".png");
            return run_model(*args, common, outputs);
          }};
}

}  // namespace cutaway::cli
