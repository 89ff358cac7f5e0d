// Cut pieces (doc/algorithms.md §4): a piece is the object's volume inside one convex cell of
// a cut. Its surface is the skin clipped to the cell, the walls of hollow regions clipped
// likewise, and one cap per cell face: the cross-section of that plane (paper §3.2) restricted
// to the cell, coloured by PMVC diffusion. The parts are stitched along their seams, so a piece
// of an object without hollows is a closed, consistently oriented 2-manifold.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "base/outcome.h"
#include "diffusion/diffusion.h"
#include "model/ds_model.h"
#include "pieces/cut_cells.h"
#include "pieces/shaded_mesh.h"
#include "section/cross_section.h"

namespace cutaway {

/// What a part of a piece's surface is.
/// Stone: the surface of a rigid surface outside the cell of the piece that holds it whole
/// (rigid_stones.h).
enum class PartKind { Skin, Wall, Stone, Cap };

/// One part of a piece's surface. Normals point out of the piece; colours are what that side
/// shows (skin: its front colour; wall: the colour of its non-hollow side; stone: the colour
/// of its inside; cap: diffused).
struct PiecePart {
  PartKind kind = PartKind::Skin;
  int surface = -1;  ///< skin, wall, stone: index into DsModel::surfaces
  int plane = -1;    ///< cap: index into CutCells::planes
  ShadedMesh mesh;
};

/// One piece: the parts of its surface, in the order skin, walls, stones, caps (by plane index).
struct Piece {
  int cell = -1;  ///< index into CutCells::cells
  std::vector<PiecePart> parts;
};

/// How pieces are made.
struct PieceOptions {
  CrossSectionOptions section;  ///< meshing of the caps (its edge_m: the template's edge);
                                ///< cut_pieces turns merge_boundary off
  /// Seam vertices closer than this (in edge_m, and at least 2 kOnPlane_m) are one: the same
  /// crossing computed by the clip and by the cap's triangulation differ by rounding, or by
  /// the kOnPlane_m that a split line may bend to pass through a cut vertex
  /// (arrange_split_lines).
  double stitch_tolerance = 1e-5;
  /// Which of the n pieces a cut makes are kept: their indices into the pieces in cell order,
  /// increasing, at least one; empty: all. Only the caps of kept pieces are coloured, so a
  /// scene that keeps a share of each cut pays PMVC for that share (a cap shared by a kept and
  /// a dropped piece is coloured whole).
  std::function<std::vector<size_t>(size_t n)> keep_pieces;
  /// Breaks ties between cells that hold equal shares of a rigid surface (holder_cell): the
  /// variant's seed.
  uint64_t stone_seed = 0;
};

/// Planes in general position (general_position): a plane that does not contain the object's
/// axis is moved along its normal until no surface vertex lies between kOnPlane_m (on the
/// plane, by symbolic perturbation) and kVertexClearance template edges from it, so that no two
/// crossings of the plane with the surfaces lie nanometres apart. A cut that still gives a
/// defective piece is redone up to kMaxCutAttempts - 1 times, attempt k first moving those
/// planes by k * kNudgeOffset template edges (2.5 um for a 2.5 mm edge). Planes through the
/// axis (halves, wedges, centred dice) never move: moved, they would pass micrometres from the
/// poles of the sweep.
constexpr int kMaxCutAttempts = 4;
constexpr double kNudgeOffset = 1e-3;
constexpr double kVertexClearance = 1e-4;
/// Distinct vertices of a piece are at least this far apart (metres), or the piece is defective.
constexpr double kMinVertexSeparation_m = 1e-9;

/// The pieces of one cut object and what making them cost.
struct PieceSet {
  CutCells cells;  ///< as cut: the planes moved by the last attempt's nudge
  /// The kept pieces (PieceOptions::keep_pieces), in cell order; cells the object misses give
  /// none.
  std::vector<Piece> pieces;
  size_t pieces_cut = 0;               ///< pieces the cut made, kept or not
  std::vector<CrossSection> sections;  ///< one per plane of `cells` (empty where it misses)
  DiffusedPoints diffused;             ///< PMVC evaluations over all caps
  size_t stitched_vertices = 0;        ///< seam vertices snapped or inserted
  double seconds_sections = 0;         ///< cross-sections: triangulation and diffusion (wall)
  /// Of which PMVC diffusion: with the caps made at once (run_with_shared_batches), the wall
  /// time of the backend's calls; one cap at a time, the caps' own seconds_diffuse, which
  /// include adaptive sampling's interpolation.
  double seconds_diffuse = 0;
  double seconds_clip = 0;  ///< clipping, stitching and checking
  // Counts and times are totals over all attempts.
  int attempts = 1;             ///< cuts made (1 unless the first was near-degenerate)
  size_t defective_pieces = 0;  ///< pieces of the last attempt that fail check_manifold (0
                                ///< for a closed skin but in rare configurations that
                                ///< kMaxCutAttempts do not escape)
};

/// Cuts `model` into pieces along `cut` (make_cut_cells with the model's bounds). Every plane is
/// cross-sectioned once, with the lines of all other planes as extra constraints (so the two
/// caps on either side of a cut are mirror images with equal colours), keeping only triangles
/// that some cell uses; the planes are meshed first, which cells hold a piece is decided, and
/// only triangles that a kept piece uses are coloured (PieceOptions::keep_pieces). Surfaces that
/// are hollow on one side (visible_front or visible_back false, not the skin) are the walls of
/// hollow regions: clipped and shown with the colour of their other side, facing the hollow. Grains
/// and other structure surfaces only colour the caps. A rigid surface (a stone) is never split
/// (rigid_stones.h): it is hollow inside for every piece, as a cavity, except the piece whose
/// cell holds most of it, which also gets the stone's surface outside its cell (stone parts),
/// so that piece holds the whole stone and everything in it. The planes are first put in general
/// position (kVertexClearance). Every piece is checked with check_manifold
/// (kMinVertexSeparation_m); when a kept one fails (a near-degenerate configuration: a surface edge
/// passing nanometres from the line where two cutting planes meet, so that the two caps' seams
/// cannot agree), the whole cut is redone with its planes nudged (kMaxCutAttempts; in the spirit of
/// symbolic perturbation, but with real sub-micrometre moves). The caps of the planes are meshed on
/// diffusion.threads() threads and coloured at once, on as many threads (up to 32 when it is 0)
/// that take them in turn, their diffusions in shared batches (shared_batches.h); one at a time
/// when it is 1. Deterministic: the result does not depend on the thread count.
/// @param model  its skin (surfaces[0]) closed and outward
/// @returns the pieces, or none (an expected outcome): kCutMisses when the cut misses the
///          object entirely (no piece), kPlaneMisses (cross_section.h) when a `plane` cut leaves
///          it whole
Outcome<PieceSet> cut_pieces(const DsModel& model, const CutSpec& cut,
                             const DiffusionBackend& diffusion, const PieceOptions& options);

/// Why cut_pieces gives no pieces (Outcome::reason), besides kPlaneMisses.
inline constexpr const char* kCutMisses = "the cut misses the object";

/// All parts of `piece` in one mesh (vertices of different parts stay separate), in part
/// order: the skin's and walls' triangles first, then the caps'.
ShadedMesh merge_parts(const Piece& piece);

/// The number of triangles of the skin and walls of `piece` (the first ones of merge_parts).
size_t surface_triangle_count(const Piece& piece);

/// Where each part's vertices start in merge_parts(piece): #parts + 1 offsets, the last one the
/// merged mesh's vertex count.
std::vector<unsigned> part_vertex_offsets(const Piece& piece);

/// The piece's skin part (parts[0] when the piece has skin), or null.
const PiecePart* skin_part(const Piece& piece);

}  // namespace cutaway
