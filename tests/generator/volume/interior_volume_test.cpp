// The interior volume (volume/interior_volume.h, volume_lookup.h, volume_accuracy.h): the grid
// and its frame, solid and empty, regions and sheet distances, PMVC at the voxel centres, the
// reading rule, and the accuracy bound against PMVC on random caps.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "cut/piece_views.h"
#include "diffusion/diffusion.h"
#include "export/gltf_export.h"
#include "export/volume_files.h"
#include "io/template_parser.h"
#include "model/grain_components.h"
#include "model/model_builder.h"
#include "test_support.h"
#include "variation/grains.h"
#include "volume/interior_volume.h"
#include "volume/volume_accuracy.h"
#include "volume/volume_lookup.h"

namespace cutaway {
namespace {

/// A sphere of radius 30 mm holding a sphere of radius 12 mm: hollow inside (the fixture as it
/// is), or, with `inner` replacing its visibility line, a solid inner sphere.
DsModel spheres(const std::string& inner = "") {
  const std::string path = test::source_path("tests/data/section_hollow.yaml").string();
  std::string text = test::read_file(path);
  if (!inner.empty()) {
    const size_t at = text.find("    visible: {back: false}");
    text.replace(at, std::string("    visible: {back: false}").size(), inner);
  }
  return build_model(parse_template(text, path, test::source_path("tests/data").string()));
}

std::unique_ptr<DiffusionBackend> cpu(const DsModel& model) {
  DiffusionOptions options;
  return make_cpu_diffusion(model, options);
}

InteriorVolume sampled(const DsModel& model, double voxel_m, int threads = 0) {
  auto grid = volume_grid(model, voxel_m);
  EXPECT_TRUE(grid.has_value());
  return sample_interior_volume(model, *cpu(model), std::move(*grid), threads);
}

TEST(InteriorVolume, GridReachesOneVoxelBeyondTheSkinOnEverySide) {
  const DsModel model = spheres();
  const auto [lo, hi] = skin_bounds(model);
  const Outcome<InteriorVolume> grid = volume_grid(model, 0.002);
  ASSERT_TRUE(grid);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(grid->size[a], static_cast<int>(std::ceil((hi[a] - lo[a]) / 0.002)) + 3);
    // The outermost voxel centres lie at least one voxel outside the skin's box...
    EXPECT_LE(grid->origin[a], lo[a] - 0.002 + 1e-12);
    EXPECT_GE(grid->centre(grid->size.x - 1, grid->size.y - 1, grid->size.z - 1)[a],
              hi[a] + 0.002 - 1e-12);
    // ...and the grid is centred on it.
    const double mid = 0.5 * (grid->origin[a] + grid->centre(grid->size.x - 1, grid->size.y - 1,
                                                             grid->size.z - 1)[a]);
    EXPECT_NEAR(mid, 0.5 * (lo[a] + hi[a]), 1e-12);
  }
  EXPECT_TRUE(grid->colour.empty());  // a grid, no samples yet
}

TEST(InteriorVolume, RefusesAVoxelThatIsNotALengthOrMakesTooManyVoxels) {
  const DsModel model = spheres();
  EXPECT_FALSE(volume_grid(model, 0.0));
  EXPECT_FALSE(volume_grid(model, -1.0));
  EXPECT_FALSE(volume_grid(model, std::nan("")));
  EXPECT_FALSE(volume_grid(model, 1e308));  // huge voxel centres would break the ray casts
  const Outcome<InteriorVolume> coarse = volume_grid(model, 0.031);  // the skin is 60 mm
  ASSERT_FALSE(coarse);
  EXPECT_NE(coarse.reason().find("at least two voxels across"), std::string::npos);
  EXPECT_TRUE(volume_grid(model, 0.030));
  const Outcome<InteriorVolume> fine = volume_grid(model, 1e-5);
  ASSERT_FALSE(fine);
  EXPECT_NE(fine.reason().find("voxels over the skin"), std::string::npos) << fine.reason();
}

TEST(InteriorVolume, OutsideAndTheHollowCavityAreEmptyTheShellIsOneSolidRegion) {
  const DsModel model = spheres();
  const double voxel = 0.003;
  const InteriorVolume v = sampled(model, voxel);
  ASSERT_EQ(v.region.size(), v.voxels());
  EXPECT_EQ(v.regions, 1u);
  size_t solid = 0;
  for (int k = 0; k < v.size.z; ++k)
    for (int j = 0; j < v.size.y; ++j)
      for (int i = 0; i < v.size.x; ++i) {
        const double r = glm::length(v.centre(i, j, k));
        const uint32_t region = v.region[v.index(i, j, k)];
        solid += region != kEmptyRegion;
        // Away from the two spheres by more than half a voxel's diagonal, the side is clear.
        if (r < 0.012 - 0.9 * voxel || r > 0.030 + 0.9 * voxel) {
          EXPECT_EQ(region, kEmptyRegion) << i << " " << j << " " << k;
        } else if (r > 0.012 + 0.9 * voxel && r < 0.030 - 0.9 * voxel) {
          EXPECT_EQ(region, 1u) << i << " " << j << " " << k;
        }
      }
  EXPECT_EQ(solid, v.solid);
  const double shell = 4.0 / 3.0 * std::numbers::pi * (std::pow(0.030, 3) - std::pow(0.012, 3));
  EXPECT_NEAR(static_cast<double>(v.solid) * std::pow(voxel, 3), shell, 0.05 * shell);
}

TEST(InteriorVolume, SolidVoxelsHoldPmvcAtTheirCentresEmptyOnesBesideThemTheirMean) {
  const DsModel model = spheres();
  const InteriorVolume v = sampled(model, 0.004);
  const auto diffusion = cpu(model);
  int checked = 0, dilated = 0;
  for (int k = 0; k < v.size.z; k += 3)
    for (int j = 0; j < v.size.y; j += 2)
      for (int i = 0; i < v.size.x; ++i) {
        const size_t at = v.index(i, j, k);
        if (v.region[at] == kEmptyRegion) {
          dilated += v.colour[at] != glm::vec3(0);
          continue;
        }
        const std::vector<glm::dvec3> pmvc = diffusion->diffuse(std::vector{v.centre(i, j, k)});
        EXPECT_EQ(v.colour[at], glm::vec3(pmvc[0])) << i << " " << j << " " << k;
        ++checked;
      }
  EXPECT_GT(checked, 50);
  EXPECT_GT(dilated, 10);  // the skin's outline and the cavity's wall
  // A corner voxel, far from everything, stays black.
  EXPECT_EQ(v.colour[0], glm::vec3(0));
}

TEST(InteriorVolume, SharpSurfacesSeparateRegionsBlurredOnesDoNot) {
  // The inner sphere solid on both sides: a sharp one bounds a region of its own...
  const InteriorVolume sharp = sampled(spheres("    blur: 0"), 0.003);
  EXPECT_EQ(sharp.regions, 2u);
  // ...one blurred by more than half a voxel does not: its colours change smoothly across it.
  const InteriorVolume soft = sampled(spheres("    blur: 2"), 0.003);
  EXPECT_EQ(soft.regions, 1u);
  // Sheet distances: within a voxel of the sharp sphere they are below one voxel, and never
  // above it anywhere.
  int near = 0;
  for (int k = 0; k < sharp.size.z; ++k)
    for (int j = 0; j < sharp.size.y; ++j)
      for (int i = 0; i < sharp.size.x; ++i) {
        const size_t at = sharp.index(i, j, k);
        EXPECT_LE(sharp.sheet_distance[at], static_cast<float>(sharp.voxel_m));
        const double r = glm::length(sharp.centre(i, j, k));
        EXPECT_LE(sharp.outline_distance[at], static_cast<float>(sharp.voxel_m));
        // Near the skin the outline distance is below a voxel and near the true one (it
        // measures to the plane of a crossing along an axis, not along the normal).
        if (std::abs(r - 0.030) < 0.4 * sharp.voxel_m) {
          EXPECT_NEAR(sharp.outline_distance[at], std::abs(r - 0.030), 0.25 * sharp.voxel_m);
        }
        if (std::abs(r - 0.012) < 0.4 * sharp.voxel_m) {
          EXPECT_LT(sharp.sheet_distance[at], 0.45 * sharp.voxel_m);
          EXPECT_NEAR(sharp.sheet_distance[at], std::abs(r - 0.012), 0.1 * sharp.voxel_m);
          ++near;
        }
      }
  EXPECT_GT(near, 20);
}

/// A white ball of radius 20 mm whose flesh (radius 14 mm) is filled with black strands 0.4 mm
/// thick and 3 mm long pointing out from the axis, 4 mm apart (grains through a region,
/// scattered with seed 5).
DsModel ball_of_strands() {
  std::string circle[2];
  for (int c = 0; c < 2; ++c) {
    const double r = c == 0 ? 20 : 14;
    circle[c] = "[";
    for (int k = 0; k <= 12; ++k) {
      const double a = std::numbers::pi * (k / 12.0 - 0.5);
      circle[c] += (k ? ", [" : "[") + std::to_string(k == 0 || k == 12 ? 0.0 : r * std::cos(a)) +
                   ", " + std::to_string(r * std::sin(a)) + "]";
    }
    circle[c] += "]";
  }
  const Template t = parse_template(
      "format: cutaway-template/1\nname: strands\nunits: mm\nsymmetry: {type: cylindrical}\n"
      "resolution: {edge: 1.2}\nsurfaces:\n"
      "  - {name: skin, kind: around, role: skin, front: \"#208020\", back: \"#ffffff\", "
      "profile: " +
          circle[0] +
          "}\n"
          "  - {name: flesh, kind: around, front: \"#ffffff\", back: \"#ffffff\", profile: " +
          circle[1] +
          "}\n"
          "grains:\n  - {name: strands, inside: flesh, spacing: 4, shape: {ellipsoid: [0.2, 0.2, "
          "1.5]}, front: \"#000000\", back: \"#000000\"}\n",
      "strands.yaml", ".");
  DsModel model = build_model(t);
  scatter_grains(t, model, 5);
  return model;
}

TEST(InteriorVolume, GrainsThinnerThanAVoxelKeepTheirColour) {
  // 1 mm voxels: most 0.4 mm strands hold no voxel centre. Every voxel a strand's axis passes
  // through is sampled inside it, so each strand shows black along its length.
  const DsModel model = ball_of_strands();
  const std::vector<GrainComponent> strands = grain_components(model);
  ASSERT_GT(strands.size(), 100u);
  const InteriorVolume v = sampled(model, 0.001);
  EXPECT_GT(v.grain_samples, strands.size());
  size_t shown = 0, dark_voxels = 0;
  for (const GrainComponent& strand : strands) {
    // The voxel at the strand's centre, and the longest run of black voxels along it.
    const glm::ivec3 at(glm::round((strand.centre - v.origin) / v.voxel_m));
    const size_t voxel = v.index(at.x, at.y, at.z);
    if (v.region[voxel] != kEmptyRegion && glm::length(v.colour[voxel]) < 0.05f) ++shown;
  }
  for (size_t voxel = 0; voxel < v.voxels(); ++voxel)
    dark_voxels += v.region[voxel] != kEmptyRegion && glm::length(v.colour[voxel]) < 0.05f;
  // Every strand clear of the skin shows at its centre; the strands (3 mm long, 1 mm voxels)
  // darken about three voxels each.
  EXPECT_GE(shown, strands.size() * 95 / 100);
  EXPECT_GT(dark_voxels, 2 * strands.size());
  std::printf("%zu strands: %zu black at their centre, %zu black voxels, %zu voxels sampled "
              "inside a strand\n",
              strands.size(), shown, dark_voxels, v.grain_samples);
}

TEST(InteriorVolume, LayersThinnerThanAVoxelKeepTheirColour) {
  // A white ball of radius 20 mm under a red peel 0.4 mm thick, at 1.5 mm voxels: most grid
  // lines pass from outside to the flesh between two centres without one in the peel. Each
  // such line's first solid voxel samples the peel's middle, so the outline is red all round.
  auto circle = [](double radius) {
    std::string out = "[";
    for (int k = 0; k <= 12; ++k) {
      const double a = std::numbers::pi * (k / 12.0 - 0.5);
      out += (k ? ", [" : "[") + std::to_string(k == 0 || k == 12 ? 0.0 : radius * std::cos(a)) +
             ", " + std::to_string(radius * std::sin(a)) + "]";
    }
    return out + "]";
  };
  const DsModel model = build_model(parse_template(
      "format: cutaway-template/1\nname: peel\nunits: mm\nsymmetry: {type: cylindrical}\n"
      "resolution: {edge: 1.2}\nsurfaces:\n"
      "  - {name: skin, kind: around, role: skin, front: \"#c02020\", back: \"#c02020\", "
      "profile: " +
          circle(20) +
          "}\n  - {name: flesh, kind: around, front: \"#c02020\", back: \"#ffffff\", profile: " +
          circle(19.6) + "}\n",
      "peel.yaml", "."));
  const InteriorVolume v = sampled(model, 0.0015);
  EXPECT_GT(v.layer_samples, 500u);
  // The first solid voxel of every grid line along +x.
  size_t lines = 0, red = 0;
  for (int k = 0; k < v.size.z; ++k)
    for (int j = 0; j < v.size.y; ++j)
      for (int i = 1; i < v.size.x; ++i) {
        const size_t at = v.index(i, j, k);
        if (v.region[at] == kEmptyRegion || v.region[v.index(i - 1, j, k)] != kEmptyRegion)
          continue;
        ++lines;
        red += v.colour[at].r > 0.3f && v.colour[at].g < 0.1f;
        break;
      }
  ASSERT_GT(lines, 400u);
  EXPECT_GE(red, lines * 9 / 10);
  std::printf("%zu grid lines along +x: %zu enter the flesh through a red voxel; %zu voxels "
              "sampled inside the peel\n",
              lines, red, v.layer_samples);
}

TEST(InteriorVolume, TheThreadCountDoesNotChangeTheVolume) {
  const DsModel model = spheres("    blur: 0");
  const InteriorVolume one = sampled(model, 0.004, 1);
  const InteriorVolume two = sampled(model, 0.004, 2);
  EXPECT_EQ(one.region, two.region);
  EXPECT_EQ(one.sheet_distance, two.sheet_distance);
  EXPECT_EQ(one.outline_distance, two.outline_distance);
  EXPECT_EQ(one.colour, two.colour);
  EXPECT_EQ(one.material, two.material);
}

/// A 4 x 2 x 2 volume cut by the plane x = origin.x + 1.3 voxels: region 1 (red) on the low
/// side, region 2 (blue) on the high side, sheet distances as the sampler measures them.
InteriorVolume two_region_volume() {
  InteriorVolume v;
  v.size = {4, 2, 2};
  v.voxel_m = 0.01;
  v.origin = {0.1, 0.2, 0.3};
  const size_t n = v.voxels();
  v.colour.resize(n);
  v.material.resize(n);
  v.region.resize(n);
  v.sheet_distance.resize(n);
  v.outline_distance.assign(n, 0.01f);  // all solid: the outline is far
  const float distance[4] = {0.01f, 0.003f, 0.007f, 0.01f};
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 4; ++i) {
        const size_t at = v.index(i, j, k);
        v.region[at] = i <= 1 ? 1 : 2;
        v.colour[at] = i <= 1 ? glm::vec3(0.8f, 0.1f, 0.1f) : glm::vec3(0.1f, 0.1f, 0.8f);
        v.material[at] = i <= 1 ? glm::vec2(0.3f, 0.1f) : glm::vec2(0.6f, 0.2f);
        v.sheet_distance[at] = distance[i];
      }
  v.regions = 2;
  return v;
}

