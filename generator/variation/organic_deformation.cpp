#include "variation/organic_deformation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "base/constants.h"
#include "base/random.h"

namespace cutaway {

namespace {

/// Purpose tag of the organic deformation's stream in derive_seed paths.
constexpr uint64_t kPurposeOrganic = 0x6f7267616e;  // "organ"

/// A uniform direction on the unit sphere (three normals, normalised; Muller 1959).
glm::dvec3 sphere_direction(Rng& rng) {
  for (;;) {
    const glm::dvec3 v(rng.normal(), rng.normal(), rng.normal());
    const double n = glm::length(v);
    if (n > 1e-9) return v / n;
  }
}

/// A uniform horizontal unit direction (angle uniform in [0, 2 pi)).
glm::dvec3 horizontal_direction(Rng& rng) {
  const double a = rng.uniform(0.0, 2 * kPi);
  return {std::cos(a), 0.0, std::sin(a)};
}

}  // namespace

Check check_organic(const OrganicSpec& spec, double amount, double metres_per_unit) {
  char text[400];
  const double lumps =
      spec.lump_size_m > 0 ? 2 * kPi * spec.lump_amplitude_m * amount / spec.lump_size_m : 0.0;
  if (lumps > kMaxLumpStrain) {
    std::snprintf(text, sizeof text,
                  "lumps this high for their size could fold the object over itself: at "
                  "variation amount %.3g they stretch space by up to %.3g (2 pi amplitude "
                  "amount / size; at most %.2g); make them at most %.3g high at this size, "
                  "or larger",
                  amount, lumps, kMaxLumpStrain,
                  kMaxLumpStrain * spec.lump_size_m / (2 * kPi * amount) / metres_per_unit);
    return Check::none(text);
  }
  if (spec.lopsided * amount > kMaxLopsided) {
    std::snprintf(text, sizeof text,
                  "lopsided %.3g at variation amount %.3g is %.3g (at most %.2g: the flatter "
                  "side would be squeezed to nothing)",
                  spec.lopsided, amount, spec.lopsided * amount, kMaxLopsided);
    return Check::none(text);
  }
  if (spec.lean_rad * amount > kMaxLeanRad) {
    std::snprintf(text, sizeof text,
                  "lean %.3g degrees at variation amount %.3g is %.3g degrees (at most 30)",
                  spec.lean_rad / (kPi / 180), amount, spec.lean_rad * amount / (kPi / 180));
    return Check::none(text);
  }
  return {};
}

double organic_reach_m(const OrganicSpec& spec, double amount, double radius_m, double height_m) {
  const double lumps = spec.lump_amplitude_m * amount;
  return lumps + spec.lopsided * amount * (radius_m + lumps) / 3 +
         std::tan(std::min(spec.lean_rad * amount, kMaxLeanRad)) * height_m;
}

glm::dvec3 OrganicDeformation::map(const glm::dvec3& p) const {
  glm::dvec3 q = p;
  for (const LumpWave& w : lumps)
    q += w.direction * (w.amplitude * std::sin(glm::dot(w.wave, p) + w.phase));
  if (lopsided > 0) {
    const double u = glm::dot(q - centre, lopsided_direction);
    q += lopsided_direction * (lopsided / (2 * reach_m) * (u * u - reach_m * reach_m / 3));
  }
  return q + lean * (q.y - base_y);
}

glm::dmat3 OrganicDeformation::jacobian(const glm::dvec3& p) const {
  // glm matrices are column-major: m[c][r] is row r of column c; a b^T has a[r] b[c] there.
  auto outer = [](const glm::dvec3& a, const glm::dvec3& b) {
    glm::dmat3 m(0.0);
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) m[c][r] = a[r] * b[c];
    return m;
  };
  glm::dmat3 j_lumps(1.0);
  glm::dvec3 q = p;
  for (const LumpWave& w : lumps) {
    const double phase = glm::dot(w.wave, p) + w.phase;
    j_lumps += outer(w.direction, w.wave) * (w.amplitude * std::cos(phase));
    q += w.direction * (w.amplitude * std::sin(phase));
  }
  glm::dmat3 j_lopsided(1.0);
  if (lopsided > 0) {
    const double u = glm::dot(q - centre, lopsided_direction);
    j_lopsided += outer(lopsided_direction, lopsided_direction) * (lopsided * u / reach_m);
  }
  const glm::dmat3 j_lean = glm::dmat3(1.0) + outer(lean, {0, 1, 0});
  return j_lean * j_lopsided * j_lumps;
}

