#include "material/relief_map.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "base/colour.h"
#include "base/error.h"

namespace cutaway {

namespace {

/// The slope of the height at texel (x, y) toward +x (`dx` 1, dy 0) or +y (dx 0, dy 1): a
/// central difference over the covered neighbours, one-sided with one, 0 with neither, per
/// texel step.
double slope(const TexelCanvas& canvas, int x, int y, int dx, int dy) {
  auto height_at = [&canvas](int xx, int yy, double& h) {
    if (canvas.wrap_u) xx = (xx % canvas.width + canvas.width) % canvas.width;
    if (xx < 0 || yy < 0 || xx >= canvas.width || yy >= canvas.height) return false;
    const size_t i = static_cast<size_t>(yy) * canvas.width + xx;
    if (!canvas.covered[i]) return false;
    h = canvas.relief[i].x;
    return true;
  };
  double here = 0, before = 0, after = 0;
  height_at(x, y, here);
  const bool has_before = height_at(x - dx, y - dy, before);
  const bool has_after = height_at(x + dx, y + dy, after);
  if (has_before && has_after) return 0.5 * (after - before);
  if (has_after) return after - here;
  if (has_before) return here - before;
  return 0.0;
}

}  // namespace

ReliefMaps bake_relief_maps(const TexelCanvas& canvas, int padding) {
  if (canvas.relief.size() != canvas.covered.size())
    throw InternalError("bake_relief_maps: the canvas has no relief channel");
  ReliefMaps maps;
  size_t covered = 0;
  for (size_t i = 0; i < canvas.covered.size(); ++i) {
    if (!canvas.covered[i]) continue;
    const double h = canvas.relief[i].x;
    maps.low_m = covered > 0 ? std::min(maps.low_m, h) : h;
    maps.high_m = covered > 0 ? std::max(maps.high_m, h) : h;
    maps.texel_m += 0.5 * (canvas.relief[i].y + canvas.relief[i].z);
    ++covered;
  }
  if (covered > 0) maps.texel_m /= static_cast<double>(covered);
  // Both maps as canvases (the normal's components and the height in the colour channel), so
  // that they are dilated and filled as colours are.
  TexelCanvas normal(canvas.width, canvas.height, canvas.wrap_u);
  TexelCanvas height(canvas.width, canvas.height, canvas.wrap_u);
  const double range = maps.high_m - maps.low_m;
  for (int y = 0; y < canvas.height; ++y)
    for (int x = 0; x < canvas.width; ++x) {
      const size_t i = static_cast<size_t>(y) * canvas.width + x;
      if (!canvas.covered[i]) continue;
      const glm::dvec2 metres(canvas.relief[i].y, canvas.relief[i].z);
      // Slopes in metres of height per metre of skin, across (+x) and up (-y).
      const double across = metres.x > 0 ? slope(canvas, x, y, 1, 0) / metres.x : 0.0;
      const double up = metres.y > 0 ? -slope(canvas, x, y, 0, 1) / metres.y : 0.0;
      normal.colour[i] = 0.5 * (glm::normalize(glm::dvec3(-across, -up, 1.0)) + 1.0);
      height.colour[i] = glm::dvec3(range > 0 ? (canvas.relief[i].x - maps.low_m) / range : 0.5);
      normal.covered[i] = height.covered[i] = 1;
    }
  for (TexelCanvas* map : {&normal, &height}) {
    dilate(*map, padding);
    fill_background(*map);
  }
  maps.normal.resize(normal.colour.size() * 3);
  maps.height.resize(height.colour.size());
  for (size_t i = 0; i < normal.colour.size(); ++i) {
    for (int k = 0; k < 3; ++k) maps.normal[3 * i + k] = unit_to_byte(normal.colour[i][k]);
    maps.height[i] = unit_to_byte(height.colour[i].x);
  }
  return maps;
}

}  // namespace cutaway