TEST(InteriorVolumeLookup, ASheetBetweenVoxelCentresStaysSharpAtItsOwnPlace) {
  const InteriorVolume v = two_region_volume();
  for (const double y : {0.2, 0.204, 0.21})
    for (const double z : {0.3, 0.307}) {
      const VolumeSample before = sample_volume(v, {0.1 + 0.0129, y, z});
      const VolumeSample after = sample_volume(v, {0.1 + 0.0131, y, z});
      EXPECT_EQ(before.region, 1u);
      EXPECT_EQ(after.region, 2u);
      // No blend of the two sides, however near the sheet.
      EXPECT_EQ(before.colour, glm::vec3(0.8f, 0.1f, 0.1f));
      EXPECT_EQ(after.colour, glm::vec3(0.1f, 0.1f, 0.8f));
      EXPECT_EQ(after.material, glm::vec2(0.6f, 0.2f));
    }
}

TEST(InteriorVolumeLookup, TheOutlineStaysAtTheSkinOverALayerThinnerThanAVoxel) {
  // Voxels 0 empty, 1..3 solid region 1: the skin at x = 0.6 voxels, and a sheet at x = 0.8
  // bounding a thin layer no voxel centre falls in. The outline distances measure to the skin
  // (0.6 and 0.4 voxels), the sheet distances to the sheet: the outline stays at 0.6.
  InteriorVolume v = two_region_volume();
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 4; ++i) {
        const size_t at = v.index(i, j, k);
        v.region[at] = i == 0 ? kEmptyRegion : 1;
        v.outline_distance[at] = i == 0 ? 0.006f : i == 1 ? 0.004f : 0.01f;
        v.sheet_distance[at] = i == 1 ? 0.002f : 0.01f;
      }
  EXPECT_EQ(sample_volume(v, {0.1 + 0.0059, 0.205, 0.305}).region, kEmptyRegion);
  EXPECT_EQ(sample_volume(v, {0.1 + 0.0061, 0.205, 0.305}).region, 1u);
  EXPECT_EQ(sample_volume(v, {0.1 + 0.0061, 0.205, 0.305}).colour, v.colour[v.index(1, 0, 0)]);
}

