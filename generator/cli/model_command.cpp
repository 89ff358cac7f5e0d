// `cutaway model`: the DS model of a template (or of a seeded variant) as glTF and a PNG.
#include <chrono>
#include <filesystem>

#include <spdlog/spdlog.h>

#include "base/timer.h"
#include "cli/commands.h"
#include "export/gltf_export.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "render/image/image.h"
#include "render/model_preview.h"
#include "variation/variation.h"

namespace cutaway::cli {

using Clock = std::chrono::steady_clock;

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
    *common.stats = {{"template", tmpl.name},
                     {"surfaces", model.surfaces.size()},
                     {"vertices", model.vertex_count()},
                     {"faces", model.face_count()},
                     {"seconds",
                      {{"parse", t_parse}, {"sweep", t_sweep}, {"render", t_render},
                       {"export", t_export}}}};
  }
  return 0;
}

}  // namespace cutaway::cli
