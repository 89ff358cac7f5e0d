#include "base/area_sampling.h"

#include <algorithm>

#include "base/error.h"

namespace cutaway {

AreaSampler::AreaSampler(const std::vector<double>& areas) {
  double sum = 0;
  cumulative_.reserve(areas.size());
  for (double a : areas) {
    CUTAWAY_CHECK(a >= 0);
    sum += a;
    cumulative_.push_back(sum);
  }
}

AreaSample AreaSampler::draw(Rng& rng) const {
  CUTAWAY_CHECK(total() > 0);
  const double r = rng.uniform(0.0, total());
  AreaSample s;
  s.triangle =
      std::min(cumulative_.size() - 1,
               static_cast<size_t>(std::upper_bound(cumulative_.begin(), cumulative_.end(), r) -
                                   cumulative_.begin()));
  double u = rng.uniform(), v = rng.uniform();
  if (u + v > 1) {
    u = 1 - u;
    v = 1 - v;
  }
  s.weights = glm::dvec3(1 - u - v, u, v);
  return s;
}

}  // namespace cutaway