TEST(InteriorVolumeLookup, OutsideTheGridIsEmpty) {
  const InteriorVolume v = two_region_volume();
  EXPECT_EQ(sample_volume(v, {0.0999, 0.205, 0.305}).region, kEmptyRegion);
  EXPECT_EQ(sample_volume(v, {0.1301, 0.205, 0.305}).region, kEmptyRegion);
  EXPECT_EQ(sample_volume(v, {std::nan(""), 0.205, 0.305}).region, kEmptyRegion);
  EXPECT_EQ(sample_volume(v, {0.1299, 0.2099, 0.3099}).region, 2u);  // inside the last centre
}

TEST(InteriorVolumeAccuracy, TomatoCapsFromTheVolumeMatchPmvcWithinTheBound) {
  // The tomato at two thirds of the default resolution (64 voxels across: 1.1 mm voxels, whose
  // half is below its chambers' 0.6 mm blur, so the regions join across it as the blur asks;
  // at 48 across they do not, and the near error doubles), on four random caps. Bounds in
  // steps of 1/255 of sRGB, with headroom over what it measures (doc/algorithms.md §8).
  const Template tmpl = load_template(test::source_path("templates/tomato.yaml").string());
  const DsModel model = build_model(tmpl);
  const auto diffusion = cpu(model);
  auto grid = volume_grid(model, voxel_length_across(model, 64));
  ASSERT_TRUE(grid);
  const InteriorVolume volume = sample_interior_volume(model, *diffusion, std::move(*grid));
  const VolumeErrors e = volume_errors(model, *diffusion, volume, random_cap_planes(model, 4, 7));
  std::printf("tomato at 64 across: far %.2f / %.1f, near %.2f / %.1f, wrong side %.3f %%\n",
              e.mean_far, e.p99_far, e.mean_near, e.p99_near, 100 * e.wrong_side);
  EXPECT_GT(e.points, 3000u);
  EXPECT_GT(e.near_points, 300u);
  EXPECT_LT(e.mean_far, 1.5);
  EXPECT_LT(e.p99_far, 12.0);
  EXPECT_LT(e.mean_near, 5.0);
  EXPECT_LT(e.p99_near, 25.0);
  EXPECT_LT(e.wrong_side, 0.005);
}

