// Variant batches (batch/variant_batch.h): shards that partition the batch, the --shard
// notation and its refusals, FNV-1a against its published test vectors, the manifest's layout.
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "batch/variant_batch.h"

namespace cutaway {
namespace {

// Every M from 1 to 12 and count from 0 to 40: the shards are contiguous, in order, cover
// 0..count-1 exactly once, and differ in size by at most one.
TEST(VariantBatch, ShardsPartitionTheBatch) {
  for (int m = 1; m <= 12; ++m) {
    for (int count = 0; count <= 40; ++count) {
      int next = 0, smallest = count, largest = 0;
      for (int k = 1; k <= m; ++k) {
        const Shard s{k, m};
        EXPECT_EQ(s.begin(count), next) << k << "/" << m << " of " << count;
        next = s.end(count);
        smallest = std::min(smallest, s.end(count) - s.begin(count));
        largest = std::max(largest, s.end(count) - s.begin(count));
      }
      EXPECT_EQ(next, count) << m;
      EXPECT_LE(largest - smallest, 1) << m << " of " << count;
    }
  }
  // No overflow at the limits: the last of the most shards of the largest count.
  const Shard last{kMaxShards, kMaxShards};
  EXPECT_EQ(last.end(100000), 100000);
  EXPECT_EQ(last.begin(100000), 99999);
}

TEST(VariantBatch, ParsesTheShardNotation) {
  const Outcome<Shard> s = parse_shard("3/8");
  ASSERT_TRUE(s);
  EXPECT_EQ(s->k, 3);
  EXPECT_EQ(s->m, 8);
  ASSERT_TRUE(parse_shard("100000/100000"));
  ASSERT_TRUE(parse_shard("1/1"));
  for (const char* bad : {"",     "/",      "3",     "3/",       "/8",        "0/8",
                          "9/8",  "3/0",    "-1/8",  "3/-8",     "+3/8",      " 3/8",
                          "3/8 ", "3.0/8",  "3/8/9", "1/100001", "1/9999999", "99999999999/1",
                          "3\\8", "three/8"}) {
    const Outcome<Shard> r = parse_shard(bad);
    ASSERT_FALSE(r) << bad;
    EXPECT_NE(r.reason().find("must be K/M"), std::string::npos) << r.reason();
  }
}

// FNV-1a 64 test vectors (Fowler, Noll, Vo: the offset basis for the empty input).
TEST(VariantBatch, Fnv1aMatchesItsTestVectors) {
  EXPECT_EQ(fnv1a64(""), 0xcbf29ce484222325ULL);
  EXPECT_EQ(fnv1a64("a"), 0xaf63dc4c8601ec8cULL);
  EXPECT_EQ(fnv1a64("foobar"), 0x85944171f73967e8ULL);
  EXPECT_NE(fnv1a64(std::string("a\0b", 3)), fnv1a64("ab"));  // every byte counts, NUL too
}

TEST(VariantBatch, ManifestListsEveryRecord) {
  const std::vector<VariantRecord> records = {{"kiwi-4.glb", 4, 0xdf52bd8c9272b6ffULL, 82900, 24},
                                              {"kiwi-5.glb", 5, 0x1ULL, 10, 0}};
  EXPECT_EQ(variant_manifest("kiwi", std::nullopt, records),
            "{\"template\": \"kiwi\", \"variants\": [\n"
            "  {\"file\": \"kiwi-4.glb\", \"seed\": 4, \"template\": \"kiwi\", \"fnv1a64\": "
            "\"df52bd8c9272b6ff\", \"ds_faces\": 82900, \"folds\": 24},\n"
            "  {\"file\": \"kiwi-5.glb\", \"seed\": 5, \"template\": \"kiwi\", \"fnv1a64\": "
            "\"0000000000000001\", \"ds_faces\": 10, \"folds\": 0}\n"
            "]}\n");
  EXPECT_EQ(variant_manifest("kiwi", Shard{2, 3}, {}),
            "{\"template\": \"kiwi\", \"shard\": \"2/3\", \"variants\": [\n]}\n");
}

}  // namespace
}  // namespace cutaway
