// The `cutaway` command line: parses arguments and calls the libraries; nothing else lives
// here (design/style.md). Exit codes: 0 success, 2 bad input, 1 internal failure.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "atomic_file.h"
#include "cross_section.h"
#include "diffusion_backends.h"
#include "error.h"
#include "gltf_export.h"
#include "model_builder.h"
#include "model_preview.h"
#include "plane_spec.h"
#include "ply_export.h"
#include "section_preview.h"
#include "template_parser.h"
#include "variation.h"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// A bad command-line argument: reported like InputError, exit code 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

void require_extension(const std::string& option, const std::string& path, const char* ext) {
  if (std::filesystem::path(path).extension() != ext) {
    throw UsageError(option + ": '" + path + "' must end in " + ext);
  }
}

struct ModelArgs {
  std::string template_path;
  std::string output;
  std::string png;
  int width = 800;
  int64_t seed = -1;  ///< >= 0: build the variant of this seed instead of the template
};

int run_model(const ModelArgs& a, bool stats) {
  const auto t0 = Clock::now();
  const cutaway::Template tmpl = cutaway::load_template(a.template_path);
  const double t_parse = seconds_since(t0);
  const auto t1 = Clock::now();
  const cutaway::DsModel model =
      a.seed >= 0 ? cutaway::make_variant(tmpl, static_cast<uint64_t>(a.seed)).model
                  : cutaway::build_model(tmpl);
  const double t_sweep = seconds_since(t1);
  spdlog::info("{}: {} surfaces, {} vertices, {} faces", tmpl.name, model.surfaces.size(),
               model.vertex_count(), model.face_count());

  const std::string glb = a.output.empty() && a.png.empty() ? tmpl.name + ".glb" : a.output;
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
    cutaway::write_model_glb(glb, model, cutaway::GltfModelOptions{});
    t_export = seconds_since(t3);
    spdlog::info("wrote {}", glb);
  }
  if (!a.png.empty()) {
    cutaway::write_png(a.png, image);
    spdlog::info("wrote {}", a.png);
  }
  if (stats) {
    std::fprintf(stderr,
                 "{\"template\": \"%s\", \"surfaces\": %zu, \"vertices\": %zu, \"faces\": %zu, "
                 "\"seconds\": {\"parse\": %.4f, \"sweep\": %.4f, \"render\": %.4f, "
                 "\"export\": %.4f}}\n",
                 tmpl.name.c_str(), model.surfaces.size(), model.vertex_count(),
                 model.face_count(), t_parse, t_sweep, t_render, t_export);
  }
  return 0;
}

struct SectionArgs {
  std::string template_path;
  std::string plane;
  std::string output;
  std::string png;
  int cube = 16;
  int width = 800;
};

