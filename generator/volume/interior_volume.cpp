#include "volume/interior_volume.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

#include "base/error.h"
#include "base/parallel_chunks.h"
#include "base/timer.h"
#include "diffusion/diffusion_sheets.h"
#include "diffusion/sheet_rays.h"
#include "volume/thin_grains.h"
#include "volume/thin_layers.h"
#include "volume/volume_cost.h"

namespace cutaway {

namespace {

using Clock = std::chrono::steady_clock;

/// The rays cast from each voxel centre: the six face-neighbour directions (+x, -x, +y, -y,
/// +z, -z), then the kSideVotes voting directions (off every axis and diagonal, so that no
/// vote grazes a sheet the grid or a fold lines up with). 15 rays: one Embree packet.
constexpr int kEdgeRays = 6;
// The cost counted before the work (volume_cost.h): these 15, the 6 edges against the walls and
// at most 3 looking for a thin layer's second sheet.
static_assert(kClassifyRaysPerVoxel == 2 * kEdgeRays + kSideVotes + 3);
const std::array<glm::vec3, kEdgeRays + kSideVotes>& voxel_directions() {
  static const std::array<glm::vec3, kEdgeRays + kSideVotes> directions = [] {
    std::array<glm::vec3, kEdgeRays + kSideVotes> d{};
    d[0] = {1, 0, 0}, d[1] = {-1, 0, 0}, d[2] = {0, 1, 0};
    d[3] = {0, -1, 0}, d[4] = {0, 0, 1}, d[5] = {0, 0, -1};
    const glm::vec3 votes[kSideVotes] = {{2, 3, 5},   {-5, 2, 3},   {3, -5, 2},
                                         {-2, -3, 5}, {5, -2, -3},  {-3, 5, -2},
                                         {2, 7, -3},  {-7, -3, -2}, {3, -2, -7}};
    for (int v = 0; v < kSideVotes; ++v) d[kEdgeRays + v] = glm::normalize(votes[v]);
    return d;
  }();
  return directions;
}

/// Whether the side of `hit`'s surface that a ray along `direction` meets is solid.
bool solid_side(const DsModel& model, const std::vector<DiffusionSheet>& sheets,
                const SheetHit& hit, const glm::vec3& direction) {
  if (hit.sheet < 0) return false;
  const DsSurface& surface = model.surfaces[static_cast<size_t>(hit.sheet)];
  const bool front =
      glm::dot(sheets[static_cast<size_t>(hit.sheet)].face_normal[hit.triangle], direction) < 0;
  if (front) return surface.role != SurfaceRole::Skin && surface.visible_front;
  return surface.visible_back;
}

/// The majority of the side votes among `hits` (kSideVotes, after the edge rays).
bool voted_solid(const DsModel& model, const std::vector<DiffusionSheet>& sheets,
                 std::span<const SheetHit> hits) {
  const auto& dirs = voxel_directions();
  int solid = 0;
  for (int v = 0; v < kSideVotes; ++v)
    solid += solid_side(model, sheets, hits[kEdgeRays + v], dirs[kEdgeRays + v]) ? 1 : 0;
  return 2 * solid > kSideVotes;
}

/// Union-find root of `v`, halving the path on the way.
uint32_t find_root(std::vector<uint32_t>& parent, uint32_t v) {
  while (parent[v] != v) {
    parent[v] = parent[parent[v]];
    v = parent[v];
  }
  return v;
}

/// The rigid surfaces of `model` as VolumeStones: triangles wound outwards (a surface whose
/// front is its inside is turned), the stone's colour from its inside side, the flesh's from
/// its outside.
std::vector<VolumeStone> volume_stones(const DsModel& model) {
  std::vector<VolumeStone> out;
  for (const DsSurface& surface : model.surfaces) {
    if (!surface.rigid) continue;
    const DsMesh& mesh = surface.mesh;
    const bool front_outside = signed_volume(mesh) > 0;
    VolumeStone stone{surface.name, {}, {}, {}, {}};
    for (auto vh : mesh.vertices()) {
      const auto& d = mesh.data(vh);
      const glm::dvec3 front(d.front[0], d.front[1], d.front[2]);
      const glm::dvec3 back(d.back[0], d.back[1], d.back[2]);
      stone.points.push_back(to_glm(mesh.point(vh)));
      stone.stone.push_back(front_outside ? back : front);
      stone.flesh.push_back(front_outside ? front : back);
    }
    for (auto fh : mesh.faces()) {
      glm::uvec3 t;
      int k = 0;
      for (auto vh : mesh.fv_range(fh)) t[k++] = static_cast<unsigned>(vh.idx());
      if (!front_outside) std::swap(t[1], t[2]);
      stone.triangles.push_back(t);
    }
    out.push_back(std::move(stone));
  }
  return out;
}

}  // namespace

double voxel_length_across(const DsModel& model, int across) {
  CUTAWAY_CHECK(across > 0);
  const auto [lo, hi] = skin_bounds(model);
  const glm::dvec3 extent = hi - lo;
  return std::max({extent.x, extent.y, extent.z}) / across;
}

Outcome<InteriorVolume> volume_grid(const DsModel& model, double voxel_m) {
  if (!std::isfinite(voxel_m) || voxel_m <= 0)
    return Outcome<InteriorVolume>::none("the voxel length must be positive and finite");
  const auto [lo, hi] = skin_bounds(model);
  const double longest = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  if (voxel_m > 0.5 * longest)
    return Outcome<InteriorVolume>::none(
        std::to_string(voxel_m) + " m is longer than half the skin's longest edge (" +
        std::to_string(longest) + " m); a volume needs at least two voxels across it");
  InteriorVolume volume;
  volume.voxel_m = voxel_m;
  const glm::dvec3 counts = grid_voxels(hi - lo, voxel_m);
  double count = 1;
  for (int a = 0; a < 3; ++a) {
    const double n = counts[a];
    count *= n;
    if (n > 1e7 || count > static_cast<double>(kMaxVolumeVoxels))
      return Outcome<InteriorVolume>::none(std::to_string(voxel_m) + " m makes more than " +
                                           std::to_string(kMaxVolumeVoxels) +
                                           " voxels over the skin; give a longer voxel length");
    volume.size[a] = static_cast<int>(n);
    volume.origin[a] = 0.5 * (lo[a] + hi[a]) - 0.5 * (n - 1) * voxel_m;
  }
  return volume;
}

std::vector<PointClass> classify_points(const DsModel& model, const std::vector<glm::dvec3>& points,
                                        double reach_m, int threads) {
  const std::vector<DiffusionSheet> sheets = surface_sheets(model);
  const SheetRayCaster caster(sheets, threads);
  const auto& dirs = voxel_directions();
  std::vector<PointClass> classes(points.size());
  parallel_chunks(points.size(), 64, threads, [&](size_t begin, size_t end) {
    std::array<SheetHit, kEdgeRays + kSideVotes> hits;
    for (size_t p = begin; p < end; ++p) {
      caster.cast(points[p], dirs, hits);
      classes[p].solid = voted_solid(model, sheets, hits);
      for (int e = 0; e < kEdgeRays; ++e)
        classes[p].near_sheet =
            classes[p].near_sheet || (hits[static_cast<size_t>(e)].sheet >= 0 &&
                                      hits[static_cast<size_t>(e)].at.t < reach_m);
    }
  });
  return classes;
}

InteriorVolume sample_interior_volume(const DsModel& model, const DiffusionBackend& diffusion,
                                      InteriorVolume grid, int threads,
                                      const ColourModulation* modulation, double strength) {
  InteriorVolume volume = std::move(grid);
  const double voxel_m = volume.voxel_m;
  CUTAWAY_CHECK(voxel_m > 0 && volume.voxels() > 0 && volume.voxels() <= kMaxVolumeVoxels);
  const auto t0 = Clock::now();
  const size_t n = volume.voxels();
  const std::vector<DiffusionSheet> sheets = surface_sheets(model);
  const SheetRayCaster caster(sheets, threads);
  // The surfaces with an empty side (the skin, cavity walls): where solid meets empty.
  std::vector<DiffusionSheet> walls;
  for (size_t s = 0; s < model.surfaces.size(); ++s) {
    const DsSurface& surface = model.surfaces[s];
    if (surface.role == SurfaceRole::Skin || !surface.visible_front || !surface.visible_back)
      walls.push_back(sheets[s]);
  }
  const SheetRayCaster wall_caster(walls, threads);
  const auto& dirs = voxel_directions();
  const std::span<const glm::vec3> edge_dirs(dirs.data(), kEdgeRays);
  constexpr float kNone = std::numeric_limits<float>::infinity();
  std::vector<char> solid(n, 0);
  // Per voxel and direction, the distance to the plane of the first wall its segment crosses
  // (infinity: none).
  std::vector<std::array<float, kEdgeRays>> wall_crossing(n);
  // Per surface, each vertex's blur (metres), for telling sharp crossings from soft ones.
  std::vector<std::vector<float>> blur(model.surfaces.size());
  for (size_t s = 0; s < model.surfaces.size(); ++s)
    for (auto vh : model.surfaces[s].mesh.vertices())
      blur[s].push_back(static_cast<float>(model.surfaces[s].mesh.data(vh).blur));
  // Per voxel and face-neighbour direction (+x, -x, +y, -y, +z, -z): the distance to the
  // plane of the surface its segment crosses first (infinity: none), and whether that
  // surface's blur there is at least half a voxel (a soft crossing, bit e).
  std::vector<std::array<float, kEdgeRays>> crossing(n);
  std::vector<uint8_t> soft(n, 0);
  // The distance from a voxel centre to the plane of the triangle `hit` crosses on the
  // segment along edge direction e, or infinity beyond the voxel.
  auto plane_distance = [&](const SheetHit& hit, const std::vector<DiffusionSheet>& of, int e) {
    if (hit.sheet < 0 || hit.at.t >= voxel_m) return kNone;
    const glm::vec3& normal = of[static_cast<size_t>(hit.sheet)].face_normal[hit.triangle];
    return static_cast<float>(hit.at.t * std::abs(static_cast<double>(normal[e / 2])));
  };
  // The blur of the surface `hit` crosses, at the crossing (metres).
  auto blur_at = [&](const SheetHit& hit) {
    const auto sheet = static_cast<size_t>(hit.sheet);
    const glm::uvec3& corner = sheets[sheet].triangle[hit.triangle];
    return (1 - hit.at.u - hit.at.v) * blur[sheet][corner[0]] + hit.at.u * blur[sheet][corner[1]] +
           hit.at.v * blur[sheet][corner[2]];
  };
  // Per voxel and axis (+x, +y, +z): the middle of a solid layer between two sharp sheets, not
  // a grain's, that the grid line crosses before the next centre (thin_layers.h), or NaN.
  constexpr double kNoLayer = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::array<double, 3>> layer_middle(n, {kNoLayer, kNoLayer, kNoLayer});
  auto sharp_sheet = [&](const SheetHit& hit) {
    return hit.sheet >= 0 &&
           model.surfaces[static_cast<size_t>(hit.sheet)].role != SurfaceRole::Grain &&
           blur_at(hit) < 0.5 * voxel_m;
  };
  parallel_chunks(n, 64, threads, [&](size_t begin, size_t end) {
    std::array<SheetHit, kEdgeRays + kSideVotes> hits;
    std::array<SheetHit, kEdgeRays> wall_hits;
    for (size_t v = begin; v < end; ++v) {
      const glm::dvec3 centre = volume.centre(volume.voxel(v));
      caster.cast(centre, dirs, hits);
      solid[v] = voted_solid(model, sheets, hits) ? 1 : 0;
      wall_caster.cast(centre, edge_dirs, wall_hits);
      for (int e = 0; e < kEdgeRays; ++e)
        wall_crossing[v][static_cast<size_t>(e)] =
            plane_distance(wall_hits[static_cast<size_t>(e)], walls, e);
      for (int e = 0; e < kEdgeRays; ++e) {
        const SheetHit& hit = hits[static_cast<size_t>(e)];
        crossing[v][static_cast<size_t>(e)] = plane_distance(hit, sheets, e);
        if (crossing[v][static_cast<size_t>(e)] == kNone) continue;
        if (blur_at(hit) >= 0.5 * voxel_m) soft[v] |= static_cast<uint8_t>(1u << e);
      }
      // A thin layer ahead along +x, +y, +z: a second sharp sheet behind the first before the
      // next centre, the side of it that faces the first solid.
      const glm::ivec3 coord = volume.voxel(v);
      for (int a = 0; a < 3; ++a) {
        const SheetHit& first = hits[static_cast<size_t>(2 * a)];
        if (coord[a] + 1 >= volume.size[a] || !sharp_sheet(first) || first.at.t >= voxel_m)
          continue;
        const double from = first.at.t + 1e-4 * voxel_m;
        SheetHit second;
        const glm::vec3& d = dirs[static_cast<size_t>(2 * a)];
        caster.cast(centre + glm::dvec3(d) * from, std::span(&d, 1), std::span(&second, 1));
        if (!sharp_sheet(second) || from + second.at.t >= voxel_m ||
            !solid_side(model, sheets, second, d))
          continue;
        layer_middle[v][static_cast<size_t>(a)] = 0.5 * (first.at.t + from + second.at.t);
      }
    }
  });
  // Sheet distances: over the sharp crossings, and the soft ones between solid and empty.
  // Outline distances: over the wall crossings between solid and empty.
  const size_t step[3] = {1, static_cast<size_t>(volume.size.x),
                          static_cast<size_t>(volume.size.x) * volume.size.y};
  volume.sheet_distance.assign(n, static_cast<float>(voxel_m));
  volume.outline_distance.assign(n, static_cast<float>(voxel_m));
  for (size_t v = 0; v < n; ++v) {
    const glm::ivec3 coord = volume.voxel(v);
    for (int e = 0; e < kEdgeRays; ++e) {
      const int a = e / 2, q = coord[a] + (e % 2 == 0 ? 1 : -1);
      const bool other_solid =
          q >= 0 && q < volume.size[a] && solid[e % 2 == 0 ? v + step[a] : v - step[a]];
      const bool outline = other_solid != static_cast<bool>(solid[v]);
      const float wall = wall_crossing[v][static_cast<size_t>(e)];
      if (outline && wall != kNone)
        volume.outline_distance[v] = std::min(volume.outline_distance[v], wall);
      const float d = crossing[v][static_cast<size_t>(e)];
      if (d == kNone || ((soft[v] >> e & 1u) && !outline)) continue;
      volume.sheet_distance[v] = std::min(volume.sheet_distance[v], d);
    }
  }

  // Regions: solid face neighbours whose segment crosses no sharp surface are joined.
  std::vector<uint32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0u);
  for (size_t v = 0; v < n; ++v) {
    if (!solid[v]) continue;
    const glm::ivec3 coord = volume.voxel(v);
    for (int a = 0; a < 3; ++a) {
      const size_t e = 2 * static_cast<size_t>(a);  // the +a direction
      if (coord[a] + 1 >= volume.size[a] || (crossing[v][e] != kNone && !(soft[v] >> e & 1u)))
        continue;
      const size_t w = v + step[a];
      if (!solid[w]) continue;
      const uint32_t rv = find_root(parent, static_cast<uint32_t>(v));
      const uint32_t rw = find_root(parent, static_cast<uint32_t>(w));
      if (rv != rw) parent[std::max(rv, rw)] = std::min(rv, rw);
    }
  }
  volume.region.assign(n, kEmptyRegion);
  std::vector<uint32_t> label(n, kEmptyRegion);
  std::vector<glm::dvec3> points;
  for (size_t v = 0; v < n; ++v) {
    if (!solid[v]) continue;
    const uint32_t root = find_root(parent, static_cast<uint32_t>(v));
    if (label[root] == kEmptyRegion) label[root] = ++volume.regions;
    volume.region[v] = label[root];
    points.push_back(volume.centre(volume.voxel(v)));
  }
  volume.solid = points.size();
  // Moves the samples of solid voxels to the points of `moves` ((voxel, point), in voxel order).
  auto move_samples = [&](const std::vector<std::pair<size_t, glm::dvec3>>& moves) {
    for (size_t v = 0, p = 0, m = 0; v < n && m < moves.size(); ++v) {
      if (!solid[v]) continue;
      if (moves[m].first == v) points[p] = moves[m++].second;
      ++p;
    }
  };
  // Grains thinner than a voxel: the voxels they pass through sample a point inside them.
  const auto inside_grains = thin_grain_samples(model, volume, solid);
  move_samples(inside_grains);
  volume.grain_samples = inside_grains.size();
  // Layers thinner than a voxel: one voxel of each grid line that misses one samples its middle.
  std::vector<ThinLayer> layers;
  for (size_t v = 0; v < n; ++v)
    for (int a = 0; a < 3; ++a)
      if (!std::isnan(layer_middle[v][static_cast<size_t>(a)]))
        layers.push_back({v, a, layer_middle[v][static_cast<size_t>(a)]});
  std::vector<char> taken(n, 0);
  for (const auto& [v, at] : inside_grains) taken[v] = 1;
  const auto inside_layers = thin_layer_samples(volume, solid, layers, taken);
  move_samples(inside_layers);
  volume.layer_samples = inside_layers.size();
  volume.seconds_classify = seconds_since(t0);

