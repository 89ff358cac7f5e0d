// A check of the material channels shared by the backends' tests: they are diffused from the
// same rays with the same weights as the colours, so a model whose vertices carry their colours'
// red and green as material channels must diffuse to materials equal to the colours' red and
// green.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <vector>

#include "diffusion/diffusion.h"
#include "model/ds_model.h"

namespace cutaway::test {

/// What material_channel_errors measured.
struct MaterialChannelErrors {
  double material_vs_colour = 0;  ///< largest |material - (colour.r, colour.g)|
  double colour_change = 0;       ///< largest colour difference with and without materials
  double distinct_values = 0;     ///< spread of the diffused roughness (0: a constant, no test)
};

/// Copies (front.r, front.g) and (back.r, back.g) into every vertex's material channels of
/// `model`, makes a backend with `make` and diffuses `points` with and without materials.
inline MaterialChannelErrors material_channel_errors(
    DsModel model, const std::vector<glm::dvec3>& points,
    const std::function<std::unique_ptr<DiffusionBackend>(const DsModel&)>& make) {
  for (DsSurface& s : model.surfaces) {
    for (auto vh : s.mesh.vertices()) {
      auto& d = s.mesh.data(vh);
      d.material_front = {d.front[0], d.front[1]};
      d.material_back = {d.back[0], d.back[1]};
    }
  }
  const auto backend = make(model);
  std::vector<glm::dvec3> colour(points.size());
  std::vector<glm::dvec2> material(points.size());
  backend->diffuse_channels(points, colour, material);
  const std::vector<glm::dvec3> alone = backend->diffuse(points);
  MaterialChannelErrors e;
  double lo = 1e300, hi = -1e300;
  for (size_t i = 0; i < points.size(); ++i) {
    e.material_vs_colour = std::max({e.material_vs_colour, std::fabs(material[i].x - colour[i].r),
                                     std::fabs(material[i].y - colour[i].g)});
    for (int k = 0; k < 3; ++k)
      e.colour_change = std::max(e.colour_change, std::fabs(alone[i][k] - colour[i][k]));
    lo = std::min(lo, material[i].x);
    hi = std::max(hi, material[i].x);
  }
  e.distinct_values = hi - lo;
  return e;
}

}  // namespace cutaway::test