double OrganicDeformation::lump_strain() const {
  double s = 0;
  for (const LumpWave& w : lumps) s += std::fabs(w.amplitude) * glm::length(w.wave);
  return s;
}

bool OrganicDeformation::identity() const {
  for (const LumpWave& w : lumps)
    if (w.amplitude != 0) return false;
  return lopsided == 0 && lean == glm::dvec3(0.0);
}

OrganicDeformation draw_organic(const Template& t, const DsModel& model, uint64_t seed) {
  OrganicDeformation d;
  const OrganicSpec& spec = t.organic;
  const double amount = t.variation_amount;
  if (!(amount > 0) || !spec.any()) return d;
  Rng rng(derive_seed(seed, {kPurposeOrganic}));
  // Every draw is made whether or not its part is used, so that each part's values do not
  // depend on the others being written.
  std::array<double, kLumpWaves> share{};
  double shares = 0;
  for (double& s : share) shares += s = rng.uniform(0.5, 1.0);
  const double amplitude = spec.lump_amplitude_m * amount * rng.uniform(0.6, 1.0);
  for (int i = 0; i < kLumpWaves; ++i) {
    LumpWave& w = d.lumps[i];
    w.wave = sphere_direction(rng) * (spec.lump_size_m > 0 ? 2 * kPi / spec.lump_size_m : 0.0);
    w.direction = sphere_direction(rng);
    w.phase = rng.uniform(0.0, 2 * kPi);
    w.amplitude = spec.lump_size_m > 0 ? amplitude * share[i] / shares : 0.0;
  }
  d.lopsided_direction = horizontal_direction(rng);
  d.lopsided = spec.lopsided * amount * rng.uniform(0.3, 1.0);
  const glm::dvec3 lean_direction = horizontal_direction(rng);
  d.lean = lean_direction * std::tan(spec.lean_rad * amount * rng.uniform(0.3, 1.0));
  const auto [skin_lo, skin_hi] = skin_bounds(model);
  d.centre = {0.5 * (skin_lo.x + skin_hi.x), 0.0, 0.5 * (skin_lo.z + skin_hi.z)};
  d.base_y = skin_lo.y;
  if (!(d.lopsided > 0)) return d;
  // The lumped model's reach from the skin's centre (every vertex: sheets and grains too, and
  // the lumps' largest displacement, so that |u| <= R wherever the lopsided stretch is applied:
  // on the lumps' image of the whole model); only the lopsided stretch uses it.
  double reach = 0;
  for (const DsSurface& s : model.surfaces)
    for (auto vh : s.mesh.vertices()) {
      const auto& q = s.mesh.point(vh);
      reach = std::max(reach, std::hypot(q[0] - d.centre.x, q[2] - d.centre.z));
    }
  d.reach_m = reach + amplitude;
  if (!(reach > 0)) d.lopsided = 0;
  return d;
}

void deform_model(const OrganicDeformation& d, DsModel& model) {
  if (d.identity()) return;
  for (DsSurface& surface : model.surfaces)
    for (auto vh : surface.mesh.vertices()) {
      const auto& q = surface.mesh.point(vh);
      const glm::dvec3 m = d.map({q[0], q[1], q[2]});
      surface.mesh.set_point(vh, DsMesh::Point(m.x, m.y, m.z));
    }
  if (d.lean != glm::dvec3(0.0))
    model.cut_axis = CutAxis{{0.0, d.base_y, 0.0}, glm::normalize(d.lean + glm::dvec3(0, 1, 0))};
  update_bounds(model);
}

}  // namespace cutaway
