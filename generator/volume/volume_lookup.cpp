#include "volume/volume_lookup.h"

#include <algorithm>
#include <cmath>

namespace cutaway {

VolumeSample sample_volume(const InteriorVolume& volume, const glm::dvec3& point) {
  VolumeSample sample;
  const glm::dvec3 g = (point - volume.origin) / volume.voxel_m;
  int base[3];
  double frac[3];
  for (int a = 0; a < 3; ++a) {
    if (!(g[a] >= 0 && g[a] <= volume.size[a] - 1)) return sample;  // also NaN
    base[a] = std::min(static_cast<int>(std::floor(g[a])), volume.size[a] - 2);
    frac[a] = g[a] - base[a];
  }
  size_t index[8];
  double weight[8];
  for (int c = 0; c < 8; ++c) {
    const int o[3] = {c & 1, c >> 1 & 1, c >> 2 & 1};
    index[c] = volume.index(base[0] + o[0], base[1] + o[1], base[2] + o[2]);
    weight[c] = 1;
    for (int a = 0; a < 3; ++a) weight[c] *= o[a] ? frac[a] : 1 - frac[a];
  }
  // Solid or empty first: the interpolated signed distance to the outline.
  double outline = 0;
  for (int k = 0; k < 8; ++k) {
    const double e = volume.outline_distance[index[k]];
    outline += weight[k] * (volume.region[index[k]] == kEmptyRegion ? -e : e);
  }
  if (outline <= 0) return sample;
  // Then the solid region: each one's interpolated signed distance to its border; the
  // highest wins.
  bool have = false;
  uint32_t best = kEmptyRegion;
  double best_score = 0;
  for (int c = 0; c < 8; ++c) {
    const uint32_t r = volume.region[index[c]];
    if (r == kEmptyRegion) continue;
    double score = 0;
    for (int k = 0; k < 8; ++k) {
      const double d = volume.sheet_distance[index[k]];
      score += weight[k] * (volume.region[index[k]] == r ? d : -d);
    }
    if (!have || score > best_score || (score == best_score && r < best)) {
      have = true;
      best = r;
      best_score = score;
    }
  }
  sample.region = best;
  glm::dvec3 colour(0);
  glm::dvec2 material(0);
  double total = 0;
  for (int c = 0; c < 8; ++c) {
    if (volume.region[index[c]] != best) continue;
    colour += weight[c] * glm::dvec3(volume.colour[index[c]]);
    material += weight[c] * glm::dvec2(volume.material[index[c]]);
    total += weight[c];
  }
  if (total <= 0) {  // the point sits on the far side of every voxel of its region
    for (int c = 0; c < 8; ++c) {
      if (volume.region[index[c]] != best) continue;
      colour += glm::dvec3(volume.colour[index[c]]);
      material += glm::dvec2(volume.material[index[c]]);
      total += 1;
    }
  }
  sample.colour = glm::vec3(colour / total);
  sample.material = glm::vec2(material / total);
  return sample;
}

}  // namespace cutaway
