// The containers of scenes (doc/scene-format.md: bowl, plate, board, none): their meshes for
// export, and the surface pieces rest on, as a height above the floor for the layout.
// Scene frame: +Y up, metres, the container standing on y = 0 centred on the Y axis.
#pragma once

#include <optional>

#include "assets/scene_assets.h"
#include "placement/container.h"

namespace cutaway {

/// The bowl and plate profiles, the board's box (choices of this code; the scene format fixes
/// only the sizes):
/// - bowl: inner surface an ellipse from the well bottom (y = 0.08 H, floor thickness) up to the
///   rim (y = H) at inner radius R - wall (wall = 0.03 D); outer surface an ellipse down to a
///   foot ring of radius 0.45 R at y = 0;
/// - plate: a flat well of radius 0.62 R at y = 0.3 H, rising to the rim at y = H (power 1.6);
/// - board: a box W x D x H with its edges and corners rounded to kBoardEdgeRadius_m (at most
///   0.3 of its smallest side), with uv: the top seen from above (u along X, v along Z, 0..1),
///   for the wood's texture (board_wood.h);
/// - none: the floor y = 0.
/// `segments` (>= 3): the bowl's and plate's segments around the axis; `profile_samples` (>= 2):
/// segments along each curve of their profiles. Every vertex lies on the surfaces above, so a
/// coarser mesh's inner surface lies inside the bowl or above the plate, never below the finer
/// one's (the physics collides with a coarse one: fewer triangles).
/// @return the container's mesh (linear colour `container.colour`, outward normals, closed),
///         or nothing for type none
std::optional<AssetMesh> container_mesh(const Container& container, int segments = 96,
                                        int profile_samples = 40);

/// The radius of a board's rounded edges, metres (a kitchen board's, 5 mm).
inline constexpr double kBoardEdgeRadius_m = 0.005;

/// The height (metres) of the surface that pieces rest on at (x, z), or nothing where pieces
/// may not rest (outside the bowl's or plate's inner rim, off the board, beyond `none_radius_m`
/// for type none).
std::optional<double> rest_height(const Container& container, double x, double z,
                                  double none_radius_m);

/// How far (metres, horizontally) the point (x, z) lies outside the area pieces may rest on
/// (rest_height's), 0 over it: beyond the board's edge (to its nearest point), beyond the bowl's
/// or plate's inner rim, or the `none_radius_m` disc of type none. A piece's overhang over the
/// container's edge is the largest of its points' (doc/algorithms.md §4, Settling).
double resting_overhang(const Container& container, double x, double z, double none_radius_m);

/// The steepest slope (rise over run) a heap of pieces keeps, 45 degrees: steeper than the
/// angle of repose of loose pieces (whose tangent is about their friction coefficient,
/// SettleOptions::friction, 0.8), as slices stack steeper than a heap of round pieces; the
/// bound refuses only what cannot fit.
inline constexpr double kHeapSlope = 1.0;
/// The fraction of a heap's volume its pieces fill, at most: the densest packing of equal
/// spheres (0.74); loose pieces fill less (random close packing, 0.64).
inline constexpr double kHeapPacking = 0.74;

/// How much the container holds, m^3 of heap (pieces and the gaps between them): a bowl's
/// inside below its rim (the half ellipsoid of its inner surface) and a cone over its rim; a
/// plate, a cone over its rim; a board, a hip roof over its top; the floor (type none), a cone
/// of radius `none_radius_m`. Heaps slope at kHeapSlope.
double heap_capacity(const Container& container, double none_radius_m);

/// The radius (metres) about the Y axis within which pieces can rest (the inner rim, half the
/// board's diagonal, `none_radius_m` for type none).
double rest_radius(const Container& container, double none_radius_m);

}  // namespace cutaway
