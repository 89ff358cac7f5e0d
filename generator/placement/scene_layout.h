// Seeded drop poses of pieces in a container (doc/algorithms.md §4), which settle_pieces then
// lets physics settle. The pile is kept as a height field over the container (Tetris-like
// dropping of conservative piece footprints), so the poses never interpenetrate. Three
// arrangements: pile (the lowest of random positions, cut faces towards the camera), fan (the
// pieces of one object in a row, each lying partly on the one before) and scatter (spread over
// the container, each on free ground).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "pieces/shaded_mesh.h"
#include "placement/container.h"

namespace cutaway {

/// One piece to place: its mesh in its object frame and the outward normal of its largest cap
/// there (zero for a whole object), its arrangement and, for a fan, its row and place in it.
struct LayoutPiece {
  const ShadedMesh* mesh = nullptr;  ///< #V >= 1, metres
  glm::dvec3 cap_normal{0.0};        ///< unit, or zero
  Arrangement arrange = Arrangement::Pile;
  /// The object the piece was cut from, or -1 for none. fan: the pieces of one group form one
  /// row (all of group -1 one row); together: a group's pieces lie side by side.
  int group = -1;
  int rank = 0;  ///< fan: the order along the row (the pieces' cells)
  /// fan: the piece's cut planes; a piece with one (an end of the object, rounded below its
  /// cap) starts the row, where its cap is a flat rest for the next slice instead of it
  /// sliding off the last one; the object's other end closes the row.
  int cut_faces = 2;
};

/// The most height-field cells along one side of the layout grid: a wider container gets cells
/// larger than cell_m (layout_pieces), 4 M cells (32 MB) at most.
inline constexpr int kMaxLayoutCells = 2048;

/// Options of layout_pieces.
struct LayoutOptions {
  double cell_m = 0.001;        ///< height-field cell edge, metres (at least; see kMaxLayoutCells)
  int candidates = 64;          ///< random positions tried per piece
  double clearance_m = 0.001;   ///< gap left under each drop pose (clear of the bodies' margins), m
  double centre_weight = 0.25;  ///< score = rest height + centre_weight * distance to the axis
  /// The same for scattered and fanned pieces that heap (no free ground left): nearly the
  /// lowest anywhere, so that a crowded board fills its low gaps before a heap rises
  double heap_centre_weight = 0.02;
  glm::dvec3 to_camera{0, 0.7, 0.7};  ///< direction from the scene towards the camera
  double none_radius_m = 0.2;         ///< resting radius on the floor (container type none)
  double tilt_deg = 12;               ///< random tilt of each piece's facing direction, degrees
  double fan_tilt_deg = 18;      ///< fan: how far each piece's cap leans along the row, degrees
  double fan_step = 0.5;         ///< fan: advance per piece, fraction of its length in the row
  int fan_headings = 12;         ///< fan: row directions tried, evenly spaced from a seeded one
  int fan_min_row = 3;           ///< fan: a row that fits nowhere splits while halves keep this
  double scatter_gap_m = 0.008;  ///< scatter: free ground kept around each piece, metres
  double scan_step_m = 0.004;    ///< scatter without a gap: the grid of positions scanned, m
};

/// Where one piece goes: scene point = translation + rotation * (object-frame point).
struct Placement {
  bool placed = false;  ///< false: no position keeps it over the resting area (too large)
  glm::dquat rotation{1, 0, 0, 0};
  glm::dvec3 translation{0.0};
};

/// Places `pieces`: first the fan rows (by group: an end of the object, the slices in rank
/// order, the other end), then the others in the given order. Every piece is turned, then put at
/// the lowest height where every vertex is above the container's resting surface (exact for its
/// convex surfaces) and its footprint (per cell: its lowest and highest surface points over the
/// cell) clears the height field of the pieces before it by clearance_m; the height field then
/// rises to the piece's top.
/// - pile: the largest cap faces halfway between up and `to_camera` (taken no lower than the
///   horizon, so a camera below the container gives caps facing up; a whole object stands
///   upright), tilted by up to tilt_deg and spun at random; of `candidates` random positions
///   (every vertex over the resting area) the lowest by score is taken;
/// - fan: a row, each piece's cap up and leaning fan_tilt_deg along the row (the first flat),
///   advancing fan_step of its length; of `candidates` random row centres, each in one of
///   fan_headings directions, whose pieces keep scatter_gap_m of free ground to the pieces
///   before the row, the lowest by score; the gap relaxes as for scatter; a row that fits
///   nowhere even without a gap is split into two rows while each keeps fan_min_row pieces,
///   and one that cannot be split may lie over the pieces before it; the pieces of a row that
///   fits nowhere at all heap as pile pieces do;
/// - scatter: turned as for pile; of `candidates` positions whose footprint, grown by
///   scatter_gap_m, is free of pieces, the farthest from the pieces placed (best candidate);
///   where none is found the gap halves until it is 0, and then every position on a grid of
///   scan_step_m is tried; with no free ground left the piece heaps as a pile piece does, the
///   lowest scored with heap_centre_weight (on a crowded board or plate pieces fill the low
///   gaps, then stack, as they would on a real one);
/// - together: as scatter, but the pieces of one group (object) are laid one after another,
///   where the first of them comes, side by side as a cook lays a fruit's halves: the first
///   where a copy of its footprint would also be free beside it (two radii of its footprint's
///   bounds and scatter_gap_m away, in one of 8 directions, over the resting area) while there
///   is such a place; each other one, of `candidates` positions drawn round a seeded one of its
///   group's pieces laid (0.8 to 2 times the sum of the two footprints' radii and
///   scatter_gap_m away), the nearest to them, and where none of those is free, as scatter
///   searches, the nearest to them.
/// Deterministic in `seed`.
/// @returns one placement per piece, in input order (placed false: no position keeps every
///          vertex over the container's resting area, a piece larger than the container)
std::vector<Placement> layout_pieces(const std::vector<LayoutPiece>& pieces,
                                     const Container& container, const LayoutOptions& options,
                                     uint64_t seed);

/// The pieces' indices 0 .. n-1 in a seeded order (Fisher-Yates with the stream of `seed`
/// reserved for it), the order they are laid out and settled in, so that the kinds mix in the
/// pile. Deterministic in `seed`.
std::vector<size_t> placement_order(size_t n, uint64_t seed);

/// The direction a layout is made for, and the turn about +Y that takes its placements to the
/// scene (layout_view).
struct LayoutView {
  glm::dvec3 to_camera{0.0};  ///< unit, for LayoutOptions::to_camera
  double turn_back = 0;       ///< radians about +Y, counter-clockwise seen from above
};

/// What of the camera's direction `to_camera` (from the scene towards the camera, unit) a
/// layout in `container` is made for. The camera's azimuth (its direction seen from above, 0
/// at the front, +Z) decides how much the pile depends on it. A round container (bowl, plate,
/// the floor's resting disc) is the same from every side: the layout is made for the camera
/// turned to the front and turned back by the azimuth. A board is not: the layout is made for
/// the camera turned to the nearest side of the board (the azimuth rounded to a quarter turn),
/// as pieces are laid out for someone at one side of it, and stays where it is (turn_back 0).
/// The elevation is rounded to a nanoradian, so that a camera moved round the scene, which
/// keeps it only up to rounding, gives the same direction to the last bit (it is part of the
/// placements' cache key). A camera straight above or below counts as at the front.
LayoutView layout_view(const Container& container, const glm::dvec3& to_camera);

}  // namespace cutaway
