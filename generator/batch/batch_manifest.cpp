#include "batch/batch_manifest.h"

#include <algorithm>
#include <cerrno>
#include <map>
#include <optional>
#include <regex>
#include <sstream>
#include <vector>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "base/error.h"
#include "base/file_read.h"
#include "base/folder.h"
#include "base/hash.h"

namespace cutaway {

namespace {

namespace fs = std::filesystem;

/// The largest manifest or batch index read back (a batch of a million assets writes about
/// 500 MB of manifest lines; ours are far below).
constexpr uint64_t kMaxManifestBytes = uint64_t{1} << 30;

/// The bytes of our own file `path` (a manifest, the batch index), not through a link, at most
/// kMaxManifestBytes; nullopt when there is none (or not a regular file).
/// @throws FileReadError when it is there but cannot be read or is too large
std::optional<std::string> read_own_file(const fs::path& path) {
  try {
    return Folder::open(path.parent_path(), false)
        .read(path.filename().string(), kMaxManifestBytes);
  } catch (const FileReadError& e) {
    if (e.rule() == "does not exist") return std::nullopt;
    throw;
  } catch (const EnvironmentError&) {  // the folder itself is not there
    return std::nullopt;
  }
}

/// 16 hex digits as a number; none when the text is not that.
std::optional<uint64_t> parse_hex64(const std::string& text) {
  if (text.size() != 16 || text.find_first_not_of("0123456789abcdef") != std::string::npos)
    return std::nullopt;
  return std::stoull(text, nullptr, 16);
}

/// A plain file name (no folder, not hidden): what a record may name in the output folder.
bool plain_file_name(const std::string& name) { return plain_name(name) && name[0] != '.'; }

/// The FNV-1a hash of the regular file `name` in `folder` (a link is not followed), read a
/// mebibyte at a time so that any file size costs the same memory; nullopt when it is not a
/// regular file or cannot be read.
std::optional<uint64_t> file_fnv1a64(const Folder& folder, const std::string& name) {
  int fd = -1;
  try {
    fd = folder.open_regular(name);
  } catch (const FileReadError&) {
    return std::nullopt;
  }
  std::vector<char> chunk(size_t{1} << 20);
  uint64_t hash = kFnv1a64Start;
  for (;;) {
    const ssize_t n = ::read(fd, chunk.data(), chunk.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      ::close(fd);
      return std::nullopt;
    }
    if (n == 0) break;
    hash = fnv1a64(std::string_view(chunk.data(), static_cast<size_t>(n)), hash);
  }
  ::close(fd);
  return hash;
}

}  // namespace

std::string shard_file_name(const std::string& stem, const std::optional<Shard>& shard) {
  if (!shard) return stem + ".jsonl";
  return stem + "-" + std::to_string(shard->k) + "-of-" + std::to_string(shard->m) + ".jsonl";
}

std::string manifest_line(const AssetRecord& r) {
  nlohmann::ordered_json j = {{"file", r.file},          {"template", r.template_name},
                              {"seed", r.seed},          {"cut", r.cut},
                              {"pieces", r.pieces},      {"triangles", r.triangles},
                              {"vertices", r.vertices},  {"volume_m3", r.volume_m3},
                              {"fnv1a64", hex64(r.hash)}};
  if (!r.stone_pieces.empty()) j["stone_pieces"] = r.stone_pieces;
  if (!r.model.empty()) {
    j["model"] = r.model;
    j["model_fnv1a64"] = hex64(r.model_hash);
  }
  if (!r.thumbnail.empty()) {
    j["thumbnail"] = r.thumbnail;
    j["thumbnail_fnv1a64"] = hex64(r.thumbnail_hash);
  }
  if (!r.volume.empty()) {
    j["volume"] = nlohmann::ordered_json::array();
    for (const auto& [name, hash] : r.volume)
      j["volume"].push_back({{"file", name}, {"fnv1a64", hex64(hash)}});
  }
  j["inputs"] = hex64(r.inputs);
  return j.dump() + "\n";
}

Outcome<AssetRecord> parse_manifest_line(std::string_view line) {
  const nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return Outcome<AssetRecord>::none("not a JSON object");
  AssetRecord r;
  try {
    r.file = j.at("file").get<std::string>();
    r.template_name = j.at("template").get<std::string>();
    r.seed = j.at("seed").get<uint64_t>();
    r.cut = j.at("cut").get<std::string>();
    r.pieces = j.at("pieces").get<size_t>();
    r.triangles = j.at("triangles").get<size_t>();
    r.vertices = j.at("vertices").get<size_t>();
    r.volume_m3 = j.at("volume_m3").get<double>();
    const auto hash = parse_hex64(j.at("fnv1a64").get<std::string>());
    const auto inputs = parse_hex64(j.at("inputs").get<std::string>());
    if (!hash || !inputs) return Outcome<AssetRecord>::none("a hash is not 16 hex digits");
    r.hash = *hash;
    r.inputs = *inputs;
    if (j.contains("stone_pieces")) {
      for (const auto& q : j.at("stone_pieces")) {
        const size_t piece = q.get<size_t>();
        if (piece >= r.pieces || (!r.stone_pieces.empty() && piece <= r.stone_pieces.back()))
          return Outcome<AssetRecord>::none("stone_pieces are not increasing piece indices");
        r.stone_pieces.push_back(piece);
      }
    }
    if (j.contains("model")) {
      r.model = j.at("model").get<std::string>();
      const auto h = parse_hex64(j.at("model_fnv1a64").get<std::string>());
      if (!h) return Outcome<AssetRecord>::none("model_fnv1a64 is not 16 hex digits");
      r.model_hash = *h;
    }
    if (j.contains("thumbnail")) {
      r.thumbnail = j.at("thumbnail").get<std::string>();
      const auto h = parse_hex64(j.at("thumbnail_fnv1a64").get<std::string>());
      if (!h) return Outcome<AssetRecord>::none("thumbnail_fnv1a64 is not 16 hex digits");
      r.thumbnail_hash = *h;
    }
    if (j.contains("volume")) {
      for (const auto& f : j.at("volume")) {
        const auto h = parse_hex64(f.at("fnv1a64").get<std::string>());
        if (!h) return Outcome<AssetRecord>::none("a volume fnv1a64 is not 16 hex digits");
        r.volume.emplace_back(f.at("file").get<std::string>(), *h);
      }
    }
  } catch (const nlohmann::json::exception& e) {
    return Outcome<AssetRecord>::none(std::string("a field is missing or of the wrong type: ") +
                                      e.what());
  }
  for (const std::string* name : {&r.file, &r.model, &r.thumbnail})
    if (!name->empty() && !plain_file_name(*name))
      return Outcome<AssetRecord>::none("a file name is not a plain name in the folder");
  for (const auto& [name, hash] : r.volume)
    if (!plain_file_name(name))
      return Outcome<AssetRecord>::none("a file name is not a plain name in the folder");
  if (r.file.empty()) return Outcome<AssetRecord>::none("the file name is empty");
  return r;
}

std::vector<AssetRecord> read_manifest(const fs::path& path, size_t* bad_lines) {
  std::vector<AssetRecord> out;
  const std::optional<std::string> bytes = read_own_file(path);
  if (!bytes) return out;
  std::istringstream in(*bytes);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    Outcome<AssetRecord> r = parse_manifest_line(line);
    if (r) {
      out.push_back(std::move(*r));
    } else if (bad_lines) {
      ++*bad_lines;
    }
  }
  return out;
}

