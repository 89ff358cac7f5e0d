// `cutaway variants` end to end on the tomato (its variants differ in fold count and fold
// shapes): glb files that pass the Khronos validator, manifest.json fields and content hashes,
// determinism, distinct seeds, shards that add up to one unsharded run, the contact sheet, no
// progress bar without a terminal, refusals of bad --shard that write nothing; and
// `model --seed`.
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "batch/variant_batch.h"
#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

uint32_t big_endian_u32(const std::string& s, size_t at) {
  uint32_t v = 0;
  for (size_t i = 0; i < 4; ++i) v = v << 8 | static_cast<unsigned char>(s.at(at + i));
  return v;
}

/// One manifest entry, its fields as text.
using Entry = std::map<std::string, std::string>;

std::vector<Entry> entries(const std::string& manifest) {
  std::vector<Entry> out;
  const std::regex object(R"(\{"file"[^}]*\})"), field(R"re("(\w+)": ("[^"]*"|[0-9.]+))re");
  for (auto it = std::sregex_iterator(manifest.begin(), manifest.end(), object);
       it != std::sregex_iterator(); ++it) {
    Entry e;
    const std::string text = it->str();
    for (auto f = std::sregex_iterator(text.begin(), text.end(), field);
         f != std::sregex_iterator(); ++f) {
      std::string value = (*f)[2];
      if (value.front() == '"') value = value.substr(1, value.size() - 2);
      e[(*f)[1]] = value;
    }
    out.push_back(e);
  }
  return out;
}

const std::string kTomatoTemplate = "templates/tomato.yaml";

