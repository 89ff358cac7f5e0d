// How an object is cut into pieces (doc/scene-format.md, Cuts; doc/algorithms.md §4): a cut
// is a set of planes in the object's frame (axis +Y), and every piece is one convex cell of them.
#pragma once

#include <string>
#include <vector>

#include "base/outcome.h"
#include "base/plane.h"

namespace cutaway {

/// The kinds of cut of the scene format and of `cutaway piece --cut`.
enum class CutType { Whole, Halves, Slices, Wedges, Dice, Plane };

/// One cut, in metres (object frame). Only the fields of its type are used.
struct CutSpec {
  CutType type = CutType::Whole;
  double thickness_m = 0;  ///< slices: distance between the parallel planes, > 0
  int count = 0;           ///< wedges: number of wedges, >= 2
  double size_m = 0;       ///< dice: edge of the cubes, > 0
  Plane plane;             ///< plane: the one cutting plane (both halves are pieces)
};

/// The most pieces one cut may make of one object (scene files; `cutaway piece` may use it too).
inline constexpr int kMaxPiecesPerCut = 512;
/// The thinnest slice and the smallest dice a cut may use, metres (0.5 mm).
inline constexpr double kMinCutLength_m = 0.5e-3;

/// A short label of `cut` in millimetres: "whole", "halves", "slices:6mm", "wedges:8",
/// "dice:12mm" or "plane" (lengths with up to 3 decimals, trailing zeros dropped).
std::string cut_label(const CutSpec& cut);

/// Every number of `cut` after its label, written so that it reads back exactly ("%.17g"):
/// "LABEL thickness size count px py pz nx ny nz", for fingerprints and cache keys (which
/// must tell apart cuts whose labels round to the same micrometre).
std::string cut_exact_text(const CutSpec& cut);

/// How far an object reaches, metres: the bounding cylinder about its axis (+Y).
struct ObjectExtents {
  double radius_m = 0;  ///< largest distance from the axis
  double height_m = 0;  ///< extent along the axis
};

struct Template;

/// The extents of a template's skin, estimated from its curves without sweeping: the profile's
/// largest r times the section loop's largest radius relative to its radius at angle 0 (the loop
/// is scaled so that this radius equals r), and the profile's y range. A template without an
/// `around` skin uses the bounds of its mesh surfaces (MeshData::points).
/// @pre `t` came from parse_template (its mesh surfaces' meshes are read)
ObjectExtents template_extents(const Template& t);

/// Estimated number of pieces `cut` makes of an object within `extents`: whole 1, halves and
/// plane 2, wedges `count`, slices ceil(height / thickness) + 1 (the end caps are pieces too),
/// dice the cubes of the bounding box, ceil(2 r / size)^2 * ceil(height / size). Saturates at
/// 1e9 (tiny lengths do not overflow).
long long estimate_piece_count(const CutSpec& cut, const ObjectExtents& extents);

/// An upper bound of the area of the cut faces `cut` makes of an object within `extents`, both
/// sides of every plane, m^2 (what the cap textures cover). A plane meets the bounding cylinder
/// (radius r, height h) in at most 2 r sqrt(h^2 + 4 r^2); a wedge's half-plane in r h; a
/// slice or dice plane across the axis in pi r^2. Saturates at 1e12 m^2.
double estimate_cut_area(const CutSpec& cut, const ObjectExtents& extents);

/// An estimate of an object's volume within `extents`, m^3: the ellipsoid of revolution in its
/// bounding cylinder, 2/3 pi r^2 h (a fruit fills about that much of it).
double estimate_object_volume(const ObjectExtents& extents);

/// The most cap-texture texels the objects of one scene, or one batch asset, may need, as
/// estimated from their cut-face area (estimate_cut_area) at the texel density: 64 M, about
/// 340 MB of RGBA with mipmaps.
inline constexpr double kMaxCapTexels = 64e6;

/// Passes when `cut_area_m2` of cut faces baked at `texels_per_mm` stays within kMaxCapTexels,
/// else fails with the rule in words, naming the density and the estimate (for a message at
/// the field that set the density or made the area).
Check check_cap_texels(double cut_area_m2, double texels_per_mm);

/// The density at which `cut_area_m2` of cut faces fits kMaxCapTexels: `wanted` when it fits,
/// else the largest multiple of 0.1 texels per mm that does (rounded down), or 0 when not even
/// 0.1 does. For a density the user did not set: a big scene is baked coarser, not refused.
double fitting_texels_per_mm(double cut_area_m2, double wanted);

}  // namespace cutaway
