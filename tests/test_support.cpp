#include "test_support.h"

#include "diffusion/diffusion.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "pieces/manifold_check.h"

#include <algorithm>
#include <thread>
#include <tuple>
#include <map>
#include <memory>
#include <array>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <cstring>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <stb/stb_image.h>
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace cutaway::test {

namespace {

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

int system_exit_code(int status) { return WIFEXITED(status) ? WEXITSTATUS(status) : 128; }

/// Appends a blank and `word` quoted for the shell to `cmd`. (Appended piece by piece: GCC 12
/// warns falsely about overlapping memcpy in `" " + std::string&&`.)
void add_word(std::string& cmd, const std::string& word) {
  cmd += ' ';
  cmd += shell_quote(word);
}

/// A shell command run from the source tree: "cd SOURCE_DIR && [ENV] PROGRAM ARGS..." (quoted;
/// `env`, when given, is "NAME=VALUE" set for the program alone).
std::string in_source_dir(const std::string& program, const std::vector<std::string>& args,
                          const std::string& env = {}) {
  std::string cmd = "cd";
  add_word(cmd, CUTAWAY_SOURCE_DIR);
  cmd += " &&";
  if (const size_t eq = env.find('='); eq != std::string::npos)  // NAME=VALUE, VALUE quoted
    cmd += " " + env.substr(0, eq + 1) + shell_quote(env.substr(eq + 1));
  add_word(cmd, program);
  for (const std::string& a : args) add_word(cmd, a);
  return cmd;
}

/// Runs the shell command `cmd` with stdin from /dev/null, capturing its stdout and stderr.
RunResult run_shell(std::string cmd) {
  static int counter = 0;
  const auto dir = std::filesystem::path(CUTAWAY_TEST_TMP) / "runs";
  std::filesystem::create_directories(dir);
  const std::string tag = std::to_string(::getpid()) + "-" + std::to_string(counter++);
  const auto out = dir / (tag + ".out"), err = dir / (tag + ".err");
  cmd += " </dev/null >";
  cmd += shell_quote(out.string());
  cmd += " 2>";
  cmd += shell_quote(err.string());
  RunResult r;
  r.exit_code = system_exit_code(std::system(cmd.c_str()));
  r.out = slurp(out);
  r.err = slurp(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

/// Every test process starts with a default cut cache of its own (XDG_CACHE_HOME), empty, so
/// that whatever runs cutaway without run_cutaway or run_cutaway_limited (the editor's server,
/// the browser pages) never reads what another test stored.
/// Removed when the process that made it ends (not a child forked from it).
struct OwnDefaultCache {
  const pid_t owner = ::getpid();
  const std::filesystem::path dir =
      std::filesystem::path(CUTAWAY_TEST_TMP) / "process-caches" / std::to_string(owner);
  OwnDefaultCache() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
    ::setenv("XDG_CACHE_HOME", dir.c_str(), 1);
  }
  ~OwnDefaultCache() {
    std::error_code ec;
    if (::getpid() == owner) std::filesystem::remove_all(dir, ec);
  }
};
const OwnDefaultCache kOwnDefaultCache;

/// A cut cache folder for one run of cutaway, empty (under test-tmp/run-caches/), removed when
/// the run is over, whichever way the test leaves.
struct RunCache {
  const std::filesystem::path dir;
  RunCache() : dir(next()) { std::filesystem::remove_all(dir); }
  ~RunCache() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
  static std::filesystem::path next() {
    static int counter = 0;
    return std::filesystem::path(CUTAWAY_TEST_TMP) / "run-caches" /
           (std::to_string(::getpid()) + "-" + std::to_string(counter++));
  }
};

}  // namespace

RunResult run_cutaway(const std::vector<std::string>& args) {
  const RunCache cache;
  return run_shell(in_source_dir(CUTAWAY_BINARY, args, "XDG_CACHE_HOME=" + cache.dir.string()));
}

RunResult run_program(const std::string& program, const std::vector<std::string>& args) {
  return run_shell(in_source_dir(program, args));
}

::testing::AssertionResult made_afresh(const RunResult& run) {
  nlohmann::json stats;
  std::istringstream lines(run.err);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("{", 0) == 0) {
      const nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
      if (j.is_object() && j.contains("cut_cache")) stats = j;
    }
  if (stats.is_null())
    return ::testing::AssertionFailure() << "no --stats line with a cut_cache in: " << run.err;
  const nlohmann::json& cache = stats["cut_cache"];
  if (!cache.is_null() && cache.value("hits", 0) != 0)
    return ::testing::AssertionFailure()
           << cache.value("hits", 0) << " cut objects were read from the cut cache, not made";
  if (stats.contains("physics") && stats["physics"].value("from_cut_cache", false))
    return ::testing::AssertionFailure() << "the placements were read from the cut cache";
  return ::testing::AssertionSuccess();
}

std::string read_file(const std::filesystem::path& path) { return slurp(path); }

std::filesystem::path fresh_dir(const std::string& name) {
  // Unique per test and process: CTest runs the cases of one suite in parallel processes.
  std::string test = "no-test";
  if (const auto* info = ::testing::UnitTest::GetInstance()->current_test_info()) {
    test = std::string(info->test_suite_name()) + "." + info->name();
    for (char& c : test)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-') c = '_';
  }
  const auto dir = std::filesystem::path(CUTAWAY_TEST_TMP) /
                   (name + "-" + test + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

SceneBuildOptions quick_scene_options(CapColours colours) {
  SceneBuildOptions options;
  options.diffusion = [](const DsModel& model) { return make_cpu_diffusion(model, {4, 0}); };
  options.cap_colours = colours;
  return options;
}

SceneAssets build_settled_scene(const Scene& scene, CapColours colours, SceneStats* stats) {
  SceneAssets assets = build_scene(scene, scene.seed, quick_scene_options(colours), stats);
  EXPECT_EQ(stats->placed, stats->pieces);
  EXPECT_EQ(stats->lost, 0);
  EXPECT_LT(stats->stability_motion_m, 0.001);
  EXPECT_GE(stats->stability_checks, 1);
  return assets;
}

std::filesystem::path source_path(const std::string& relative) {
  return std::filesystem::path(CUTAWAY_SOURCE_DIR) / relative;
}

DsModel model_of(const std::string& relative) {
  return build_model(load_template(source_path(relative).string()));
}

Plane plane_of(glm::dvec3 point, glm::dvec3 normal) { return {point, glm::normalize(normal)}; }

DsSurface blurred_tetrahedron(double x0, double scale, const std::array<double, 4>& blur) {
  DsSurface s;
  std::vector<DsMesh::VertexHandle> v;
  const glm::dvec3 corners[] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (size_t k = 0; k < 4; ++k) {
    const glm::dvec3 p = corners[k];
    v.push_back(s.mesh.add_vertex(DsMesh::Point(x0 + scale * p.x, scale * p.y, scale * p.z)));
    s.mesh.data(v.back()).blur = blur[k];
  }
  s.mesh.add_face(v[0], v[2], v[1]);
  s.mesh.add_face(v[0], v[1], v[3]);
  s.mesh.add_face(v[0], v[3], v[2]);
  s.mesh.add_face(v[1], v[2], v[3]);
  return s;
}

std::vector<std::string> files_in(const std::filesystem::path& dir) {
  std::vector<std::string> out;
  if (!std::filesystem::exists(dir)) return out;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    if (e.is_regular_file()) out.push_back(std::filesystem::relative(e.path(), dir).string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

GltfReport validate_gltf(const std::filesystem::path& file) {
  const NodeToolRun run =
      run_node_tool("validate_gltf.mjs", {std::filesystem::absolute(file).string()});
  GltfReport r;
  r.output = run.output;
  if (run.report.is_object() && run.report.contains("errors") &&
      (run.exit_code == 0 || run.exit_code == 1)) {
    r.errors = run.report["errors"].get<int>();
  }
  return r;
}

NodeToolRun run_node_tool(const std::string& script, const std::vector<std::string>& args) {
  const auto log =
      std::filesystem::path(CUTAWAY_TEST_TMP) /
      ("node-" + std::to_string(::getpid()) + "-" +
       std::to_string(std::hash<std::thread::id>{}(std::this_thread::get_id())) + ".log");
  std::filesystem::create_directories(log.parent_path());
  std::vector<std::string> words{"tests/tools/" + script};
  words.insert(words.end(), args.begin(), args.end());
  std::string cmd = in_source_dir("node", words);
  cmd += " >";
  cmd += shell_quote(log.string());
  cmd += " 2>&1";
  NodeToolRun run;
  run.exit_code = system_exit_code(std::system(cmd.c_str()));
  run.output = slurp(log);
  std::filesystem::remove(log);
  std::istringstream lines(run.output);
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] != '{') continue;
    auto parsed = nlohmann::json::parse(line, nullptr, false);
    if (!parsed.is_discarded() && parsed.is_object()) run.report = std::move(parsed);
  }
  return run;
}

ThreeLoadReport load_gltf_three(const std::filesystem::path& file,
                                const std::filesystem::path& screenshot, int width, int height) {
  std::vector<std::string> args = {std::filesystem::absolute(file).string()};
  if (!screenshot.empty()) {
    args.insert(args.end(), {"--screenshot", std::filesystem::absolute(screenshot).string(),
                             std::to_string(width), std::to_string(height)});
  }
  const NodeToolRun run = run_node_tool("load_gltf_three.mjs", args);
  const int code = run.exit_code;
  const nlohmann::json& j = run.report;
  ThreeLoadReport r;
  r.output = run.output;
  if (!j.is_object()) {
    r.error = "no report from tests/tools/load_gltf_three.mjs (exit " + std::to_string(code) +
              "): " + r.output;
    return r;
  }
  try {
    r.ok = j.value("ok", false) && code == 0;
    r.meshes = j.value("meshes", 0);
    r.nodes = j.value("nodes", 0);
    r.cameras = j.value("cameras", 0);
    r.lights = j.value("lights", 0);
    r.triangles = j.value("triangles", 0L);
    r.mesh_objects = j.value("mesh_objects", 0);
    if (j.contains("camera_position") && j["camera_position"].is_array())
      r.camera_position = j["camera_position"].get<std::array<double, 3>>();
    if (j.contains("camera_direction") && j["camera_direction"].is_array())
      r.camera_direction = j["camera_direction"].get<std::array<double, 3>>();
    if (j.contains("light_directions"))
      r.light_directions = j["light_directions"].get<std::vector<std::array<double, 3>>>();
    if (j.contains("warnings")) r.warnings = j["warnings"].get<std::vector<std::string>>();
    r.seconds = j.value("seconds", 0.0);
    r.error = j.value("error", std::string());
  } catch (const nlohmann::json::exception& e) {
    r.ok = false;
    r.error = std::string("malformed report: ") + e.what();
  }
  if (!r.ok && r.error.empty()) r.error = "exit code " + std::to_string(code);
  return r;
}

std::vector<std::filesystem::path> shipped_templates() {
  std::vector<std::filesystem::path> out;
  for (const auto& e : std::filesystem::directory_iterator(source_path("templates"))) {
    if (e.path().extension() == ".yaml") out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string template_test_name(const std::filesystem::path& path) {
  std::string name = path.stem().string();
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

const BuiltTemplate& built_template(const std::filesystem::path& path) {
  static std::map<std::string, std::unique_ptr<BuiltTemplate>> built;
  std::unique_ptr<BuiltTemplate>& slot = built[path.string()];
  if (!slot) {
    Template tmpl = load_template(path.string());
    DsModel model = build_model(tmpl);
    slot = std::make_unique<BuiltTemplate>(BuiltTemplate{std::move(tmpl), std::move(model)});
  }
  return *slot;
}

MidHeightCut mid_height_cut(const std::filesystem::path& path) {
  const BuiltTemplate& b = built_template(path);
  return {b.tmpl, b.model, mid_height_plane(b.model)};
}

std::vector<size_t> interior_vertices(const CrossSection& cs, size_t at_most) {
  std::vector<size_t> interior;
  for (size_t v = 0; v < cs.position.size(); ++v)
    if (cs.cut_surface[v] < 0) interior.push_back(v);
  const size_t step = std::max<size_t>(1, interior.size() / at_most);
  std::vector<size_t> picked;
  for (size_t i = 0; i < interior.size(); i += step) picked.push_back(interior[i]);
  return picked;
}

PngInfo png_info(const std::filesystem::path& file) {
  const std::string png = read_file(file);
  PngInfo info;
  int channels = 0;
  unsigned char* pixels =
      stbi_load_from_memory(reinterpret_cast<const unsigned char*>(png.data()),
                            static_cast<int>(png.size()), &info.width, &info.height, &channels, 4);
  if (!pixels) return PngInfo{};
  for (int i = 0; i < info.width * info.height; ++i) {
    const unsigned char* px = pixels + 4 * i;
    info.not_background += std::memcmp(px, pixels, 3) != 0;
    info.dark += px[0] < 8 && px[1] < 8 && px[2] < 8;
    info.blue += px[2] > 2 * px[0] && px[2] > 60;
    info.yellow += px[0] > 2 * px[2] && px[1] > 2 * px[2] && px[1] > 60;
  }
  auto background = [&](int x, int y) {
    return x < 0 || y < 0 || x >= info.width || y >= info.height ||
           std::memcmp(pixels + 4 * (y * info.width + x), pixels, 3) == 0;
  };
  size_t inside = 0;
  for (int y = 0; y < info.height; ++y)
    for (int x = 0; x < info.width; ++x) {
      if (background(x, y) || background(x - 1, y) || background(x + 1, y) ||
          background(x, y - 1) || background(x, y + 1))
        continue;
      const unsigned char* px = pixels + 4 * (y * info.width + x);
      info.mean_colour += glm::dvec3(px[0], px[1], px[2]);
      ++inside;
    }
  if (inside) info.mean_colour /= static_cast<double>(inside);
  stbi_image_free(pixels);
  return info;
}

bool watertight(const tinygltf::Model& m, const tinygltf::Mesh& mesh) {
  std::map<std::array<float, 3>, int> id;
  std::map<std::pair<int, int>, int> edges;
  for (const tinygltf::Primitive& prim : mesh.primitives) {
    const tinygltf::Accessor& pos = m.accessors.at(prim.attributes.at("POSITION"));
    const tinygltf::BufferView& pv = m.bufferViews.at(pos.bufferView);
    const auto* xyz = reinterpret_cast<const float*>(m.buffers[0].data.data() + pv.byteOffset);
    const tinygltf::Accessor& idx = m.accessors.at(prim.indices);
    const tinygltf::BufferView& iv = m.bufferViews.at(idx.bufferView);
    const unsigned char* raw = m.buffers[0].data.data() + iv.byteOffset;
    auto vertex = [&](size_t i) {
      uint32_t v = 0;
      if (idx.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
        uint16_t s;
        std::memcpy(&s, raw + 2 * i, 2);
        v = s;
      } else {
        std::memcpy(&v, raw + 4 * i, 4);
      }
      const std::array<float, 3> p = {xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]};
      return id.emplace(p, static_cast<int>(id.size())).first->second;
    };
    for (size_t t = 0; t + 2 < idx.count; t += 3) {
      const int c[3] = {vertex(t), vertex(t + 1), vertex(t + 2)};
      for (int k = 0; k < 3; ++k) ++edges[std::minmax(c[k], c[(k + 1) % 3])];
    }
  }
  return std::all_of(edges.begin(), edges.end(), [](const auto& e) { return e.second % 2 == 0; });
}

double fraction_differing(const std::filesystem::path& a, const std::filesystem::path& b,
                          int tolerance) {
  int size[2][2] = {}, channels = 0;
  unsigned char* pixels[2] = {};
  const std::filesystem::path files[2] = {a, b};
  for (int k = 0; k < 2; ++k) {
    const std::string png = read_file(files[k]);
    pixels[k] =
        stbi_load_from_memory(reinterpret_cast<const unsigned char*>(png.data()),
                              static_cast<int>(png.size()), &size[k][0], &size[k][1], &channels, 4);
  }
  double fraction = 1.0;
  if (pixels[0] && pixels[1] && size[0][0] == size[1][0] && size[0][1] == size[1][1]) {
    const int n = size[0][0] * size[0][1];
    int differing = 0;
    for (int i = 0; i < n; ++i) {
      int worst = 0;
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, std::abs(pixels[0][4 * i + c] - pixels[1][4 * i + c]));
      differing += worst > tolerance;
    }
    fraction = n > 0 ? static_cast<double>(differing) / n : 0.0;
  }
  for (unsigned char* p : pixels) stbi_image_free(p);
  return fraction;
}

void texture_with_halves(SceneAssets& assets, size_t mesh, int size) {
  AssetTexture texture{"halves", size, size, 3, {}};
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const bool left = x < size / 2;
      texture.pixels.insert(texture.pixels.end(), {static_cast<uint8_t>(left ? 20 : 240),
                                                   static_cast<uint8_t>(left ? 40 : 220),
                                                   static_cast<uint8_t>(left ? 230 : 20)});
    }
  assets.textures.push_back(texture);
  assets.materials.push_back(
      {"cube_texture", PbrMaterial{}, static_cast<int>(assets.textures.size()) - 1});
  AssetMesh& m = assets.meshes[mesh];
  for (size_t v = 0; v < m.position.size(); ++v) {
    const int corner = static_cast<int>(v % 4);
    m.uv.push_back({corner == 1 || corner == 2 ? 1.0 : 0.0, corner >= 2 ? 1.0 : 0.0});
  }
  m.primitives = {{0, m.triangle.size(), static_cast<int>(assets.materials.size()) - 1, {}}};
}

::testing::AssertionResult closed_and_oriented(const ShadedMesh& mesh) {
  const Check manifold = check_manifold(mesh, 0);
  if (manifold) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << manifold.reason();
}

namespace {

/// The counter `key` ("rchar", "wchar") of a /proc/.../io file; UINT64_MAX when it cannot be
/// read (a kernel without task I/O accounting), which no bound admits.
uint64_t io_count(const std::string& io_file, const std::string& key) {
  std::ifstream io(io_file);
  for (std::string line; std::getline(io, line);)
    if (line.rfind(key + ": ", 0) == 0) return std::stoull(line.substr(key.size() + 2));
  return UINT64_MAX;
}

/// The address space this process has mapped now, bytes (VmSize of /proc/self/status).
uint64_t mapped_bytes() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmSize:", 0) == 0) return std::stoull(line.substr(7)) * 1024;
  return 0;
}

}  // namespace

LimitedRun run_cutaway_limited(const std::vector<std::string>& args, uint64_t address_space,
                               int cpu_seconds) {
  const std::filesystem::path dir = fresh_dir("limited_run");
  const std::filesystem::path err_file = dir / "stderr.txt", report_file = dir / "report.txt";
  const RunCache cache;
  // tests/tools/measured_run starts cutaway and measures it: a child forked from this process
  // would carry this process's peak memory into its own.
  std::vector<std::string> words{CUTAWAY_MEASURED_RUN, report_file.string(), CUTAWAY_BINARY};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  // The environment with a cut cache of the run's own, built before fork (setenv is not
  // async-signal-safe).
  std::vector<std::string> env_words{"XDG_CACHE_HOME=" + cache.dir.string()};
  for (char** e = environ; *e != nullptr; ++e)
    if (std::strncmp(*e, "XDG_CACHE_HOME=", 15) != 0) env_words.emplace_back(*e);
  std::vector<char*> envp;
  for (auto& w : env_words) envp.push_back(w.data());
  envp.push_back(nullptr);
  const std::string err_path = err_file.string();
  const pid_t pid = ::fork();
  if (pid == 0) {
    // Only async-signal-safe calls between fork and exec. The limits pass to cutaway.
    const rlimit as{address_space, address_space},
        cpu{static_cast<rlim_t>(cpu_seconds), static_cast<rlim_t>(cpu_seconds)};
#ifndef __SANITIZE_ADDRESS__  // AddressSanitizer reserves terabytes of shadow address space
    ::setrlimit(RLIMIT_AS, &as);
#else
    (void)as;
#endif
    ::setrlimit(RLIMIT_CPU, &cpu);
    if (::chdir(CUTAWAY_SOURCE_DIR) != 0) ::_exit(126);
    const int null = ::open("/dev/null", O_RDWR);
    const int err = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(null, 0);
    ::dup2(null, 1);
    ::dup2(err, 2);
    ::execve(argv[0], argv.data(), envp.data());
    ::_exit(127);
  }
  LimitedRun r;
  int status = 0;
  if (pid < 0 || ::waitpid(pid, &status, 0) != pid) {
    ADD_FAILURE() << "cannot run " << CUTAWAY_MEASURED_RUN;
    return r;
  }
  r.err = read_file(err_file);
  const std::string report = read_file(report_file);
  long long peak_kib = 0, read_bytes = 0, written_bytes = 0;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 ||
      std::sscanf(report.c_str(),
                  "exit %d signal %d peak_rss_kib %lld read_bytes %lld written_bytes %lld",
                  &r.exit_code, &r.signal, &peak_kib, &read_bytes, &written_bytes) != 5) {
    ADD_FAILURE() << "no measured run of " << CUTAWAY_BINARY << " (wait status " << status
                  << "): " << r.err;
    r.exit_code = -1;
    return r;
  }
  r.peak_rss_bytes = static_cast<uint64_t>(peak_kib) * 1024;
  // -1: the kernel keeps no I/O counts.
  r.read_bytes = read_bytes < 0 ? UINT64_MAX : static_cast<uint64_t>(read_bytes);
  r.written_bytes = written_bytes < 0 ? UINT64_MAX : static_cast<uint64_t>(written_bytes);
  return r;
}

