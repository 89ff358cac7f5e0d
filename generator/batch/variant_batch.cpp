#include "batch/variant_batch.h"

namespace cutaway {

Outcome<Shard> parse_shard(std::string_view text) {
  const std::string rule =
      quoted(text) + " must be K/M with whole numbers 1 <= K <= M <= " + std::to_string(kMaxShards);
  const size_t slash = text.find('/');
  if (slash == std::string_view::npos) return Outcome<Shard>::none(rule);
  // A whole number of at most six decimal digits, or -1.
  const auto number = [](std::string_view part) {
    if (part.empty() || part.size() > 6 || part.find_first_not_of("0123456789") != part.npos)
      return -1;
    int value = 0;
    for (const char c : part) value = 10 * value + (c - '0');
    return value;
  };
  const Shard s{number(text.substr(0, slash)), number(text.substr(slash + 1))};
  if (s.k < 1 || s.m < 1 || s.k > s.m || s.m > kMaxShards) return Outcome<Shard>::none(rule);
  return s;
}

std::string variant_manifest(const std::string& name, const std::optional<Shard>& shard,
                             const std::vector<VariantRecord>& records) {
  std::string out = "{\"template\": \"" + name + "\", ";
  if (shard)
    out += "\"shard\": \"" + std::to_string(shard->k) + "/" + std::to_string(shard->m) + "\", ";
  out += "\"variants\": [\n";
  for (size_t i = 0; i < records.size(); ++i) {
    const VariantRecord& r = records[i];
    out += "  {\"file\": \"" + r.file + "\", \"seed\": " + std::to_string(r.seed) +
           ", \"template\": \"" + name + "\", \"fnv1a64\": \"" + hex64(r.hash) +
           "\", \"ds_faces\": " + std::to_string(r.ds_faces) +
           ", \"folds\": " + std::to_string(r.folds) + "}" + (i + 1 < records.size() ? "," : "") +
           "\n";
  }
  out += "]}\n";
  return out;
}

}  // namespace cutaway
