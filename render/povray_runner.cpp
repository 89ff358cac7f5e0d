#include "render/povray_runner.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <sys/wait.h>

#include "base/atomic_file.h"
#include "base/child_process.h"
#include "base/error.h"

namespace cutaway {

namespace {

namespace fs = std::filesystem;

constexpr int kTailLines = 15;  // lines of it quoted in an error

}  // namespace

void render_povray(const fs::path& pov_file, const fs::path& png_out, int width, int height,
                   const PovrayOptions& options) {
  if (width < 1 || width > 16384 || height < 1 || height > 16384) {
    throw InternalError("render_povray: image size " + std::to_string(width) + "x" +
                        std::to_string(height) + " outside 1..16384");
  }
  if (options.quality < 0 || options.quality > 11) {
    throw InternalError("render_povray: quality " + std::to_string(options.quality) +
                        " outside 0..11");
  }
  if (options.threads < 0) {
    throw InternalError("render_povray: threads must be >= 0");
  }
  const std::string exe =
      find_executable(options.executable, "install POV-Ray 3.7 (scripts/install-deps.sh "
                                          "installs the Debian package povray)");
  const std::string scene = read_file_bytes(pov_file);

  TempDir dir("cutaway-povray-");
  {
    std::ofstream out(dir.path() / "scene.pov", std::ios::binary);
    out << scene;
    if (!out.flush()) {
      throw EnvironmentError("cannot write the scene into " + dir.path().string());
    }
  }

  std::vector<std::string> args = {options.executable,
                                   "+Iscene.pov",
                                   "+Oscene.png",
                                   "+FN",
                                   "+W" + std::to_string(width),
                                   "+H" + std::to_string(height),
                                   "-D",
                                   "-P",
                                   "-V",
                                   "-GS",
                                   "-GR",
                                   "+Q" + std::to_string(options.quality),
                                   "File_Gamma=sRGB"};
  if (options.antialias) {
    args.insert(args.end(), {"+A0.3", "+AM2", "+R3"});
  } else {
    args.push_back("-A");
  }
  if (options.threads > 0) args.push_back("+WT" + std::to_string(options.threads));
  // Files the scene names (image_map textures) are found beside it.
  args.push_back("+L" + fs::absolute(pov_file).parent_path().string());

  const ChildResult run = run_child(dir.path(), exe, args);
  const fs::path image = dir.path() / "scene.png";
  const bool exited_ok = WIFEXITED(run.status) && WEXITSTATUS(run.status) == 0;
  if (!exited_ok || !fs::is_regular_file(image) || fs::file_size(image) == 0) {
    std::string how;
    if (WIFEXITED(run.status)) {
      how = "exited with status " + std::to_string(WEXITSTATUS(run.status));
    } else if (WIFSIGNALED(run.status)) {
      how = "was killed by signal " + std::to_string(WTERMSIG(run.status));
    }
    if (exited_ok) how = "wrote no image";
    throw EnvironmentError("POV-Ray failed on " + pov_file.string() + " (" + how + "):\n" +
                           last_lines(run.output, kTailLines));
  }
  write_file_atomically(png_out, read_file_bytes(image));
}

}  // namespace cutaway
