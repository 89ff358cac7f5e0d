#include "diffusion/cube_directions.h"

#include <cmath>
#include <cstdint>
#include <cstring>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "base/constants.h"
#include "base/error.h"
#include "base/random.h"

namespace cutaway {

namespace {

double area_element(double x, double y) { return std::atan2(x * y, std::sqrt(x * x + y * y + 1)); }

/// Point (a, b) of face f on the cube [-1, 1]^3.
glm::dvec3 face_point(int f, double a, double b) {
  switch (f) {
    case 0: return {1, b, -a};
    case 1: return {-1, b, a};
    case 2: return {a, 1, -b};
    case 3: return {a, -1, b};
    case 4: return {a, b, 1};
    default: return {-a, b, -1};
  }
}

}  // namespace

CubeDirections make_cube_directions(int n) {
  CUTAWAY_CHECK_OP(n, >=, 1);
  CubeDirections d;
  d.n = n;
  d.direction.reserve(6 * n * n);
  d.solid_angle.reserve(6 * n * n);
  for (int f = 0; f < 6; ++f) {
    for (int row = 0; row < n; ++row) {
      const double y0 = -1 + 2.0 * row / n, y1 = -1 + 2.0 * (row + 1) / n;
      for (int col = 0; col < n; ++col) {
        const double x0 = -1 + 2.0 * col / n, x1 = -1 + 2.0 * (col + 1) / n;
        const glm::dvec3 p = face_point(f, 0.5 * (x0 + x1), 0.5 * (y0 + y1));
        d.direction.push_back(glm::vec3(glm::normalize(p)));
        d.solid_angle.push_back(area_element(x0, y0) - area_element(x0, y1) - area_element(x1, y0) +
                                area_element(x1, y1));
      }
    }
  }
  return d;
}

glm::dmat3 cube_rotation(const glm::dvec3& point) {
  uint64_t bits[3];
  for (int k = 0; k < 3; ++k) {
    const double v = point[k] == 0 ? 0.0 : point[k];  // -0 and +0 get one rotation
    std::memcpy(&bits[k], &v, sizeof v);
  }
  constexpr uint64_t kPurposeCubeRotation = 0x63756265726f74ull;  // "cuberot"
  Rng rng(derive_seed(kPurposeCubeRotation, {bits[0], bits[1], bits[2]}));
  const double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
  constexpr double kTwoPi = 2 * kPi;
  const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
  const glm::dquat q(b * std::cos(kTwoPi * u3), a * std::sin(kTwoPi * u2),
                     a * std::cos(kTwoPi * u2), b * std::sin(kTwoPi * u3));  // (w, x, y, z)
  return glm::mat3_cast(q);
}

}  // namespace cutaway