int run_section(const SectionArgs& a, const std::string& backend, int threads, bool stats) {
  const auto t0 = Clock::now();
  const cutaway::Template tmpl = cutaway::load_template(a.template_path);
  cutaway::Plane plane;
  try {
    plane = cutaway::parse_plane_spec(a.plane, tmpl.metres_per_unit);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--plane: ") + e.what());
  }
  const cutaway::DsModel model = cutaway::build_model(tmpl);
  const double t_model = seconds_since(t0);
  const auto t1 = Clock::now();
  const auto diffusion = cutaway::make_diffusion(model, {a.cube, threads},
                                                 cutaway::parse_diffusion_choice(backend));
  const double t_backend = seconds_since(t1);
  const auto t2 = Clock::now();
  cutaway::CrossSection section;
  try {
    section = cutaway::make_cross_section(model, plane, *diffusion, {tmpl.edge_m});
  } catch (const std::domain_error& e) {
    throw UsageError(std::string("--plane ") + a.plane + ": " + e.what());
  }
  const double t_section = seconds_since(t2);
  spdlog::info("{}: cross-section with {} vertices ({} interior), {} triangles", tmpl.name,
               section.position.size(), section.interior_vertices, section.triangle.size());
  cutaway::Image image;
  if (!a.png.empty()) {
    cutaway::SectionPreviewOptions opt;
    opt.width = a.width;
    image = cutaway::render_section_preview(section, opt);
  }
  const std::string out = a.output.empty() && a.png.empty() ? tmpl.name + "-section.glb" : a.output;
  if (!out.empty()) {
    const bool ply = std::filesystem::path(out).extension() == ".ply";
    cutaway::write_file_atomically(out, ply ? cutaway::section_to_ply(section)
                                            : cutaway::section_to_glb(section));
    spdlog::info("wrote {}", out);
  }
  if (!a.png.empty()) {
    cutaway::write_png(a.png, image);
    spdlog::info("wrote {}", a.png);
  }
  if (stats) {
    std::fprintf(stderr,
                 "{\"template\": \"%s\", \"backend\": \"%s\", \"ds_faces\": %zu, "
                 "\"cut_segments\": %zu, \"vertices\": %zu, \"interior_vertices\": %zu, "
                 "\"diffused_points\": %zu, \"rays\": %zu, \"seconds\": {\"model\": %.4f, "
                 "\"backend_setup\": %.4f, \"section\": %.4f, \"triangulate\": %.4f, "
                 "\"diffuse\": %.4f}}\n",
                 tmpl.name.c_str(), diffusion->name().c_str(), model.face_count(),
                 section.cut_segments, section.position.size(), section.interior_vertices,
                 section.diffused_points,
                 section.diffused_points * 6 * static_cast<size_t>(a.cube * a.cube), t_model,
                 t_backend, t_section, section.seconds_triangulate, section.seconds_diffuse);
  }
  return 0;
}

int run_check(const std::vector<std::string>& files) {
  int failed = 0;
  for (const auto& f : files) {
    try {
      const cutaway::Template tmpl = cutaway::load_template(f);
      const cutaway::DsModel model = cutaway::build_model(tmpl);
      std::printf("%s: ok (template '%s', %zu surfaces, %zu DS faces)\n", f.c_str(),
                  tmpl.name.c_str(), model.surfaces.size(), model.face_count());
    } catch (const cutaway::InputError& e) {
      std::fprintf(stderr, "%s\n", e.what());
      ++failed;
    }
  }
  return failed ? 2 : 0;
}

/// FNV-1a, 64 bits: the content hash of a written file in manifests.
uint64_t fnv1a64(const std::string& bytes) {
  uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : bytes) h = (h ^ c) * 0x100000001b3ULL;
  return h;
}

struct VariantsArgs {
  std::string template_path;
  std::string output_dir;
  int count = 1;
  uint64_t seed = 0;
};