const LimitedRun& cutaway_start() {
  static const LimitedRun start = [] {
    LimitedRun r = run_cutaway_limited({"--version"}, uint64_t{1} << 30, 60);
    EXPECT_EQ(r.exit_code, 0) << "cutaway --version: " << r.err;
    return r;
  }();
  return start;
}

uint64_t thread_bytes_read() {
  const uint64_t n = io_count("/proc/thread-self/io", "rchar");
  if (n == UINT64_MAX) ADD_FAILURE() << "no /proc/thread-self/io: the kernel keeps no I/O counts";
  return n;
}

int exit_code_within_address_space(uint64_t headroom, const std::function<int()>& body) {
  const uint64_t limit = mapped_bytes() + headroom;
  const pid_t child = ::fork();
  if (child < 0) return -1;
  if (child == 0) {
    const rlimit as{limit, limit};
    if (::setrlimit(RLIMIT_AS, &as) != 0) ::_exit(102);
    try {
      ::_exit(body());
    } catch (const std::bad_alloc&) {
      ::_exit(100);
    } catch (...) {
      ::_exit(101);
    }
  }
  int status = 0;
  if (::waitpid(child, &status, 0) != child || !WIFEXITED(status)) return -1;
  return WEXITSTATUS(status);
}

}  // namespace cutaway::test
