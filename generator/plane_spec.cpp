#include "plane_spec.h"

#include <cmath>
#include <regex>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace cutaway {

Plane parse_plane_spec(const std::string& spec, double metres_per_unit) {
  static const std::string num = R"(\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*)";
  static const std::regex axis_form(R"(\s*([xyzXYZ])\s*=)" + num);
  static const std::regex point_normal_form(num + "," + num + "," + num + "/" + num + "," + num +
                                            "," + num);
  std::smatch m;
  Plane plane;
  if (std::regex_match(spec, m, axis_form)) {
    const int axis = std::tolower(m[1].str()[0]) - 'x';
    plane.point = glm::dvec3(0.0);
    plane.point[axis] = std::stod(m[2].str()) * metres_per_unit;
    plane.normal = glm::dvec3(0.0);
    plane.normal[axis] = 1;
    return plane;
  }
  if (std::regex_match(spec, m, point_normal_form)) {
    for (int k = 0; k < 3; ++k) {
      plane.point[k] = std::stod(m[1 + k].str()) * metres_per_unit;
      plane.normal[k] = std::stod(m[4 + k].str());
    }
    const double len = glm::length(plane.normal);
    if (!(len > 0) || !std::isfinite(len)) {
      throw std::invalid_argument("'" + spec + "': the plane's normal must not be zero");
    }
    plane.normal /= len;
    return plane;
  }
  throw std::invalid_argument("'" + spec +
                              "' is not a plane: write AXIS=VALUE (e.g. y=20) or "
                              "px,py,pz/nx,ny,nz (a point and a normal, template units)");
}

}  // namespace cutaway