int run_variants(const VariantsArgs& a) {
  const cutaway::Template tmpl = cutaway::load_template(a.template_path);
  const std::filesystem::path dir(a.output_dir);
  std::filesystem::create_directories(dir);
  std::string manifest = "{\"template\": \"" + tmpl.name + "\", \"variants\": [\n";
  for (int i = 0; i < a.count; ++i) {
    const uint64_t seed = a.seed + static_cast<uint64_t>(i);
    const auto t0 = Clock::now();
    const cutaway::Variant v = cutaway::make_variant(tmpl, seed);
    const std::string glb = cutaway::model_to_glb(v.model, cutaway::GltfModelOptions{});
    const std::string file = tmpl.name + "-" + std::to_string(seed) + ".glb";
    cutaway::write_file_atomically(dir / file, glb);
    char line[512];
    std::snprintf(line, sizeof line,
                  "  {\"file\": \"%s\", \"seed\": %llu, \"template\": \"%s\", "
                  "\"fnv1a64\": \"%016llx\", \"ds_faces\": %zu, \"folds\": %d, "
                  "\"seconds\": %.4f}%s\n",
                  file.c_str(), static_cast<unsigned long long>(seed), tmpl.name.c_str(),
                  static_cast<unsigned long long>(fnv1a64(glb)), v.model.face_count(),
                  v.tmpl.folds, seconds_since(t0), i + 1 < a.count ? "," : "");
    manifest += line;
    spdlog::info("wrote {}", (dir / file).string());
  }
  manifest += "]}\n";
  cutaway::write_file_atomically(dir / "manifest.json", manifest);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"cutaway: cut objects with a consistent interior, from diffusion surfaces "
               "(Takayama et al. 2010)"};
  app.require_subcommand(1);
  app.fallthrough();  // common options may follow the subcommand
  bool stats = false, quiet = false, verbose = false;
  app.add_flag("--stats", stats, "print JSON timings and counts on stderr");
  app.add_flag("-q,--quiet", quiet, "print errors only");
  app.add_flag("-v,--verbose", verbose, "print progress and details");
  int threads = 0;
  app.add_option("--threads", threads, "worker threads (0: all cores); results do not depend on it")
      ->check(CLI::Range(0, 1024));
  std::string backend = "auto";
  app.add_option("--backend", backend,
                 "colour diffusion: cpu (Embree), gl (OpenGL cube maps), auto (gl on a GPU, "
                 "else cpu)")
      ->check(CLI::IsMember({"auto", "cpu", "gl"}));

  ModelArgs model_args;
  CLI::App* model = app.add_subcommand("model", "build the DS model of a template (glb, PNG)");
  model->add_option("TEMPLATE", model_args.template_path, "template file (.yaml)")->required();
  model->add_option("-o,--output", model_args.output,
                    "glTF binary to write (.glb); default NAME.glb when no --png is given");
  model->add_option("--png", model_args.png, "PNG picture of the see-through model");
  model->add_option("--size", model_args.width, "PNG width and height in pixels")
      ->check(CLI::Range(16, 8192));
  model->add_option("--seed", model_args.seed, "build the random variant of this seed")
      ->check(CLI::NonNegativeNumber);

  SectionArgs section_args;
  CLI::App* section = app.add_subcommand("section", "one cross-section with diffused colours");
  section->add_option("TEMPLATE", section_args.template_path, "template file (.yaml)")->required();
  section->add_option("--plane", section_args.plane,
                      "cutting plane: AXIS=VALUE (e.g. y=20) or px,py,pz/nx,ny,nz, template units")
      ->required();
  section->add_option("-o,--output", section_args.output,
                      "cut face to write: .glb (linear COLOR_0) or .ply (sRGB colours); "
                      "default NAME-section.glb when no --png is given");
  section->add_option("--png", section_args.png, "PNG of the cut face seen head-on (sRGB)");
  section->add_option("--size", section_args.width, "PNG width in pixels")
      ->check(CLI::Range(16, 8192));
  section->add_option("--cube", section_args.cube, "cube-map texels per face edge for PMVC")
      ->check(CLI::Range(2, 256));

  VariantsArgs variants_args;
  CLI::App* variants = app.add_subcommand("variants", "random variants of a template (glb + manifest.json)");
  variants->add_option("TEMPLATE", variants_args.template_path, "template file (.yaml)")->required();
  variants->add_option("--count", variants_args.count, "number of variants")
      ->check(CLI::Range(1, 100000));
  variants->add_option("--seed", variants_args.seed, "seed of the first variant (then seed + 1, ...)");
  variants->add_option("-o,--output", variants_args.output_dir, "output folder")->required();

  std::vector<std::string> check_files;
  CLI::App* check = app.add_subcommand("check", "validate templates without writing anything");
  check->add_option("FILE", check_files, "template files")->required();

  auto logger = spdlog::stderr_color_st("cutaway");
  spdlog::set_default_logger(logger);
  spdlog::set_pattern("%v");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  spdlog::set_level(quiet ? spdlog::level::err
                          : (verbose ? spdlog::level::debug : spdlog::level::info));
  try {
    if (*model) {
      if (!model_args.output.empty()) require_extension("-o", model_args.output, ".glb");
      if (!model_args.png.empty()) require_extension("--png", model_args.png, ".png");
      return run_model(model_args, stats);
    }
    if (*section) {
      if (!section_args.output.empty() &&
          std::filesystem::path(section_args.output).extension() != ".ply") {
        require_extension("-o", section_args.output, ".glb");
      }
      if (!section_args.png.empty()) require_extension("--png", section_args.png, ".png");
      return run_section(section_args, backend, threads, stats);
    }
    if (*check) return run_check(check_files);
    if (*variants) return run_variants(variants_args);
  } catch (const cutaway::InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const UsageError& e) {
    std::fprintf(stderr, "cutaway: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cutaway: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