bool record_files_intact(const AssetRecord& r, const fs::path& dir) {
  std::vector<std::pair<const std::string*, uint64_t>> files = {
      {&r.file, r.hash}, {&r.model, r.model_hash}, {&r.thumbnail, r.thumbnail_hash}};
  for (const auto& [name, hash] : r.volume) files.emplace_back(&name, hash);
  Folder folder;
  try {
    folder = Folder::open(dir, false);
  } catch (const EnvironmentError&) {
    return false;
  }
  for (const auto& [name, hash] : files) {
    if (name->empty()) continue;
    // A link, or anything but a regular file, is damaged: never followed, never read.
    const std::optional<uint64_t> h = file_fnv1a64(folder, *name);
    if (!h || *h != hash) return false;
  }
  return true;
}

std::string batch_index_text(const Batch& batch, const BatchPlan& plan) {
  // One asset per line, so that the file reads and diffs well.
  std::string text =
      "{\"format\":\"cutaway-batch-index/1\",\"batch\":" + nlohmann::json(batch.name).dump() +
      ",\"units\":" + std::to_string(plan.units.size()) + ",\"assets\":[\n";
  for (size_t i = 0; i < plan.assets.size(); ++i) {
    const BatchAsset& a = plan.assets[i];
    const nlohmann::ordered_json j = {
        {"stem", a.stem}, {"inputs", hex64(a.inputs)}, {"sample", a.sample}};
    text += j.dump() + (i + 1 < plan.assets.size() ? ",\n" : "\n");
  }
  return text + "]}\n";
}

