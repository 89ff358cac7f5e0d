// The cut cache: entries read back exactly, damaged ones rebuilt, the size bound kept by
// evicting the least recently used, one folder shared by runs at once, and scenes and batches
// that give the same bytes with and without it.
#include "cache/cut_cache.h"

#include <atomic>
#include <cstring>
#include <functional>
#include <limits>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <glm/trigonometric.hpp>

#include "base/hash.h"
#include "cache/cached_cut.h"
#include "cache/cached_placement.h"
#include "export/gltf_export.h"
#include "io/scene_parser.h"
#include "scene/scene_builder.h"
#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

/// A payload of `bytes` bytes that depends on `key`.
std::string payload_of(const std::string& key, size_t bytes) {
  std::string p(bytes, '\0');
  uint64_t h = fnv1a64(key);
  for (char& c : p) {
    h = h * 6364136223846793005ULL + 1442695040888963407ULL;
    c = static_cast<char>(h >> 56);
  }
  return p;
}

/// Every entry file of a cache folder.
std::vector<fs::path> entries(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && e.path().extension() == ".cut") out.push_back(e.path());
  return out;
}

TEST(CutCache, ReadsBackWhatItStoredAndNothingForAnotherKey) {
  CutCache cache({test::fresh_dir("cut_cache"), kDefaultCutCacheBytes, {}});
  EXPECT_FALSE(cache.load("a"));
  cache.store("a", payload_of("a", 1000));
  cache.store("b", "");
  EXPECT_EQ(cache.load("a"), payload_of("a", 1000));
  EXPECT_EQ(cache.load("b"), "");
  EXPECT_FALSE(cache.load("c"));
  const CutCacheStats s = cache.stats();
  EXPECT_EQ(s.hits, 2);
  EXPECT_EQ(s.misses, 2);
  EXPECT_EQ(s.stored, 2);
  EXPECT_EQ(entries(cache.dir()).size(), 2u);
}

// A folder that cannot be made (here: below a regular file) is warned about once, with the
// reason, and the run goes on without storing.
TEST(CutCache, AFolderThatCannotBeMadeIsWarnedAboutOnceAndNothingIsStored) {
  const fs::path file = test::fresh_dir("cut_cache_blocked") / "a-file";
  std::ofstream(file) << "not a folder";
  std::vector<std::string> warnings;
  CutCache cache({file / "cache", kDefaultCutCacheBytes,
                  [&](const std::string& w) { warnings.push_back(w); }});
  cache.store("a", payload_of("a", 100));
  cache.store("b", payload_of("b", 100));
  EXPECT_FALSE(cache.load("a"));
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("cannot create the folder"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("Not a directory"), std::string::npos) << warnings[0];
  EXPECT_EQ(cache.stats().stored, 0);
}

TEST(CutCache, DamagedEntriesAreReportedRemovedAndNotRead) {
  std::vector<std::string> warnings;
  CutCache cache({test::fresh_dir("cut_cache"), kDefaultCutCacheBytes,
                  [&](const std::string& w) { warnings.push_back(w); }});
  for (const char* key : {"flipped", "truncated", "emptied"}) {
    cache.store(key, payload_of(key, 5000));
  }
  for (const fs::path& file : entries(cache.dir())) {
    std::string bytes = test::read_file(file);
    if (bytes.find("flipped") != std::string::npos) bytes[bytes.size() / 2] ^= 0x10;
    if (bytes.find("truncated") != std::string::npos) bytes.resize(bytes.size() - 9);
    if (bytes.find("emptied") != std::string::npos) bytes.clear();
    std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
  }
  for (const char* key : {"flipped", "truncated", "emptied"}) EXPECT_FALSE(cache.load(key)) << key;
  EXPECT_EQ(cache.stats().damaged, 3);
  ASSERT_EQ(warnings.size(), 3u);
  EXPECT_NE(warnings[0].find("damaged"), std::string::npos) << warnings[0];
  EXPECT_TRUE(entries(cache.dir()).empty());
  // Made again, it is read back.
  cache.store("flipped", payload_of("flipped", 5000));
  EXPECT_EQ(cache.load("flipped"), payload_of("flipped", 5000));
}

