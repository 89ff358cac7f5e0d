// `cutaway section`: one cross-section of a template (or of a seeded variant) with diffused
// colours, as glTF or PLY and a PNG.
#include <chrono>
#include <filesystem>
#include <memory>

#include <spdlog/spdlog.h>

#include "app/cli/commands.h"
#include "base/atomic_file.h"
#include "base/timer.h"
#include "diffusion/diffusion.h"
#include "export/gltf_export.h"
#include "export/ply_export.h"
#include "io/plane_spec.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "render/image/image.h"
#include "render/section_preview.h"
#include "section/cross_section.h"
#include "variation/variation.h"

namespace cutaway::cli {

namespace {

using Clock = std::chrono::steady_clock;

/// `cutaway section TEMPLATE --plane SPEC [-o cut.glb|cut.ply] [--png cut.png] [--cube N]
/// [--seed S]`.
struct SectionArgs {
  std::string template_path;
  std::string plane;
  std::string output;
  std::string png;
  int cube = kDefaultCubeSize;
  int width = 800;
  int64_t seed = -1;  ///< >= 0: cut the variant of this seed instead of the template
};

int run_section(const SectionArgs& a, const Common& common, OutputSet& outputs) {
  const auto t0 = Clock::now();
  const cutaway::Template tmpl = cutaway::load_template(a.template_path);
  const cutaway::Outcome<cutaway::Plane> parsed =
      cutaway::parse_plane_spec(a.plane, tmpl.metres_per_unit);
  if (!parsed) throw UsageError("--plane: " + parsed.reason());
  const cutaway::Plane plane = *parsed;
  const std::string out = a.output.empty() && a.png.empty() ? tmpl.name + "-section.glb" : a.output;
  const std::filesystem::path out_file = out.empty() ? "" : outputs.add("-o", out);
  const std::filesystem::path png_file = a.png.empty() ? "" : outputs.add("--png", a.png);
  const cutaway::DsModel model =
      a.seed >= 0 ? cutaway::make_variant(tmpl, static_cast<uint64_t>(a.seed)).model
                  : cutaway::build_model(tmpl);
  const double t_model = seconds_since(t0);
  const auto t1 = Clock::now();
  const auto diffusion = diffusion_factory(a.cube, common)(model);
  const double t_backend = seconds_since(t1);
  const auto t2 = Clock::now();
  cutaway::CrossSectionOptions options{tmpl.edge_m};
  options.sampling = common.sampling;
  cutaway::Outcome<cutaway::CrossSection> made =
      cutaway::make_cross_section(model, plane, *diffusion, options);
  if (!made) throw UsageError("--plane " + cutaway::quoted(a.plane) + ": " + made.reason());
  const cutaway::CrossSection section = std::move(*made);
  const double t_section = seconds_since(t2);
  spdlog::info("{}: cross-section with {} vertices ({} interior), {} triangles", tmpl.name,
               section.position.size(), section.interior_vertices, section.triangle.size());
  cutaway::Image image;
  if (!a.png.empty()) {
    cutaway::SectionPreviewOptions opt;
    opt.width = a.width;
    image = cutaway::render_section_preview(section, opt);
  }
  if (!out.empty()) {
    const bool ply = std::filesystem::path(out).extension() == ".ply";
    cutaway::write_file_atomically(out_file, ply ? cutaway::section_to_ply(section)
                                                 : cutaway::section_to_glb(section));
    spdlog::info("wrote {}", out);
  }
  if (!a.png.empty()) {
    cutaway::write_png(png_file, image);
    spdlog::info("wrote {}", a.png);
  }
  if (common.stats) {
    *common.stats = {{"template", tmpl.name},
                     {"backend", diffusion->name()},
                     {"ds_faces", model.face_count()},
                     {"cut_segments", section.cut_segments},
                     {"vertices", section.position.size()},
                     {"interior_vertices", section.interior_vertices},
                     {"diffused_points", section.diffused.all},
                     {"rays", diffusion->rays_cast()},
                     {"seconds",
                      {{"model", t_model},
                       {"backend_setup", t_backend},
                       {"section", t_section},
                       {"triangulate", section.seconds_triangulate},
                       {"diffuse", section.seconds_diffuse}}}};
  }
  return 0;
}

}  // namespace

Command add_section_command(CLI::App& app) {
  auto args = std::make_shared<SectionArgs>();
  CLI::App* section = app.add_subcommand("section", "one cross-section with diffused colours");
  section->add_option("TEMPLATE", args->template_path, "template file (.yaml)")->required();
  section
      ->add_option("--plane", args->plane,
                   "cutting plane: AXIS=VALUE (e.g. y=20) or px,py,pz/nx,ny,nz, template units")
      ->required();
  section->add_option("-o,--output", args->output,
                      "cut face to write: .glb (linear COLOR_0) or .ply (sRGB colours); "
                      "default NAME-section.glb when no --png is given");
  section->add_option("--png", args->png, "PNG of the cut face seen head-on (sRGB)");
  section->add_option("--size", args->width, "PNG width in pixels")->check(number_rule(16, 2880));
  section->add_option("--cube", args->cube, "cube-map texels per face edge for PMVC")
      ->check(number_rule(2, 256));
  section->add_option("--seed", args->seed, "cut the random variant of this seed")
      ->check(seed_rule());
  return {section, [args](const Common& common, OutputSet& outputs) {
            if (!args->output.empty() && std::filesystem::path(args->output).extension() != ".ply")
              require_extension("-o", args->output, ".glb");
            if (!args->png.empty()) require_extension("--png", args->png, ".png");
            return run_section(*args, common, outputs);
          }};
}

}  // namespace cutaway::cli
