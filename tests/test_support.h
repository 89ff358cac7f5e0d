// Shared helpers of the tests: running the CLI, fresh temporary folders, glTF validation.
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>
#include <vector>

#include <gtest/gtest.h>

#include <tiny_gltf.h>

#include "assets/scene_assets.h"
#include "model/ds_model.h"
#include "model/template.h"
#include "pieces/shaded_mesh.h"
#include "scene/scene_builder.h"
#include "section/cross_section.h"

namespace cutaway::test {

/// What one run of the `cutaway` executable did.
struct RunResult {
  int exit_code = -1;
  std::string out;  ///< stdout
  std::string err;  ///< stderr
};

/// Runs build/cutaway with `args` (no shell interpretation of the arguments), in the source
/// directory, and captures exit code, stdout and stderr. Each run has a default cut cache of
/// its own, empty (XDG_CACHE_HOME), removed afterwards: two runs never share cut objects unless
/// the test names one `--cache DIR` for both.
RunResult run_cutaway(const std::vector<std::string>& args);

/// Whether `run` (a scene or batch run given `--stats`) made every cut object and placement
/// itself: its stats line reports a cut_cache (or null with --no-cache) without hits, and no
/// placements from the cache. What every byte comparison across runs asserts of each run, so
/// that it compares work done, not a cache read back.
::testing::AssertionResult made_afresh(const RunResult& run);

/// Runs `program` (a path, or a name found on PATH) with `args` as run_cutaway runs cutaway.
RunResult run_program(const std::string& program, const std::vector<std::string>& args);

/// What one run of build/cutaway under limits did, measured in work (memory, bytes), never in
/// time: a run that hangs is stopped by its CPU limit or by CTest's timeout.
struct LimitedRun {
  int exit_code = -1;  ///< -1: killed by a signal
  int signal = 0;
  std::string err;  ///< stderr
  /// cutaway's own peak resident memory (wait4's ru_maxrss, taken by tests/tools/measured_run,
  /// which starts it: not this process's peak, which a child forked from it would carry).
  uint64_t peak_rss_bytes = 0;
  /// Bytes cutaway's read calls returned (rchar of /proc/PID/io, taken before it is reaped):
  /// files, pipes and /proc alike, whether from the page cache or the disk; cutaway_start()
  /// says what the program reads before any input. UINT64_MAX (which no bound admits) when the
  /// kernel keeps no I/O counts.
  uint64_t read_bytes = 0;
  uint64_t written_bytes = 0;  ///< bytes its write calls took (wchar of /proc/PID/io), likewise
};

/// Runs build/cutaway with `args` in the source directory through tests/tools/measured_run,
/// with at most `address_space` bytes of address space (RLIM_INFINITY: no limit; an allocation
/// beyond it fails: std::bad_alloc, exit code 1; not under AddressSanitizer, which needs far
/// more address space, and reports huge allocations itself) and `cpu_seconds` of CPU time (a
/// safety net against a hang, never a measure: a regression fails the test instead of taking
/// the machine). Like run_cutaway, each run has an empty cut cache of its own; its stdout is
/// discarded. A run that cannot be started or measured adds a test failure (exit_code -1).
/// Peak memory under AddressSanitizer (shadow memory, a quarantine of freed blocks) says little:
/// see kPeakMemoryBounds.
LimitedRun run_cutaway_limited(const std::vector<std::string>& args, uint64_t address_space,
                               int cpu_seconds);

/// Whether bounds on peak resident memory hold in this build: not under AddressSanitizer, whose
/// shadow memory and quarantine of freed blocks (256 MiB) add to every peak.
#ifdef __SANITIZE_ADDRESS__
inline constexpr bool kPeakMemoryBounds = false;
#else
inline constexpr bool kPeakMemoryBounds = true;
#endif

/// What build/cutaway costs before it looks at any input: its run of `cutaway --version` under
/// run_cutaway_limited (1 GiB, 60 s of CPU), made once per test process. Its read_bytes are
/// the libraries' headers, /proc and /sys (about 56 KiB), its peak_rss_bytes the loaded program
/// (about 100 MiB): the baseline that bounds on a run's work are stated over.
const LimitedRun& cutaway_start();

/// Bytes the calling thread's read calls have returned so far (rchar of /proc/thread-self/io):
/// the difference of two calls is what the code between them read, plus the about 100 bytes
/// of the first call's own read of that file. A test failure when the kernel keeps no such
/// count.
uint64_t thread_bytes_read();

/// Runs `body` in a forked child whose address space may grow by at most `headroom` bytes over
/// what this process has mapped now (VmSize of /proc/self/status), and returns the child's exit
/// code: what `body` returned, 100 when it threw std::bad_alloc (an allocation beyond the
/// headroom), 101 when it threw anything else, -1 when the child could not be started or
/// did not exit. Measures peak allocation (reserved, not only touched, memory) of in-process
/// code without the test process's own history.
int exit_code_within_address_space(uint64_t headroom, const std::function<int()>& body);

/// A fresh, empty directory under the build tree, named after `name`, the running test and
/// the process (parallel test processes never share one).
std::filesystem::path fresh_dir(const std::string& name);

/// Absolute path of a file in the source tree, e.g. source_path("templates/tomato.yaml").
std::filesystem::path source_path(const std::string& relative);

/// The diffusion-surface model of the template at `relative` in the source tree (the template's
/// own sweep, no variation), e.g. model_of("templates/kiwi.yaml"). Throws what load_template
/// and build_model throw.
DsModel model_of(const std::string& relative);

/// A surface that is a tetrahedron with corners (x0, 0, 0) + scale * {0, e_x, e_y, e_z}
/// (metres), faces wound outwards, corner k with blur blur[k] (metres).
DsSurface blurred_tetrahedron(double x0, double scale, const std::array<double, 4>& blur);

/// The plane through `point` (metres) with the unit normal along `normal` (any length > 0).
Plane plane_of(glm::dvec3 point, glm::dvec3 normal);

/// Options of build_scene for quick scene tests: the cpu backend with 4 cube-map cells per face
/// and all threads, cap colours `colours`, every other option its default.
SceneBuildOptions quick_scene_options(CapColours colours);

/// Builds `scene` at its own seed with quick_scene_options(colours), its statistics into
/// *stats, and checks (as gtest expectations) what every settled scene meets: every piece
/// placed, none lost, and the stability check run and under 1 mm.
SceneAssets build_settled_scene(const Scene& scene, CapColours colours, SceneStats* stats);

/// The bytes of the file at `path` (empty when it cannot be read).
std::string read_file(const std::filesystem::path& path);

/// Every regular file below `dir` (recursively), relative paths, sorted.
std::vector<std::string> files_in(const std::filesystem::path& dir);

/// What one run of a node script of tests/tools printed.
struct NodeToolRun {
  nlohmann::json report;  ///< its last line that parses as a JSON object (null when none)
  int exit_code = -1;
  std::string output;  ///< everything it printed (stdout and stderr)
};

/// Runs `node tests/tools/SCRIPT ARGS...` in the source directory (no shell interpretation of
/// the arguments).
NodeToolRun run_node_tool(const std::string& script, const std::vector<std::string>& args);

/// Result of the Khronos glTF validator on one file.
struct GltfReport {
  int errors = -1;     ///< -1: the validator did not run
  std::string output;  ///< its JSON line (messages included)
};

/// Runs the Khronos glTF validator (node + npm gltf-validator from node_modules/, installed by
/// `make test`) on `file`. The validator missing is a test failure, never a skip.
GltfReport validate_gltf(const std::filesystem::path& file);

/// What three.js's GLTFLoader (a real glTF client) made of one file in headless Chromium.
struct ThreeLoadReport {
  bool ok = false;       ///< the file loaded
  int meshes = 0;        ///< glTF meshes built
  int nodes = 0;         ///< glTF nodes built
  int cameras = 0;       ///< camera objects in the loaded scene
  int lights = 0;        ///< light objects in the loaded scene
  long triangles = 0;    ///< triangles of every mesh object (instances counted)
  int mesh_objects = 0;  ///< mesh objects in the scene (one per node and primitive)
  std::array<double, 3> camera_position{};              ///< world space, metres (the last camera)
  std::array<double, 3> camera_direction{};             ///< world space, unit: where it looks
  std::vector<std::array<double, 3>> light_directions;  ///< of directional lights, unit
  std::vector<std::string> warnings;                    ///< console warnings and errors of the page
  double seconds = 0;  ///< the whole run: server, Chromium launch, load
  std::string error;   ///< why it failed
  std::string output;  ///< everything the script printed
};

/// Loads `file` (.glb, or .gltf with its .bin) with three.js's GLTFLoader in headless Chromium
/// (tests/tools/load_gltf_three.mjs: /usr/bin/chromium through npm playwright-core, three from
/// node_modules/, served on 127.0.0.1 only). Chromium, node or the npm modules missing is a
/// failed report (ok false, error set), never a skip. Takes about a second or two. With
/// `screenshot`, also renders the file with its camera and lights (WebGL in software) into
/// that PNG, width x height pixels.
ThreeLoadReport load_gltf_three(const std::filesystem::path& file,
                                const std::filesystem::path& screenshot = {}, int width = 800,
                                int height = 600);

/// A summary of a PNG file for checks on pictures.
struct PngInfo {
  int width = 0, height = 0;  ///< 0 when the file is not a PNG stb_image can read
  size_t not_background = 0;  ///< pixels whose RGB differs from the top-left pixel's
  size_t dark = 0;            ///< pixels with R, G and B all below 8
  size_t blue = 0;            ///< pixels clearly blue: B > 2 R and B > 60
  size_t yellow = 0;          ///< pixels clearly yellow: R and G > 2 B, and G > 60
  /// Mean 8-bit sRGB (0..255) of the pixels that differ from the top-left one and whose four
  /// neighbours do too: the objects' colour without their edges blended with the background.
  glm::dvec3 mean_colour{0.0};
};

/// Reads `file` with stb_image and summarises it.
PngInfo png_info(const std::filesystem::path& file);

/// Whether the triangles of all primitives of glTF mesh `mesh` (float positions, buffer 0) form
/// a surface without holes once vertices at one position are one: every edge in an even number
/// of triangles (two on a 2-manifold; simplification may pinch a sliver near a pole into four).
bool watertight(const tinygltf::Model& m, const tinygltf::Mesh& mesh);

/// The fraction of pixels of two PNG files of one size whose RGB differ by more than
/// `tolerance` (of 255) in some channel; 1 when the sizes differ or a file cannot be read.
double fraction_differing(const std::filesystem::path& a, const std::filesystem::path& b,
                          int tolerance);

/// Maps mesh `mesh` of `assets` (4 vertices per face, in each face the corners (-1, -1),
/// (1, -1), (1, 1), (-1, 1) of its square, as the tests' cubes are built) onto a new `size` x
/// `size` texture "halves", blue on its left half and yellow on its right, through a new
/// plain material "cube_texture" for all its triangles.
void texture_with_halves(SceneAssets& assets, size_t mesh, int size);

/// The template files shipped in templates/ (absolute paths, sorted).
std::vector<std::filesystem::path> shipped_templates();

/// The name a sweep over templates gives the test of the template at `path`: its file stem with
/// every character that is not a letter or digit made '_' ("kiwi", "boiled_egg").
std::string template_test_name(const std::filesystem::path& path);

/// A template and its DS model.
struct BuiltTemplate {
  Template tmpl;
  DsModel model;
};

/// The template at `path`, loaded and built once per test process: the sweeps over every
/// template run one process per template (tests/CMakeLists.txt), and every test of the sweep in
/// it shares this build. Throws as load_template and build_model do.
const BuiltTemplate& built_template(const std::filesystem::path& path);

/// A template, its DS model (shared, built_template) and the horizontal plane through the
/// middle of the model's bounding box (the cut the accuracy tests make on every shipped
/// template).
struct MidHeightCut {
  const Template& tmpl;
  const DsModel& model;
  Plane plane;
};

/// The mid-height cut of the template at `path` (throws as built_template does).
MidHeightCut mid_height_cut(const std::filesystem::path& path);

/// Up to about `at_most` interior vertices of `cs` (off the cut segments, cut_surface < 0),
/// evenly through its vertex list, in order.
std::vector<size_t> interior_vertices(const CrossSection& cs, size_t at_most);

/// Welds the mesh's vertices by exact position; every directed edge must have exactly one
/// twin running the other way, no triangle may have two corners at one point, and the
/// triangles around each vertex must form a single fan: a closed, consistently oriented
/// 2-manifold.
::testing::AssertionResult closed_and_oriented(const ShadedMesh& mesh);

}  // namespace cutaway::test