// An entry written by an earlier cutaway (version 1: the key first, an FNV-1a check) is not
// damaged: it is not read, not warned about, and the next store replaces it.
TEST(CutCache, AnEntryOfTheFirstVersionIsReplacedWithoutAWarning) {
  std::vector<std::string> warnings;
  const fs::path dir = test::fresh_dir("cut_cache_v1");
  CutCache cache(
      {dir, kDefaultCutCacheBytes, [&](const std::string& w) { warnings.push_back(w); }});
  // The entry's file, where the cache names it, rewritten as version 1 wrote it.
  cache.store("old", payload_of("old", 300));
  ASSERT_EQ(entries(dir).size(), 1u);
  std::ofstream(entries(dir)[0], std::ios::binary | std::ios::trunc) << "cutaway cut cache 1\n"
                                                                     << payload_of("old", 300);
  EXPECT_FALSE(cache.load("old"));
  EXPECT_TRUE(warnings.empty());
  EXPECT_EQ(cache.stats().damaged, 0);
  EXPECT_EQ(cache.stats().misses, 1);
  cache.store("old", payload_of("old", 5000));
  EXPECT_EQ(cache.load("old"), payload_of("old", 5000));
  EXPECT_EQ(entries(dir).size(), 1u);
}

TEST(CutCache, KeepsItsBoundByEvictingTheLeastRecentlyUsed) {
  // Entries of about 100 kB under a bound of 280 kB: the third store evicts down to 210 kB.
  CutCache cache({test::fresh_dir("cut_cache"), 280'000, {}});
  cache.store("old but read", payload_of("1", 100'000));
  cache.store("not read", payload_of("2", 100'000));
  const auto now = fs::file_time_type::clock::now();
  for (const fs::path& file : entries(cache.dir())) {
    const bool first = test::read_file(file).find("old but read") != std::string::npos;
    fs::last_write_time(file, now - std::chrono::seconds(first ? 100 : 50));
  }
  ASSERT_TRUE(cache.load("old but read"));  // now the most recently used
  cache.store("new", payload_of("3", 100'000));
  EXPECT_EQ(cache.stats().evicted, 1);
  EXPECT_TRUE(cache.load("old but read"));
  EXPECT_TRUE(cache.load("new"));
  EXPECT_FALSE(cache.load("not read"));
}

TEST(CutCache, RunsSharingOneFolderAtOnceReadWholeEntriesOnly) {
  // Four caches on one folder (as four runs), storing and reading the same keys at once, with
  // a bound that makes them evict each other's entries meanwhile.
  const fs::path dir = test::fresh_dir("cut_cache");
  std::atomic<int> wrong{0}, warned{0}, hits{0};
  std::vector<std::thread> runs;
  for (int t = 0; t < 4; ++t) {
    runs.emplace_back([&, t] {
      CutCache cache({dir, 1'500'000, [&](const std::string& w) {
                        if (++warned == 1) ADD_FAILURE() << w;
                      }});
      for (int round = 0; round < 3; ++round) {
        for (int k = 0; k < 24; ++k) {
          const std::string key = "key " + std::to_string((k + 7 * t) % 24);
          const std::string expected = payload_of(key, 60'000 + 1000 * ((k + 7 * t) % 24));
          if (std::optional<std::string> got = cache.load(key)) {
            wrong += *got != expected;
            ++hits;
          } else {
            cache.store(key, expected);
          }
        }
      }
    });
  }
  for (std::thread& run : runs) run.join();
  EXPECT_EQ(wrong.load(), 0);
  EXPECT_EQ(warned.load(), 0);
  EXPECT_GT(hits.load(), 0);
  for (const auto& e : fs::recursive_directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
}

TEST(CutCacheKey, EveryInputThatChangesTheCutChangesTheKey) {
  ObjectCutOptions cut;
  cut.cut.type = CutType::Slices;
  cut.cut.thickness_m = 0.008;
  const CollisionShapeOptions collision;
  const CutKeyInputs base{
      1, 1.0, 2, "i0_tomato_0", "backend=cpu cube=16 directions=adaptive", &cut, &collision};
  const std::string key = cut_cache_key(base);
  EXPECT_EQ(key, cut_cache_key(base));
  std::vector<std::string> keys;
  auto with = [&](auto change) {
    CutKeyInputs in = base;
    ObjectCutOptions c = cut;
    CollisionShapeOptions h = collision;
    in.cut = &c;
    in.collision = &h;
    change(in, c, h);
    keys.push_back(cut_cache_key(in));
  };
  with([](CutKeyInputs& in, ObjectCutOptions&, CollisionShapeOptions&) { in.template_hash = 3; });
  with([](CutKeyInputs& in, ObjectCutOptions&, CollisionShapeOptions&) {
    in.variation_amount = 1.0 + 1e-15;
  });
  with([](CutKeyInputs& in, ObjectCutOptions&, CollisionShapeOptions&) { in.variant_seed = 3; });
  with([](CutKeyInputs& in, ObjectCutOptions&, CollisionShapeOptions&) { in.object += "x"; });
  with([](CutKeyInputs& in, ObjectCutOptions&, CollisionShapeOptions&) {
    in.diffusion = "backend=gl cube=16 directions=adaptive";
  });
  with([](CutKeyInputs& in, ObjectCutOptions&, CollisionShapeOptions&) { in.collision = nullptr; });
  with([](CutKeyInputs&, ObjectCutOptions& c, CollisionShapeOptions&) {
    c.cut.thickness_m = 0.0080000001;  // the same label, 8mm
  });
  with([](CutKeyInputs&, ObjectCutOptions& c, CollisionShapeOptions&) { c.keep = 0.5; });
  with([](CutKeyInputs&, ObjectCutOptions& c, CollisionShapeOptions&) { c.keep_seed = 9; });
  with([](CutKeyInputs&, ObjectCutOptions& c, CollisionShapeOptions&) { c.modulation_seed = 9; });
  with([](CutKeyInputs&, ObjectCutOptions& c, CollisionShapeOptions&) { c.perlin = 0; });
  with([](CutKeyInputs&, ObjectCutOptions& c, CollisionShapeOptions&) {
    c.sampling = CapSampling::Dense;
  });
  with([](CutKeyInputs&, ObjectCutOptions& c, CollisionShapeOptions&) {
    c.cap_colours = CapColours::Vertex;
  });
  with([](CutKeyInputs&, ObjectCutOptions& c, CollisionShapeOptions&) {
    c.atlas.texels_per_m = 5000;
  });
  with([](CutKeyInputs&, ObjectCutOptions& c, CollisionShapeOptions&) {
    c.skin.power_of_two = true;
  });
  with([](CutKeyInputs&, ObjectCutOptions& c, CollisionShapeOptions&) {
    c.whole_when_missed = false;
  });
  with([](CutKeyInputs&, ObjectCutOptions&, CollisionShapeOptions& h) { h.max_corners = 64; });
  for (size_t k = 0; k < keys.size(); ++k) {
    EXPECT_NE(keys[k], key) << "change " << k;
    for (size_t j = 0; j < k; ++j) EXPECT_NE(keys[k], keys[j]) << k << " " << j;
  }
}

/// The tiny test scene, seen by a camera `orbit_deg` around the default view's direction (none:
/// the file's own view), with a narrower field of view.
Scene tiny_scene(std::optional<double> orbit_deg = std::nullopt) {
  Scene scene = load_scene(test::source_path("tests/data/scenes/tiny.yaml").string());
  if (orbit_deg) {
    const double a = glm::radians(*orbit_deg);
    const glm::dvec3 d = 0.6 * default_view_direction();
    scene.camera = SceneCamera{{std::cos(a) * d.x + std::sin(a) * d.z, d.y,
                                -std::sin(a) * d.x + std::cos(a) * d.z},
                               glm::dvec3(0.0),
                               30};
  }
  return scene;
}

/// The glTF binary of `scene` with the quick options and `cache` (null: none), cutting
/// `objects_at_once` objects side by side.
std::string scene_glb(const Scene& scene, CutCache* cache, SceneStats& st,
                      int objects_at_once = 1) {
  SceneBuildOptions options = test::quick_scene_options(CapColours::Texture);
  options.cache = cache;
  options.objects_at_once = objects_at_once;
  options.diffusion_settings = "backend=cpu cube=4 directions=adaptive";
  return scene_to_glb(build_scene(scene, scene.seed, options, &st));
}

/// The tiny test scene's glTF binary with the quick options and `cache` (null: none).
std::string tiny_scene_glb(CutCache* cache, SceneStats& st) {
  return scene_glb(tiny_scene(), cache, st);
}

TEST(CutCacheScene, CachedObjectsGiveTheSameBytesAndDamagedOnesAreCutAgain) {
  SceneStats uncached, first, second, repaired;
  const std::string without = tiny_scene_glb(nullptr, uncached);
  std::vector<std::string> warnings;
  CutCache cache({test::fresh_dir("cut_cache"), kDefaultCutCacheBytes,
                  [&](const std::string& w) { warnings.push_back(w); }});
  EXPECT_EQ(tiny_scene_glb(&cache, first), without);
  EXPECT_EQ(first.cached_objects, 0);
  EXPECT_EQ(cache.stats().stored, uncached.objects + 1);  // and the placements
  EXPECT_EQ(tiny_scene_glb(&cache, second), without);
  EXPECT_EQ(second.cached_objects, uncached.objects);
  EXPECT_EQ(second.diffused.all, 0u);     // nothing was cut
  EXPECT_TRUE(second.cached_placements);  // nor laid out and settled
  EXPECT_FALSE(first.cached_placements);
  EXPECT_EQ(second.placed, uncached.placed);
  EXPECT_EQ(second.stability_motion_m, uncached.stability_motion_m);
  // One object's entry damaged on disk: warned about, cut again, the same bytes.
  const std::vector<fs::path> files = entries(cache.dir());
  ASSERT_EQ(files.size(), static_cast<size_t>(uncached.objects + 1));
  size_t damaged = 0;
  for (const fs::path& f : files) {
    std::string bytes = test::read_file(f);
    if (bytes.find("\"object\":\"i1_") == std::string::npos) continue;
    bytes[bytes.size() / 3] ^= 0x01;
    std::ofstream(f, std::ios::binary | std::ios::trunc) << bytes;
    ++damaged;
  }
  ASSERT_EQ(damaged, 1u);
  EXPECT_EQ(tiny_scene_glb(&cache, repaired), without);
  EXPECT_EQ(repaired.cached_objects, uncached.objects - 1);
  EXPECT_TRUE(repaired.cached_placements);  // the same bytes were cut again
  EXPECT_EQ(warnings.size(), 1u);
}

// Objects cut side by side are added to the scene in order: the bytes do not depend on how
// many are cut at once, nor on whether they were read from the cache in between.
TEST(CutCacheScene, ObjectsCutSideBySideGiveTheSameBytes) {
  const Scene scene = tiny_scene();
  SceneStats one, four, three_cached;
  const std::string serial = scene_glb(scene, nullptr, one, 1);
  ASSERT_GE(one.objects, 2);
  EXPECT_EQ(scene_glb(scene, nullptr, four, 4), serial);
  EXPECT_EQ(four.pieces, one.pieces);
  EXPECT_EQ(four.diffused.all, one.diffused.all);  // the cut counts of every object, added
  CutCache cache({test::fresh_dir("cut_cache_side_by_side"), kDefaultCutCacheBytes, {}});
  SceneStats stored;
  EXPECT_EQ(scene_glb(scene, &cache, stored, 3), serial);
  EXPECT_EQ(scene_glb(scene, &cache, three_cached, 3), serial);
  EXPECT_EQ(three_cached.cached_objects, one.objects);
}

// The placements depend on the direction the camera looks from (the pieces turn their cut
// faces to it), not on its distance or field of view: a zoom reads them back; on a board, the
// side of the board the camera looks from decides (the azimuth to a quarter turn), so an orbit
// of 40 degrees reads them back too and one of 100 settles the cached pieces again; all give
// the bytes a run without the cache gives.
TEST(CutCacheScene, AZoomOrAnOrbitToTheSameSideOfABoardReadsThePlacementsBack) {
  CutCache cache({test::fresh_dir("cut_cache"), kDefaultCutCacheBytes, {}});
  SceneStats first, zoomed, zoomed_uncached, orbited, orbited_uncached, side, side_uncached;
  const auto on_board = [](Scene scene) {
    scene.container = {ContainerType::Board, 0, 0.3, 0.2, 0.02, scene.container.colour};
    return scene;
  };
  scene_glb(on_board(tiny_scene(0)), &cache, first);
  Scene zoom = on_board(tiny_scene(0));
  zoom.camera->eye *= 1.5;
  zoom.camera->fov_deg = 25;
  EXPECT_EQ(scene_glb(zoom, &cache, zoomed), scene_glb(zoom, nullptr, zoomed_uncached));
  EXPECT_EQ(zoomed.cached_objects, first.objects);
  EXPECT_TRUE(zoomed.cached_placements);
  const Scene orbit = on_board(tiny_scene(40));
  EXPECT_EQ(scene_glb(orbit, &cache, orbited), scene_glb(orbit, nullptr, orbited_uncached));
  EXPECT_TRUE(orbited.cached_placements);
  const Scene other_side = on_board(tiny_scene(100));
  EXPECT_EQ(scene_glb(other_side, &cache, side), scene_glb(other_side, nullptr, side_uncached));
  EXPECT_EQ(side.cached_objects, first.objects);
  EXPECT_FALSE(side.cached_placements);
  EXPECT_GT(side.simulated_seconds, 0);
}

// A bowl is the same from every side: the pile is laid out for the camera turned to the front
// and turned back with it, so an orbit reads the placements back from the cache, and every
// piece lies where the front view's piece lies, turned by the orbit's angle.
TEST(CutCacheScene, AnOrbitRoundABowlTurnsThePileWithTheCamera) {
  CutCache cache({test::fresh_dir("cut_cache_bowl_orbit"), kDefaultCutCacheBytes, {}});
  SceneBuildOptions options = test::quick_scene_options(CapColours::Texture);
  options.diffusion_settings = "backend=cpu cube=4 directions=adaptive";
  const Scene front = tiny_scene(0), orbit = tiny_scene(40);
  SceneStats st_front, st_orbit, st_cached;
  const SceneAssets a = build_scene(front, front.seed, options, &st_front);
  const SceneAssets b = build_scene(orbit, orbit.seed, options, &st_orbit);
  ASSERT_EQ(a.instances.size(), b.instances.size());
  const glm::dquat turn = glm::angleAxis(glm::radians(40.0), glm::dvec3(0, 1, 0));
  for (size_t k = 1; k < a.instances.size(); ++k) {  // the bowl first, where it was
    if (a.instances[k].backdrop) continue;           // staging that follows the camera
    const AssetInstance& p = a.instances[k];
    const AssetInstance& q = b.instances[k];
    EXPECT_LT(glm::length(turn * p.translation - q.translation), 1e-9) << k;
    EXPECT_GT(std::abs(glm::dot(turn * p.rotation, q.rotation)), 1 - 1e-12) << k;
  }
  EXPECT_GT(st_orbit.simulated_seconds, 0);
  options.cache = &cache;
  scene_to_glb(build_scene(front, front.seed, options, nullptr));
  EXPECT_EQ(scene_to_glb(build_scene(orbit, orbit.seed, options, &st_cached)), scene_to_glb(b));
  EXPECT_TRUE(st_cached.cached_placements);
}

// ---------------------------------------------------------------------------------------------
// Every entry is untrusted input: entries with a valid CRC-32 whose content is wrong are found
// by the checks of what they decode to, removed with one warning naming the file, and made
// again; the scene comes out as without the cache.

/// The key an entry file holds (its trailer: the key, the key's and the payload's sizes as
/// 64-bit counts, the format line of 20 bytes and the CRC-32).
std::string entry_key(const std::string& bytes) {
  const size_t tail = 8 + 8 + 20 + 4;
  uint64_t key_size = 0, payload_size = 0;
  std::memcpy(&key_size, bytes.data() + bytes.size() - tail, 8);
  std::memcpy(&payload_size, bytes.data() + bytes.size() - tail + 8, 8);
  return bytes.substr(payload_size, key_size);
}

/// The key of the entry file in `dir` whose key contains `marker`.
std::string key_containing(const fs::path& dir, const std::string& marker) {
  for (const fs::path& f : entries(dir)) {
    const std::string key = entry_key(test::read_file(f));
    if (key.find(marker) != std::string::npos) return key;
  }
  ADD_FAILURE() << "no entry whose key holds " << marker;
  return {};
}

/// What one run of the tiny scene through a cache whose entry was rewritten found.
struct CraftedRun {
  bool same_bytes = false;
  std::vector<std::string> warnings;
  CutCacheStats stats;
  SceneStats scene;
};

/// The tiny scene through `dir`'s cache, against the bytes `without` a cache.
CraftedRun run_tiny(const fs::path& dir, const std::string& without) {
  CraftedRun r;
  CutCache cache(
      {dir, kDefaultCutCacheBytes, [&](const std::string& w) { r.warnings.push_back(w); }});
  r.same_bytes = tiny_scene_glb(&cache, r.scene) == without;
  r.stats = cache.stats();
  return r;
}

/// Rewrites the cut entry of the tiny scene's object whose key names `object` (its CRC made
/// valid again by storing it) after `change` altered what it decodes to.
void rewrite_cut_entry(const fs::path& dir, const std::string& object,
                       const std::function<void(CachedCut&, SceneAssets&)>& change) {
  CutCache cache({dir, kDefaultCutCacheBytes, {}});
  const std::string key = key_containing(dir, "\"object\":\"" + object);
  const std::optional<std::string> payload = cache.load(key);
  ASSERT_TRUE(payload);
  SceneAssets own;
  const PieceMaterials materials = add_piece_materials(own, "x", PbrMaterial{}, PbrMaterial{});
  const int first_new = static_cast<int>(own.materials.size());
  CachedCut cut = add_cut_entry(CutEntry{*payload, true, 0}, own, materials);
  change(cut, own);
  cache.store(key, encode_cut_payload(cut, own, materials, first_new));
}

/// The tests of crafted entries share one filled cache of the tiny scene (CTest runs the suite
/// as one test, tests/CMakeLists.txt): filled once, by a run that cut every object and settled
/// every placement afresh (the cache was empty, as the suite asserts), so its bytes are those of
/// a run without a cache (CutCacheScene.CachedObjectsGiveTheSameBytesAndDamagedOnesAreCutAgain).
class UntrustedCacheEntry : public ::testing::Test {
 public:
  static void SetUpTestSuite() {
    filled_ = new fs::path(test::fresh_dir("entry_filled"));
    CutCache cache({*filled_, kDefaultCutCacheBytes, {}});
    SceneStats first;
    without_ = new std::string(tiny_scene_glb(&cache, first));
    filling_cut_afresh_ =
        first.cached_objects == 0 && !first.cached_placements && first.objects > 0;
  }
  static void TearDownTestSuite() {
    delete filled_;
    delete without_;
  }

 protected:
  /// A copy of the filled cache in a folder of this test's own, and in *without the filling
  /// run's bytes.
  static fs::path tiny_cache(const std::string& name, std::string* without) {
    EXPECT_TRUE(filling_cut_afresh_) << "the run that filled the cache read from a cache";
    const fs::path dir = test::fresh_dir(name);
    fs::copy(*filled_, dir, fs::copy_options::recursive);
    *without = *without_;
    return dir;
  }

 private:
  static fs::path* filled_;
  static std::string* without_;
  static bool filling_cut_afresh_;
};
fs::path* UntrustedCacheEntry::filled_ = nullptr;
std::string* UntrustedCacheEntry::without_ = nullptr;
bool UntrustedCacheEntry::filling_cut_afresh_ = false;

/// The crafted entry was caught: the same bytes, one warning naming the entry's file, counted
/// damaged; and made again, so the next run reads every object back without a word.
void expect_caught_and_rebuilt(const fs::path& dir, const std::string& without,
                               const std::string& reason) {
  const CraftedRun r = run_tiny(dir, without);
  EXPECT_TRUE(r.same_bytes);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find((dir / kCutCacheLayout).string()), std::string::npos)
      << r.warnings[0];
  EXPECT_NE(r.warnings[0].find("is damaged ("), std::string::npos) << r.warnings[0];
  EXPECT_NE(r.warnings[0].find(reason), std::string::npos) << r.warnings[0];
  EXPECT_EQ(r.stats.damaged, 1);
  const CraftedRun again = run_tiny(dir, without);
  EXPECT_TRUE(again.same_bytes);
  EXPECT_TRUE(again.warnings.empty()) << again.warnings[0];
  EXPECT_EQ(again.scene.cached_objects, again.scene.objects);
  EXPECT_TRUE(again.scene.cached_placements);
}

TEST_F(UntrustedCacheEntry, AShapeTriangleIndexOutOfRangeIsCaughtNotACrash) {
  std::string without;
  const fs::path dir = tiny_cache("entry_shape_index", &without);
  rewrite_cut_entry(dir, "i1_", [](CachedCut& c, SceneAssets&) {
    c.pieces.shapes[0].triangle[5] = {100000000u, 200000000u, 300000000u};
  });
  expect_caught_and_rebuilt(dir, without, "triangle vertex index not below");
}

TEST_F(UntrustedCacheEntry, ATriangleIndexNanPositionOrPrimitiveRangeIsCaught) {
  std::string without;
  const fs::path dir = tiny_cache("entry_mesh", &without);
  const std::vector<std::pair<std::function<void(CachedCut&, SceneAssets&)>, std::string>> cases = {
      {[](CachedCut& c, SceneAssets&) {
         c.pieces.meshes[0].triangle[5] = {100000000u, 0, 0};
       },
       "triangle vertex index not below"},
      {[](CachedCut& c, SceneAssets&) {
         c.pieces.meshes[0].position[3].x = std::numeric_limits<double>::quiet_NaN();
       },
       "non-finite"},
      {[](CachedCut& c, SceneAssets&) { c.pieces.meshes[0].primitives[1].count = 10000000; },
       "primitives"}};
  for (const auto& [change, reason] : cases) {
    rewrite_cut_entry(dir, "i0_", change);
    expect_caught_and_rebuilt(dir, without, reason);
  }
}

TEST_F(UntrustedCacheEntry, ATextureLargerThanItsPixelsIsCaught) {
  std::string without;
  const fs::path dir = tiny_cache("entry_texture", &without);
  rewrite_cut_entry(dir, "i0_", [](CachedCut&, SceneAssets& own) {
    ASSERT_FALSE(own.textures.empty());
    own.textures[0].width = own.textures[0].height = 4096;
    own.textures[0].channels = 4;
  });
  expect_caught_and_rebuilt(dir, without, "bytes of pixels");
}

// Plausible but wrong content changes the output silently unless it is checked against the
// object that asked for it: a mesh scaled by half again leaves its shape's place; a piece scaled
// thirty times, mesh and shape, leaves its template's reach.
TEST_F(UntrustedCacheEntry, AMovedMeshIsCaughtByItsShapeAndItsTemplatesReach) {
  std::string without;
  const fs::path dir = tiny_cache("entry_moved", &without);
  rewrite_cut_entry(dir, "i1_", [](CachedCut& c, SceneAssets&) {
    for (glm::dvec3& p : c.pieces.meshes[0].position) p *= 1.5;
  });
  expect_caught_and_rebuilt(dir, without, "does not lie where its shape lies");
  rewrite_cut_entry(dir, "i1_", [](CachedCut& c, SceneAssets&) {
    for (glm::dvec3& p : c.pieces.meshes[0].position) p *= 30.0;
    for (glm::dvec3& p : c.pieces.shapes[0].position) p *= 30.0;
  });
  expect_caught_and_rebuilt(dir, without, "beyond its template's reach");
}

TEST_F(UntrustedCacheEntry, PlacementsFarAwayOrNotFiniteAreCaught) {
  std::string without;
  const fs::path dir = tiny_cache("entry_placements", &without);
  const std::vector<std::pair<std::function<void(Placement&)>, std::string>> cases = {
      {[](Placement& p) { p.translation.y = 1000; }, "outside the container's reach"},
      {[](Placement& p) { p.rotation.x = std::numeric_limits<double>::quiet_NaN(); },
       "not a finite unit quaternion"},
      {[](Placement& p) { p.translation.z = std::numeric_limits<double>::infinity(); },
       "non-finite translation"}};
  for (const auto& [change, reason] : cases) {
    {
      CutCache cache({dir, kDefaultCutCacheBytes, {}});
      const std::string key = key_containing(dir, "\"placements\":");
      const std::optional<std::string> payload = cache.load(key);
      ASSERT_TRUE(payload);
      uint64_t bodies = 0;
      std::memcpy(&bodies, payload->data(), 8);
      std::optional<SettleResult> settled = decode_settled(*payload, bodies);
      ASSERT_TRUE(settled);
      change(settled->placements[1]);
      cache.store(key, encode_settled(*settled));
    }
    const CraftedRun r = run_tiny(dir, without);
    EXPECT_TRUE(r.same_bytes) << reason;
    ASSERT_EQ(r.warnings.size(), 1u) << reason;
    EXPECT_NE(r.warnings[0].find(reason), std::string::npos) << r.warnings[0];
    EXPECT_FALSE(r.scene.cached_placements);
    EXPECT_GT(r.scene.simulated_seconds, 0);
  }
}

// Counts are checked against what each element costs at least, before anything is allocated:
// an entry of zeros whose first count claims one texture per 8 bytes is refused at that count.
TEST_F(UntrustedCacheEntry, ACountBeyondWhatItsElementsCostIsRefusedBeforeAllocating) {
  std::string without;
  const fs::path dir = tiny_cache("entry_counts", &without);
  {
    CutCache cache({dir, kDefaultCutCacheBytes, {}});
    const std::string key = key_containing(dir, "\"object\":\"i2_");
    std::string crafted(size_t{8} << 20, '\0');
    const uint64_t claimed = (crafted.size() - 8) / 8;
    std::memcpy(crafted.data(), &claimed, 8);
    cache.store(key, crafted);
  }
  expect_caught_and_rebuilt(dir, without, "a count beyond the data");
  // The placements: a count of one placement per byte left is refused just the same.
  std::string plc(size_t{1} << 20, '\0');
  const uint64_t claimed = plc.size() - 8;
  std::memcpy(plc.data(), &claimed, 8);
  EXPECT_FALSE(decode_settled(plc, claimed));
}

}  // namespace
}  // namespace cutaway