  const auto t1 = Clock::now();
  std::vector<glm::dvec3> colour(points.size());
  std::vector<glm::dvec2> material(points.size());
  diffusion.diffuse_channels(points, colour, material);
  if (modulation)
    for (size_t p = 0; p < points.size(); ++p)
      colour[p] = (*modulation)(points[p], colour[p], strength);
  volume.seconds_diffuse = seconds_since(t1);
  volume.colour.assign(n, glm::vec3(0));
  volume.material.assign(n, glm::vec2(0));
  size_t p = 0;
  for (size_t v = 0; v < n; ++v) {
    if (!solid[v]) continue;
    volume.colour[v] = glm::vec3(colour[p]);
    volume.material[v] = glm::vec2(material[p]);
    ++p;
  }
  // Empty voxels next to solid ones take their solid face neighbours' mean.
  for (size_t v = 0; v < n; ++v) {
    if (solid[v]) continue;
    const glm::ivec3 coord = volume.voxel(v);
    glm::dvec3 c(0);
    glm::dvec2 m(0);
    int count = 0;
    for (int a = 0; a < 3; ++a) {
      for (int s = -1; s <= 1; s += 2) {
        const int q = coord[a] + s;
        if (q < 0 || q >= volume.size[a]) continue;
        const size_t w = s > 0 ? v + step[a] : v - step[a];
        if (!solid[w]) continue;
        c += glm::dvec3(volume.colour[w]);
        m += glm::dvec2(volume.material[w]);
        ++count;
      }
    }
    if (count == 0) continue;
    volume.colour[v] = glm::vec3(c / static_cast<double>(count));
    volume.material[v] = glm::vec2(m / static_cast<double>(count));
  }
  volume.stones = volume_stones(model);
  return volume;
}

}  // namespace cutaway