Outcome<BatchIndex> read_batch_index(const fs::path& dir) {
  const fs::path path = dir / "batch.json";
  std::optional<std::string> bytes;
  try {
    bytes = read_own_file(path);
  } catch (const FileReadError& e) {
    return Outcome<BatchIndex>::none(e.what());
  }
  if (!bytes)
    return Outcome<BatchIndex>::none(path.string() + " is missing (not a batch output folder)");
  const nlohmann::json j = nlohmann::json::parse(*bytes, nullptr, false);
  BatchIndex index;
  try {
    if (j.is_discarded() || j.at("format") != "cutaway-batch-index/1")
      return Outcome<BatchIndex>::none(path.string() + " is not a cutaway-batch-index/1 file");
    index.batch = j.at("batch").get<std::string>();
    index.units = j.at("units").get<size_t>();
    for (const auto& a : j.at("assets")) {
      const auto inputs = parse_hex64(a.at("inputs").get<std::string>());
      if (!inputs) return Outcome<BatchIndex>::none(path.string() + ": a bad inputs hash");
      index.assets.push_back(
          {a.at("stem").get<std::string>(), *inputs, a.at("sample").get<bool>()});
    }
  } catch (const nlohmann::json::exception& e) {
    return Outcome<BatchIndex>::none(path.string() + ": " + e.what());
  }
  return index;
}

MergeReport merge_manifests(const BatchIndex& index, const fs::path& dir) {
  MergeReport report;
  static const std::regex shard_name(R"(manifest-[0-9]+-of-[0-9]+\.jsonl)");
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (e.symlink_status(ec).type() == fs::file_type::regular && std::regex_match(name, shard_name))
      report.manifests.push_back(name);
  }
  if (report.manifests.empty() &&
      fs::symlink_status(dir / "manifest.jsonl", ec).type() == fs::file_type::regular)
    report.manifests.push_back("manifest.jsonl");
  std::sort(report.manifests.begin(), report.manifests.end());
  std::map<std::string, std::vector<AssetRecord>> by_file;
  for (const std::string& name : report.manifests)
    for (AssetRecord& r : read_manifest(dir / name, &report.bad_lines))
      by_file[r.file].push_back(std::move(r));
  for (const IndexedAsset& a : index.assets) {
    const std::string file = a.stem + ".glb";
    auto it = by_file.find(file);
    if (it == by_file.end()) {
      report.missing.push_back(a.stem);
      continue;
    }
    std::vector<AssetRecord> listed = std::move(it->second);
    by_file.erase(it);
    std::erase_if(listed, [&](const AssetRecord& r) { return r.inputs != a.inputs; });
    if (listed.empty()) {  // listed only by a run of other inputs (another batch file)
      report.missing.push_back(a.stem);
      continue;
    }
    const bool same = std::all_of(listed.begin(), listed.end(),
                                  [&](const AssetRecord& r) { return r == listed.front(); });
    if (!same) {
      report.conflicting.push_back(a.stem);
      continue;
    }
    if (listed.size() > 1) report.duplicated.push_back(a.stem);
    if (!record_files_intact(listed.front(), dir)) {
      report.damaged.push_back(a.stem);
      continue;
    }
    report.records.push_back(std::move(listed.front()));
  }
  for (const auto& [file, records] : by_file) report.unknown.push_back(file);
  return report;
}

std::string merged_manifest(const MergeReport& report) {
  CUTAWAY_CHECK(report.complete());
  std::string lines;
  for (const AssetRecord& r : report.records) lines += manifest_line(r);
  return lines;
}

}  // namespace cutaway