test::RunResult variants(const fs::path& dir, int count, int seed,
                         std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {"variants", test::source_path(kTomatoTemplate).string(),
                                   "--count",  std::to_string(count),
                                   "--seed",   std::to_string(seed),
                                   "-o",       dir.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  return test::run_cutaway(args);
}

TEST(VariantsCommand, WritesValidVariantsAManifestAndAContactSheetDeterministically) {
  const fs::path a = test::fresh_dir("cli_variants_a"), b = test::fresh_dir("cli_variants_b");
  const test::RunResult ra = variants(a, 4, 0, {"--sheet", "4"});
  ASSERT_EQ(ra.exit_code, 0) << ra.err;
  EXPECT_EQ(ra.err.find("variants: ["), std::string::npos) << "a progress bar without a terminal";
  const std::vector<std::string> files = {"contact-sheet.png", "manifest.json", "tomato-0.glb",
                                          "tomato-1.glb",      "tomato-2.glb",  "tomato-3.glb"};
  ASSERT_EQ(test::files_in(a), files);

  // manifest.json: one entry per variant with file, seed, template, hash, DS faces, folds.
  const std::string manifest = slurp(a / "manifest.json");
  EXPECT_NE(manifest.find("\"template\": \"tomato\""), std::string::npos) << manifest;
  const std::vector<Entry> e = entries(manifest);
  ASSERT_EQ(e.size(), 4u) << manifest;
  std::set<std::string> glbs;
  for (int i = 0; i < 4; ++i) {
    const std::string file = "tomato-" + std::to_string(i) + ".glb";
    EXPECT_EQ(e[i].at("file"), file);
    EXPECT_EQ(e[i].at("seed"), std::to_string(i));
    EXPECT_EQ(e[i].at("template"), "tomato");
    const std::string bytes = slurp(a / file);
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(fnv1a64(bytes)));
    EXPECT_EQ(e[i].at("fnv1a64"), hex) << file;
    EXPECT_GT(std::stoul(e[i].at("ds_faces")), 10000u);
    EXPECT_EQ(e[i].count("seconds"), 0u) << "timings make two runs' manifests differ";
    glbs.insert(bytes);
  }
  EXPECT_EQ(glbs.size(), 4u) << "distinct seeds gave identical glb files";
  for (const char* file : {"tomato-0.glb", "tomato-3.glb"}) {
    const test::GltfReport v = test::validate_gltf(a / file);
    EXPECT_EQ(v.errors, 0) << file << ": " << v.output;
  }

  // Contact sheet: 4 tiles of 256 pixels in 2 x 2 cells, 16-pixel margins.
  const std::string png = slurp(a / "contact-sheet.png");
  ASSERT_GT(png.size(), 24u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  EXPECT_EQ(big_endian_u32(png, 16), 2u * 256 + 3 * 16);
  EXPECT_EQ(big_endian_u32(png, 20), 2u * 256 + 3 * 16);

  // The same seeds again (no sheet): byte-identical glb files and manifest.
  const test::RunResult rb = variants(b, 4, 0, {"--sheet", "0"});
  ASSERT_EQ(rb.exit_code, 0) << rb.err;
  for (int i = 0; i < 4; ++i) {
    const std::string file = "tomato-" + std::to_string(i) + ".glb";
    EXPECT_TRUE(slurp(a / file) == slurp(b / file)) << file << " differs between two runs";
  }
  EXPECT_EQ(slurp(b / "manifest.json"), manifest);
  EXPECT_FALSE(fs::exists(b / "contact-sheet.png"));

  // Shards 1/2 and 2/2 together: the unsharded run's files with the same hashes.
  std::vector<Entry> union_entries;
  std::set<std::string> union_files;
  for (const char* shard : {"1/2", "2/2"}) {
    const fs::path s = test::fresh_dir(std::string("cli_variants_shard") + shard[0]);
    const test::RunResult rs = variants(s, 4, 0, {"--sheet", "0", "--shard", shard});
    ASSERT_EQ(rs.exit_code, 0) << rs.err;
    const std::string m = slurp(s / "manifest.json");
    EXPECT_NE(m.find(std::string("\"shard\": \"") + shard + "\""), std::string::npos) << m;
    const std::vector<Entry> se = entries(m);
    EXPECT_EQ(se.size(), 2u) << m;
    for (const Entry& x : se) {
      union_entries.push_back(x);
      EXPECT_TRUE(slurp(s / x.at("file")) == slurp(a / x.at("file"))) << x.at("file");
    }
    for (const std::string& f : test::files_in(s))
      if (f != "manifest.json") union_files.insert(f);
  }
  EXPECT_EQ(union_files, (std::set<std::string>(files.begin() + 2, files.end())));
  ASSERT_EQ(union_entries.size(), e.size());
  for (size_t i = 0; i < e.size(); ++i) {
    EXPECT_EQ(union_entries[i].at("file"), e[i].at("file"));
    EXPECT_EQ(union_entries[i].at("fnv1a64"), e[i].at("fnv1a64"));
  }
}

TEST(VariantsCommand, RefusesBadShardsWritingNothing) {
  for (const std::string shard : {"0/2", "3/2", "2", "1/0", "a/b", "1/2/3", "-1/2", ""}) {
    const fs::path dir = test::fresh_dir("cli_variants_bad_shard");
    const fs::path out = dir / "out";
    const test::RunResult r = variants(out, 2, 0, {"--shard", shard});
    EXPECT_EQ(r.exit_code, 2) << "--shard '" << shard << "': " << r.err;
    EXPECT_NE(r.err.find("--shard"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << "--shard '" << shard << "' wrote " << out;
  }
}

TEST(VariantsCommand, ModelSeedBuildsAVariant) {
  const fs::path dir = test::fresh_dir("cli_model_seed");
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{}, std::vector<std::string>{"--seed", "3"}}) {
    std::vector<std::string> args = {"model", test::source_path(kTomatoTemplate).string(), "-o",
                                     (dir / (extra.empty() ? "plain.glb" : "seed.glb")).string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const test::RunResult r = test::run_cutaway(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  EXPECT_FALSE(slurp(dir / "plain.glb") == slurp(dir / "seed.glb"));
  // The variant of a seed is the one `variants` writes for that seed.
  const fs::path v = test::fresh_dir("cli_model_seed_variants");
  ASSERT_EQ(variants(v, 1, 3, {"--sheet", "0"}).exit_code, 0);
  EXPECT_TRUE(slurp(dir / "seed.glb") == slurp(v / "tomato-3.glb"));
}

}  // namespace
}  // namespace cutaway
