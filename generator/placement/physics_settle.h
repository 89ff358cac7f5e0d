// Rigid-body settling of placed pieces with Bullet (doc/algorithms.md §4, Settling): every
// piece a rigid body (its collision_shape, mass = density x volume), the container static
// convex tiles (a box for the board) on a table at y = 0, stepped with a fixed time step (the
// contacts of a step computed on several threads, in the serial order: ordered_dispatcher.h),
// bodies added in input order, until the layout rests or a time cap is reached.
// A piece that has rested for freeze_after_s is frozen (made static where it lies), so the
// work follows the pieces still moving; once none moves, every piece is freed for up to
// free_seconds more (when some piece was frozen).
// A piece that ends outside the container, or hanging over its edge by more than
// max_overhang of its size, is dropped again from above the pile, nearer the axis; after
// `max_redrops` it is reported as not placed, never silently lost. Settling ends with the
// stability check: the layout, in a new world at rest, may move at most `stable_motion_m` in
// `verify_seconds`; if it moves more it settles on from there and is checked again. When the
// last check does not pass, the layout of the check that moved least within the limit is kept.
#pragma once

#include <vector>

#include "placement/collision_shape.h"
#include "placement/container.h"
#include "placement/scene_layout.h"

namespace cutaway {

/// One piece to settle: its collision shape (object frame) and its drop pose.
struct SettleBody {
  const CollisionShape* shape = nullptr;  ///< required
  double density_kg_m3 = 1000;            ///< > 0
  Placement drop;  ///< where it starts, at rest; not placed: the piece is left out
  /// The outward unit normal (in its own frame) of the one cut face it should rest showing (a
  /// half, a wedge's end), or zero: none (a slice, whose two faces both show, or no cap).
  glm::dvec3 cut_face{0.0};
};

/// Options of settle_pieces. Lengths in metres, times in seconds.
struct SettleOptions {
  double time_step_s = 1.0 / 240;  ///< fixed step
  double max_seconds = 8;          ///< simulated time cap per round of drops
  double margin_m = 0.00025;       ///< collision margin around each convex part
  /// Bullet's sequential impulse iterations per step (with 20, a bowl of 64 slices did not
  /// come to rest in 8 s; with 40 it rested after 1.75 s).
  int solver_iterations = 40;
  /// The same for the stability check and the settling after a failed one: a new world starts
  /// without the contact impulses that settling built up step after step, and with 40
  /// iterations a settled salad sagged 6.7 mm while they built up again; with 100, 1.7 mm.
  int check_solver_iterations = 100;
  double verify_seconds = 1.0;     ///< simulated time of the stability check
  double stable_motion_m = 0.001;  ///< the most any corner may move in the check (metres)
  /// A check passes (no more settling) when no corner moves more than this, half the limit:
  /// with the limit itself, 64 slices in a bowl ended at 0.997 mm, a hair inside it.
  double check_motion_m = 0.0005;
  /// Stability checks, each after a round of settling. The rounds end at a check that passes
  /// (check_motion_m), at one that moves more than an earlier check within stable_motion_m, or
  /// after this many. When the last does not pass, the layout of the check that moved least,
  /// within stable_motion_m, is kept; with none within it the last one's, with its motion
  /// (counted until it passed the limit).
  int max_verify_rounds = 3;
  /// After a failed check only the pieces that moved more than check_motion_m in it, and those
  /// whose bounding boxes come within this of theirs, settle on; the others stay where the
  /// check left them (metres). Settling every piece again unsettled pieces that had rested: the
  /// market stall's steadiest check moved 0.88 mm that way, 0.71 mm this way, in half the time;
  /// a heap of 160 pieces ended at 2.66 mm, now 0.48 mm, one of 320 at 4.13 mm, now 1.33 mm.
  double resettle_gap_m = 0.002;
  double friction = 0.8;  ///< Coulomb friction (piece on piece and on the container)
  /// Rolling (and spinning) resistance, metres: soft produce flattens where it rests, and the
  /// contact patch resists rolling with a torque up to this x the normal force. Without it a
  /// rounded avocado half rolled 0.5 mm a second on the flat board for three stability checks;
  /// with 0.5 mm it rests after one.
  double rolling_friction_m = 0.0005;
  double linear_damping = 0.2;  ///< fraction of velocity lost per second
  double angular_damping = 0.5;
  double sleep_speed_m_s = 0.005;  ///< a body below this speed ...
  double sleep_spin_rad_s = 0.15;  ///< ... and this spin for 2 s sleeps (Bullet's rule)
  /// The layout is at rest when every body sleeps or no corner of any body's collision shape
  /// moved more than this in the last quarter second (checked every quarter second), metres.
  double rest_motion_m = 0.00015;
  /// A body that has rested this long (no corner moved more than rest_motion_m in each quarter
  /// second) is frozen: made static where it lies, so that the solver works only on the bodies
  /// still moving and settling grows with them, not with the whole pile. The stability check
  /// runs with every body free again. 0: nothing is frozen.
  double freeze_after_s = 0.5;
  /// Once no piece moves, frozen pieces are freed and the layout runs on, every piece free,
  /// until it rests or for at most this long (seconds): a piece frozen before others came to
  /// lie on it settles under their weight, as it will in the stability check. Skipped when no
  /// piece is frozen then: the layout already rested with every piece free.
  double free_seconds = 1.0;
  /// The bowl's and plate's collision mesh (container_mesh): segments around the axis and
  /// along each profile curve (the exported mesh has 96 and 40). Its chords lie on the open
  /// side of the exported surface: on a 26 cm bowl at most 0.6 mm above it.
  int container_segments = 32, container_profile_samples = 12;
  int max_redrops = 3;  ///< drops again of a piece that left the container
  /// A piece may hang over the container's edge (resting_overhang of its collision shape's
  /// corners) by at most this share of its size (the longest side of its corners' bounding
  /// box) and is dropped again otherwise: food is not laid half over a board's edge. Half the
  /// fifth a reviewer accepts, so that what a layout ends with is well inside it.
  double max_overhang = 0.1;
  /// A piece whose cut face (SettleBody::cut_face) ends turned down, its normal's upward
  /// component below this, is dropped again (as one that left the container), and kept as it
  /// lies after max_redrops: a half is laid cut face up, not on it (an avocado half with its
  /// stone rolled onto its cut face). Below -1: never.
  double min_cut_face_up = 0.0;
  /// The direction from the scene towards the camera (unit; zero: no camera). A piece whose cut
  /// face ends up but turned away from it, the normal's component along it below
  /// min_cut_face_seen, is spun where it lies about the vertical until the face leans towards
  /// the camera, and settled again (kept as it lies after max_redrops): the layout turned the
  /// face towards the camera, and a half that rolled onto its back showing the camera only a
  /// sliver of it (a thick half, its face seen edge on) is not the picture it promised.
  glm::dvec3 to_camera{0.0};
  /// At 0.5 a face may lean up to about 20 degrees away from a camera 50 degrees above the
  /// board (it is then seen at 30 degrees or more); straight up it shows 0.77.
  double min_cut_face_seen = 0.5;
  double none_radius_m = 0.2;  ///< resting radius on the floor (container type none)
};

/// What settle_pieces did.
struct SettleResult {
  std::vector<Placement> placements;  ///< one per body, input order; placed false: lost
  double simulated_s = 0;             ///< simulated seconds, all rounds
  int steps = 0;
  /// The bodies simulated, summed over the steps of settling (the stability checks left out): a
  /// frozen body (freeze_after_s) is not. The work of the settling, which grows with the pieces
  /// still moving rather than with the pile.
  long long body_steps = 0;
  bool all_asleep = false;  ///< the last round of settling came to rest (rest_motion_m) before
                            ///< the time cap (the free_seconds after it not counted)
  /// The stability check of `placements`: how far the farthest corner of any body's collision
  /// shape moved in verify_seconds simulated from rest in a new world (metres).
  double stability_motion_m = 0;
  bool stable = false;    ///< stability_motion_m <= stable_motion_m
  int verify_rounds = 0;  ///< stability checks run (a failed one is followed by settling)
  /// The check whose starting layout `placements` is: the last one, unless it did not pass
  /// (check_motion_m) and an earlier one moved less while within stable_motion_m.
  int kept_round = 0;
  int redrops = 0;  ///< drops again of pieces that had left the container, hung over its edge,
                    ///< lay on their cut face or turned it away from the camera
  int lost = 0;     ///< pieces still outside after max_redrops drops again
};

/// Settles `bodies` from their drop poses in `container` and checks that the result is at rest
/// (see the file comment). Deterministic: the same bodies and options give the same placements
/// whatever the thread count (a fixed order and step; the contacts of a step are computed on
/// TBB's threads and merged in the serial order: ordered_dispatcher.h). Errors: a placed body
/// without a shape or with a density <= 0 is a programming error (CUTAWAY_CHECK).
SettleResult settle_pieces(const std::vector<SettleBody>& bodies, const Container& container,
                           const SettleOptions& options);

}  // namespace cutaway
