#include "placement/hull_shape.h"

#include <cfloat>
#include <limits>

#include "base/error.h"

namespace cutaway {

namespace {

using Float4 = float __attribute__((vector_size(16)));
using Int4 = int __attribute__((vector_size(16)));

/// Blocks of four corners compared side by side.
constexpr int kChains = 2;

Float4 load(const float* p) {
  Float4 v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}

}  // namespace

HullShape::HullShape(std::span<const btVector3> corners) {
  CUTAWAY_CHECK(!corners.empty());
  for (const btVector3& c : corners) addPoint(c, false);
  recalcLocalAabb();
  m_shapeType = CUSTOM_POLYHEDRAL_SHAPE_TYPE;
  const size_t block = 4 * kChains;
  const size_t padded = (corners.size() + block - 1) / block * block;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  x_.assign(padded, nan);
  y_.assign(padded, nan);
  z_.assign(padded, nan);
  for (size_t i = 0; i < corners.size(); ++i) {
    x_[i] = corners[i].x();
    y_[i] = corners[i].y();
    z_[i] = corners[i].z();
  }
}

btVector3 HullShape::localGetSupportingVertexWithoutMargin(const btVector3& direction) const {
  const btVector3 d = direction * m_localScaling;
  const Float4 dx = {d.x(), d.x(), d.x(), d.x()}, dy = {d.y(), d.y(), d.y(), d.y()},
               dz = {d.z(), d.z(), d.z(), d.z()};
  // kChains independent blocks of four lanes, so that no comparison waits for the one before.
  // Lane j of block b keeps the first maximum of corners 4 (kChains k + b) + j over k: a later
  // corner replaces it only when strictly greater, as in Bullet's scan (from -FLT_MAX).
  Float4 best[kChains];
  Int4 index[kChains], at[kChains];
  for (int b = 0; b < kChains; ++b) {
    best[b] = Float4{-FLT_MAX, -FLT_MAX, -FLT_MAX, -FLT_MAX};
    index[b] = Int4{-1, -1, -1, -1};
    at[b] = Int4{4 * b, 4 * b + 1, 4 * b + 2, 4 * b + 3};
  }
  const Int4 step = {4 * kChains, 4 * kChains, 4 * kChains, 4 * kChains};
  for (size_t i = 0; i < x_.size(); i += 4 * kChains) {
    for (int b = 0; b < kChains; ++b) {
      const size_t k = i + 4 * static_cast<size_t>(b);
      Float4 dot = load(&x_[k]) * dx + load(&y_[k]) * dy;
      dot = dot + load(&z_[k]) * dz;
      const Int4 greater = dot > best[b];
      best[b] = greater ? dot : best[b];
      index[b] = greater ? at[b] : index[b];
      at[b] += step;
    }
  }
  // The greatest of the lanes' maxima; of equal ones, the lowest index (the first in order).
  int chosen = -1;
  float top = -FLT_MAX;
  for (int b = 0; b < kChains; ++b) {
    for (int j = 0; j < 4; ++j) {
      const int k = index[b][j];
      if (k < 0) continue;
      if (chosen < 0 || best[b][j] > top || (best[b][j] == top && k < chosen)) {
        top = best[b][j];
        chosen = k;
      }
    }
  }
  return getUnscaledPoints()[chosen < 0 ? 0 : chosen] * m_localScaling;
}

}  // namespace cutaway
