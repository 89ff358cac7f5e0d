#include "material/skin_texture.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

#include "base/error.h"
#include "material/texel_bake.h"

namespace cutaway {

namespace {
constexpr double kPoleTolerance = 1e-12;
bool at_pole(double t_profile) {
  return t_profile <= kPoleTolerance || t_profile >= 1 - kPoleTolerance;
}
}  // namespace

glm::ivec2 skin_texture_size(const DsSurface& skin, const SkinTextureOptions& options) {
  // Lengths of the ring edges (one t_profile) and of the profile edges (one t_section).
  std::map<double, double> ring, line;
  const DsMesh& mesh = skin.mesh;
  for (auto eh : mesh.edges()) {
    const auto he = mesh.halfedge_handle(eh, 0);
    const auto a = mesh.from_vertex_handle(he), b = mesh.to_vertex_handle(he);
    const auto pa = mesh.data(a).param, pb = mesh.data(b).param;
    const double length = (mesh.point(a) - mesh.point(b)).norm();
    if (pa[0] == pb[0]) ring[pa[0]] += length;
    if (pa[1] == pb[1]) line[pa[1]] += length;
  }
  double around = 0, along = 0;
  for (const auto& [t, length] : ring) around = std::max(around, length);
  for (const auto& [t, length] : line) along = std::max(along, length);
  // Multiples of 4, the block size of GPU texture compression (the texture repeats in u and
  // spans the skin in v whatever its size: the coordinates do not change).
  auto texels = [&](double metres) {
    const int n = static_cast<int>(std::ceil(metres * options.texels_per_m));
    int side = (n + 3) / 4 * 4;
    if (options.power_of_two) {
      side = 16;
      while (side < n && 2 * side <= options.max_size) side *= 2;
    }
    return std::clamp(side, 16, options.max_size / 4 * 4);
  };
  return {texels(around), texels(along)};
}

std::array<glm::dvec2, 3> skin_corner_uv(const ShadedMesh& mesh, const glm::uvec3& t) {
  std::array<glm::dvec2, 3> uv;
  std::array<double, 3> t_profile;
  for (int k = 0; k < 3; ++k) {
    const glm::dvec2 p = mesh.param[t[k]];
    uv[k] = {p.y, 1 - p.x};
    t_profile[k] = p.x;
  }
  // A corner at t_profile 0 or 1 is a pole when no other corner shares its t_profile (the
  // triangle leaves the end of the profile, where one vertex stands for every t_section).
  std::array<bool, 3> pole;
  for (int k = 0; k < 3; ++k)
    pole[k] = at_pole(t_profile[k]) && t_profile[(k + 1) % 3] != t_profile[k] &&
              t_profile[(k + 2) % 3] != t_profile[k];
  double lo = 2, hi = -1;
  for (int k = 0; k < 3; ++k)
    if (!pole[k]) lo = std::min(lo, uv[k].x), hi = std::max(hi, uv[k].x);
  if (hi - lo > 0.5)
    for (int k = 0; k < 3; ++k)
      if (!pole[k] && uv[k].x < 0.5) uv[k].x += 1;
  for (int k = 0; k < 3; ++k) {
    if (!pole[k]) continue;
    double sum = 0;
    int n = 0;
    for (int j = 0; j < 3; ++j)
      if (!pole[j]) sum += uv[j].x, ++n;
    if (n > 0) uv[k].x = sum / n;
  }
  return uv;
}

std::vector<glm::dvec2> unwrap_skin(ShadedMesh& skin) {
  if (skin.param.size() != skin.position.size())
    throw InternalError("unwrap_skin: the mesh has no sweep parameters");
  std::vector<glm::dvec2> uv(skin.position.size());
  std::vector<uint8_t> assigned(skin.position.size(), 0);
  std::map<std::tuple<unsigned, double, double>, unsigned> copies;
  for (glm::uvec3& t : skin.triangle) {
    const std::array<glm::dvec2, 3> corner = skin_corner_uv(skin, t);
    for (int k = 0; k < 3; ++k) {
      const unsigned v = t[k];
      if (!assigned[v]) {
        uv[v] = corner[k];
        assigned[v] = 1;
        continue;
      }
      if (uv[v] == corner[k]) continue;
      const auto key = std::make_tuple(v, corner[k].x, corner[k].y);
      auto it = copies.find(key);
      if (it == copies.end()) {
        it = copies.emplace(key, copy_vertex(skin, v, skin)).first;
        uv.push_back(corner[k]);
        assigned.push_back(1);
      }
      t[k] = it->second;
    }
  }
  return uv;
}

SkinTexture bake_skin_texture(const std::vector<const ShadedMesh*>& parts,
                              const std::vector<const std::vector<glm::dvec2>*>& uv,
                              glm::ivec2 size, const SkinPatterns* patterns,
                              const ColourModulation* modulation, double strength,
                              const SkinTextureOptions& options) {
  TexelCanvas canvas(size.x, size.y, true);
  const bool relief = patterns && patterns->has_relief();
  if (relief) canvas.relief.assign(canvas.covered.size(), glm::dvec3(0.0));
  for (size_t i = 0; i < parts.size(); ++i) {
    std::vector<glm::dvec2> texel(uv[i]->size());
    for (size_t v = 0; v < texel.size(); ++v) texel[v] = (*uv[i])[v] * glm::dvec2(size);
    rasterise(*parts[i], texel, patterns, modulation, strength, canvas);
  }
  SkinTexture out;
  if (relief) out.relief = bake_relief_maps(canvas, options.padding);
  dilate(canvas, options.padding);
  fill_background(canvas);
  out.srgb = srgb_pixels(canvas);
  return out;
}

}  // namespace cutaway
