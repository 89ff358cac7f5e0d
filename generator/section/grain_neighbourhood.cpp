#include "section/grain_neighbourhood.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "model/grain_components.h"

namespace cutaway {

GrainNeighbourhood::GrainNeighbourhood(const DsModel& model, const Plane& plane) {
  for (const GrainComponent& grain : grain_components(model)) {
    const double reach = kNearGrainRadii * grain.radius;
    if (std::fabs(glm::dot(grain.centre - plane.point, plane.normal)) >= reach) continue;
    centre_.push_back(grain.centre);
    reach_.push_back(reach);
  }
}

bool GrainNeighbourhood::near(const glm::dvec3& p) const {
  for (size_t g = 0; g < centre_.size(); ++g)
    if (glm::distance(p, centre_[g]) < reach_[g]) return true;
  return false;
}

}  // namespace cutaway
