#include "pieces/cut_cells.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "base/constants.h"
#include "base/error.h"
#include "model/spine_bend.h"

namespace cutaway {

bool in_half_space(const CutCells& cells, const CellFace& face, const glm::dvec3& x,
                   double tolerance_m) {
  const Plane& p = cells.planes[face.plane];
  const double d = glm::dot(x - p.point, p.normal);
  return face.outward ? d <= tolerance_m : d >= -tolerance_m;
}

bool in_cell(const CutCells& cells, const Cell& cell, const glm::dvec3& x, int skip_plane,
             double tolerance_m) {
  for (const CellFace& f : cell.faces) {
    if (f.plane != skip_plane && !in_half_space(cells, f, x, tolerance_m)) return false;
  }
  return true;
}

namespace {

/// Positions of parallel planes `spacing` apart, centred on [lo, hi]: floor(span / spacing) - 1
/// of them (at least one), so that the two end pieces are 1 to 1.5 spacings thick.
std::vector<double> centred_positions(double lo, double hi, double spacing) {
  const int count = std::max(1, static_cast<int>(std::floor((hi - lo) / spacing)) - 1);
  std::vector<double> out;
  for (int k = 0; k < count; ++k)
    out.push_back(0.5 * (lo + hi) + (k - 0.5 * (count - 1)) * spacing);
  return out;
}

/// The slabs between consecutive planes of one axis (indices into planes), as faces.
std::vector<std::vector<CellFace>> slabs(const std::vector<int>& planes) {
  std::vector<std::vector<CellFace>> out;
  for (size_t k = 0; k <= planes.size(); ++k) {
    std::vector<CellFace> faces;
    if (k > 0) faces.push_back({planes[k - 1], false});
    if (k < planes.size()) faces.push_back({planes[k], true});
    out.push_back(faces);
  }
  return out;
}

/// A plane through the straight axis (x = z = 0) turned to contain a leaned `axis`: its normal
/// made perpendicular to the axis's direction, through the axis's point. No axis: `p` itself.
Plane along_axis(const Plane& p, const CutAxis* axis) {
  if (!axis) return p;
  const glm::dvec3 n = p.normal - glm::dot(p.normal, axis->direction) * axis->direction;
  return {axis->point, glm::normalize(n)};
}

/// The axis's direction (+Y without one) and its point at height `y`.
struct AxisAt {
  glm::dvec3 up, point;
};
AxisAt axis_at(const CutAxis* axis, double y) {
  const glm::dvec3 up = axis ? axis->direction : glm::dvec3(0, 1, 0);
  const glm::dvec3 base = axis ? axis->point : glm::dvec3(0.0);
  return {up, base + up * ((y - base.y) / up.y)};
}

/// The plane of unit `normal` through `pivot` leaned by knife.lean_rad about `line` (a unit
/// direction in it), then moved by knife.offset_m along its new normal.
Plane leaned(const glm::dvec3& normal, const glm::dvec3& line, const glm::dvec3& pivot,
             const KnifeWobble& knife) {
  const glm::dvec3 n = glm::normalize(normal * std::cos(knife.lean_rad) +
                                      glm::cross(line, normal) * std::sin(knife.lean_rad));
  return {pivot + knife.offset_m * n, n};
}

/// The halves' plane `p` (through the axis, turned to it) wobbled by `knife`: leaned about the
/// line of `p` across the axis at height `mid_y`, then moved along its normal.
Plane wobbled(const Plane& p, const CutAxis* axis, double mid_y, const KnifeWobble& knife) {
  if (knife.lean_rad == 0.0 && knife.offset_m == 0.0) return p;
  const AxisAt at = axis_at(axis, mid_y);
  return leaned(p.normal, glm::normalize(glm::cross(p.normal, at.up)), at.point, knife);
}

/// The halves' plane across the axis (normal along it) at height `mid_y`, wobbled by `knife`:
/// leaned about a line in the plane through the axis, then moved along its normal; with a
/// bent axis, its cross plane there.
Plane across_axis(const CutAxis* axis, const BentAxis* bent, double mid_y,
                  const KnifeWobble& knife) {
  if (bent) return bent->bend->cross_plane(mid_y);
  const AxisAt at = axis_at(axis, mid_y);
  return leaned(at.up, glm::normalize(glm::cross(at.up, glm::dvec3(0, 0, 1))), at.point, knife);
}

}  // namespace

CutCells make_cut_cells(const CutSpec& cut, const glm::dvec3& bbox_min, const glm::dvec3& bbox_max,
                        const BentAxis* bent_axis, const CutAxis* cut_axis,
                        const KnifeWobble& knife, bool across) {
  CutCells out;
  switch (cut.type) {
    case CutType::Whole: out.cells.push_back({}); break;
    case CutType::Halves:
    case CutType::Plane: {
      Plane p;
      if (cut.type == CutType::Plane) p = cut.plane;
      const double mid_y = 0.5 * (bbox_min.y + bbox_max.y);
      if (cut.type == CutType::Halves && across)
        p = across_axis(cut_axis, bent_axis,
                        bent_axis ? 0.5 * (bent_axis->y_min + bent_axis->y_max) : mid_y, knife);
      else if (cut.type == CutType::Halves)
        p = wobbled(along_axis(p, cut_axis), cut_axis, mid_y, knife);
      out.planes.push_back(p);
      out.cells.push_back({{{0, true}}});
      out.cells.push_back({{{0, false}}});
      break;
    }
    case CutType::Slices: {
      CUTAWAY_CHECK(cut.thickness_m > 0);
      std::vector<int> ids;
      const double lo = bent_axis ? bent_axis->y_min : bbox_min.y;
      const double hi = bent_axis ? bent_axis->y_max : bbox_max.y;
      for (double y : centred_positions(lo, hi, cut.thickness_m)) {
        ids.push_back(static_cast<int>(out.planes.size()));
        out.planes.push_back(bent_axis ? bent_axis->bend->cross_plane(y)
                                       : Plane{{0, y, 0}, {0, 1, 0}});
      }
      for (auto& faces : slabs(ids)) out.cells.push_back({faces});
      break;
    }
    case CutType::Wedges: {
      CUTAWAY_CHECK(cut.count >= 2);
      const int n = cut.count;
      // Half-plane k points along e_k = (cos t, 0, -sin t); its plane's normal (sin t, 0,
      // cos t) points towards decreasing angles. Opposite half-planes (even n) share a plane.
      std::vector<int> plane_of(n);
      std::vector<bool> flipped(n, false);
      for (int k = 0; k < n; ++k) {
        if (n % 2 == 0 && k >= n / 2) {
          plane_of[k] = plane_of[k - n / 2];
          flipped[k] = true;
          continue;
        }
        const double t = 2 * kPi * k / n;
        plane_of[k] = static_cast<int>(out.planes.size());
        out.planes.push_back(along_axis({{0, 0, 0}, {std::sin(t), 0, std::cos(t)}}, cut_axis));
      }
      for (int k = 0; k < n; ++k) {
        const int next = (k + 1) % n;
        // The wedge from angle k to k+1 lies on the -normal side of half-plane k's plane and on
        // the +normal side of half-plane k+1's (each with its own normal, flipped if shared).
        Cell cell;
        cell.faces.push_back({plane_of[k], !flipped[k]});
        const CellFace second{plane_of[next], flipped[next]};
        if (second.plane != cell.faces[0].plane) cell.faces.push_back(second);
        out.cells.push_back(cell);
      }
      break;
    }
    case CutType::Dice: {
      CUTAWAY_CHECK(cut.size_m > 0);
      std::vector<int> ids[3];
      for (int axis = 0; axis < 3; ++axis) {
        for (double c : centred_positions(bbox_min[axis], bbox_max[axis], cut.size_m)) {
          glm::dvec3 point(0.0), normal(0.0);
          point[axis] = c;
          normal[axis] = 1;
          ids[axis].push_back(static_cast<int>(out.planes.size()));
          out.planes.push_back({point, normal});
        }
      }
      for (const auto& fx : slabs(ids[0]))
        for (const auto& fy : slabs(ids[1]))
          for (const auto& fz : slabs(ids[2])) {
            Cell cell;
            for (const auto* f : {&fx, &fy, &fz})
              cell.faces.insert(cell.faces.end(), f->begin(), f->end());
            out.cells.push_back(cell);
          }
      break;
    }
  }
  return out;
}

}  // namespace cutaway
