// The `variants` run (batch/variant_set.h): the DS models handed over in seed order with
// their records, the same bytes for the same seeds, and the mid-height cut of a variant.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "batch/variant_set.h"
#include "diffusion/diffusion.h"
#include "io/template_parser.h"
#include "section/cut_segments.h"
#include "test_support.h"
#include "variation/variation.h"

namespace cutaway {
namespace {

const Template& kiwi() {
  static const Template t = load_template(test::source_path("templates/kiwi.yaml").string());
  return t;
}

TEST(VariantSet, HandsEachModelOverInSeedOrderWithItsRecord) {
  std::vector<std::string> files;
  std::map<std::string, std::string> bytes;
  std::vector<int> progress;
  const std::vector<VariantRecord> records = build_variant_models(
      kiwi(), 40, 2, 4,
      [&](const std::string& file, const std::string& glb) {
        files.push_back(file);
        bytes[file] = glb;
      },
      [&](int done) { progress.push_back(done); });
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(files, (std::vector<std::string>{"kiwi-42.glb", "kiwi-43.glb"}));
  EXPECT_EQ(progress, (std::vector<int>{1, 2}));
  for (size_t k = 0; k < 2; ++k) {
    const VariantRecord& r = records[k];
    EXPECT_EQ(r.file, files[k]);
    EXPECT_EQ(r.seed, 42 + k);
    EXPECT_EQ(r.hash, fnv1a64(bytes[r.file]));
    EXPECT_EQ(bytes[r.file].substr(0, 4), "glTF");
    const Variant v = make_variant(kiwi(), r.seed);
    EXPECT_EQ(r.ds_faces, v.model.face_count());
    EXPECT_EQ(r.folds, v.tmpl.folds);
  }
  EXPECT_NE(records[0].hash, records[1].hash);
  // The same seeds again: the same bytes; a run of one seed is that seed's part of the run.
  const std::vector<VariantRecord> again =
      build_variant_models(kiwi(), 40, 3, 4, [](const std::string&, const std::string&) {});
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0].hash, records[1].hash);
  EXPECT_TRUE(build_variant_models(kiwi(), 40, 5, 5, [](auto&, auto&) {}).empty());
  EXPECT_THROW(build_variant_models(kiwi(), 40, 5, 4, [](auto&, auto&) {}), InternalError);
}

TEST(VariantSet, TheSheetSectionLiesAtTheSkinsMidHeight) {
  const Variant v = make_variant(kiwi(), 7);
  const Outcome<CrossSection> s = variant_section(v, [](const DsModel& model) {
    return make_cpu_diffusion(model, {4, 0});
  });
  ASSERT_TRUE(s) << s.reason();
  double lo = 1e9, hi = -1e9;
  for (const auto vh : v.model.skin().mesh.vertices()) {
    lo = std::min(lo, v.model.skin().mesh.point(vh)[1]);
    hi = std::max(hi, v.model.skin().mesh.point(vh)[1]);
  }
  EXPECT_NEAR(s->plane.point.y, 0.5 * (lo + hi), 1e-12);
  EXPECT_NEAR(std::abs(s->plane.normal.y), 1.0, 1e-12);
  EXPECT_FALSE(s->position.empty());
  // On the plane: a mesh vertex within kOnPlane_m of it counts as on it and keeps its place.
  for (const glm::dvec3& p : s->position) ASSERT_NEAR(p.y, 0.5 * (lo + hi), kOnPlane_m);
  EXPECT_THROW(variant_section(v, DiffusionFactory{}), InternalError);
}

}  // namespace
}  // namespace cutaway
