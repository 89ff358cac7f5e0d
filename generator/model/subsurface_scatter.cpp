#include "model/subsurface_scatter.h"

#include <algorithm>

#include <glm/common.hpp>

namespace cutaway {

namespace {

double luminance(const glm::dvec3& linear) {
  return 0.2126 * linear.r + 0.7152 * linear.g + 0.0722 * linear.b;
}

}  // namespace

double subsurface_scatter_m(const Template& t, double translucency, double skin_size_m) {
  if (!(translucency > 0)) return 0.0;
  double scatter = std::min(
      {kMaxScatter_m, kScatterPerTranslucency_m * translucency, kScatterPerSize * skin_size_m});
  for (const GrainSpec& g : t.grains) {
    const double thinnest = 2 * glm::min(g.semi_axes.x, glm::min(g.semi_axes.y, g.semi_axes.z));
    if (luminance(g.back) < kDarkGrainLuminance) scatter = std::min(scatter, thinnest);
    if (g.core && luminance(g.core->back) < kDarkGrainLuminance)
      scatter = std::min(scatter, g.core->scale * thinnest);
  }
  return scatter;
}

}  // namespace cutaway