TEST(InteriorVolumeAccuracy, RandomCapPlanesCrossTheMiddleOfTheSkin) {
  const DsModel model = spheres();
  const std::vector<Plane> planes = random_cap_planes(model, 20, 3);
  ASSERT_EQ(planes.size(), 20u);
  for (const Plane& p : planes) {
    EXPECT_NEAR(glm::length(p.normal), 1.0, 1e-12);
    for (int a = 0; a < 3; ++a) EXPECT_LE(std::abs(p.point[a]), 0.015 + 1e-9);
  }
  EXPECT_EQ(random_cap_planes(model, 20, 3)[7].normal, planes[7].normal);  // seeded
  EXPECT_NE(random_cap_planes(model, 20, 4)[7].normal, planes[7].normal);
}

}  // namespace
}  // namespace cutaway

namespace cutaway {
namespace {

// Every shipped template's volume, coarse (20 voxels across), in every form: the sidecar and
// flipbooks, the OpenVDB file and the whole object's glTF. One test per shipped template (the
// sweep's process shares the template's build).
class InteriorVolumeForms : public ::testing::TestWithParam<std::filesystem::path> {};

TEST_P(InteriorVolumeForms, EveryFormIsMade) {
  const test::BuiltTemplate& built = test::built_template(GetParam());
  const Template& tmpl = built.tmpl;
  const DsModel& model = built.model;
  const auto diffusion = cpu(model);
  auto grid = volume_grid(model, voxel_length_across(model, 20));
  ASSERT_TRUE(grid);
  const InteriorVolume volume = sample_interior_volume(model, *diffusion, std::move(*grid));
  EXPECT_GT(volume.solid, 0u);
  EXPECT_GE(volume.regions, 1u);
  const Outcome<std::vector<NamedFile>> files = volume_files(volume, "x", tmpl.name, -1, true);
  ASSERT_TRUE(files) << files.reason();
  ASSERT_EQ(files->size(), 5u);
  const nlohmann::json sidecar = nlohmann::json::parse((*files)[0].second);
  EXPECT_EQ(sidecar["template"], tmpl.name);
  EXPECT_EQ(sidecar["vdb"], "x.vdb");
  EXPECT_EQ((*files)[4].second.substr(0, 4), std::string(" BDV"));
  const std::string glb =
      scene_to_glb(whole_object_assets(Variant{tmpl, model}, *diffusion, 1.0, 0));
  EXPECT_EQ(glb.substr(0, 4), "glTF");
}

INSTANTIATE_TEST_SUITE_P(Templates, InteriorVolumeForms,
                         ::testing::ValuesIn(test::shipped_templates()),
                         [](const auto& info) { return test::template_test_name(info.param); });

}  // namespace
}  // namespace cutaway
