// Artistic silhouettes (doc/algorithms.md §6; paper §5, Fig. 10; Northrup and Markosian
// 2000, "Artistic silhouettes: a hybrid approach"): for the scene's camera, the silhouette,
// crease and boundary edges of every instance, hidden parts removed, linked into long strokes
// with a tapered width. The OpenGL preview draws them (render/gl/stroke_renderer.h) and the
// POV-Ray export writes them as sphere_sweep objects (pov_export.h).
#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "assets/scene_assets.h"

namespace cutaway {

/// One stroke: a polyline in the scene frame with a width at each point.
struct Stroke {
  std::vector<glm::dvec3> points;  ///< scene frame, metres; at least 2
  std::vector<double> width_px;    ///< one per point: full width in pixels of the image the
                                   ///< strokes were extracted for (thin at both ends)
  glm::dvec3 colour{0.0};          ///< linear RGB
  bool closed = false;             ///< the last point connects back to the first (not repeated)
};

/// How extract_strokes() finds and shapes strokes.
struct StrokeOptions {
  int width = 0, height = 0;  ///< image size in pixels; 0 = SceneAssets::width/height
  double strength = 1.0;      ///< scales every width; <= 0 gives no strokes
  double crease_deg = 60;     ///< an edge between two faces whose normals differ by more than
                              ///< this (degrees) is a crease (cap outlines: about 90)
  double width_px = 0;        ///< widest point of a long stroke at strength 1, pixels; 0 = auto:
                              ///< max(1.5, height / 320)
  double min_length_px = 4;   ///< shorter strokes (projected length) are dropped
  double max_turn_deg = 70;   ///< linking never turns by more than this at a joint
  int smoothing = 2;          ///< Laplacian smoothing passes over each stroke's points
  double smoothing_shift_px = 1.5;  ///< the most a pass moves a point, pixels: smoothing takes
                                    ///< out the zigzag of mesh edges, not the corners of long
                                    ///< edges (a box's outline)
  double darkening = 0.12;          ///< colour = darkening * mean colour of the faces along it
  double structure_width = 0.6;     ///< width of structure lines (inside cut faces) relative to
                                    ///< outlines; 0 turns them off
};

/// Extracts the strokes of `assets` as seen from `assets.camera` in an image of the options'
/// size (the same projection as render_scene_preview: vertical fov, aspect of the image).
///
/// Per instance, on the mesh welded by exact vertex position (parts that share seam vertices
/// become adjacent), an edge is a feature when it is
/// - a silhouette: one adjacent face turns toward the eye, the other away;
/// - a crease: the normals of its two faces differ by more than crease_deg and one of them
///   faces the eye (every cap outline, where a cut face meets the skin);
/// - a boundary (one face) or non-manifold (more than two) edge;
/// - a structure line: an edge of two nearly coplanar faces (one facing the eye) that use
///   different copies of its vertices. Cross-sections split their vertices along the
///   cut segments (paper Fig. 3c), so these are the outlines of the structures inside a cut
///   face (flesh and gel, rings, seeds): the strokes "along structures" of the paper's Fig. 10.
///   They are linked apart from the outlines and drawn structure_width times as wide.
/// Degenerate (zero-area) faces are ignored. Visibility: a CPU z-buffer of all instances at the
/// image size; an edge is kept when at least half of its sample points (about one per pixel,
/// at least 3) lie within a depth tolerance of the nearest surface in their 3x3 pixel
/// neighbourhood. Visible feature edges of one instance are linked at shared vertices into
/// polylines, each time continuing with the edge that turns least (in the image), never more
/// than max_turn_deg; strokes shorter than min_length_px are dropped, the rest smoothed. Width
/// along a stroke of projected length L at arc-length fraction t:
///   w = W * s * (0.15 + 0.85 * sin(pi t)^0.6)  (open), W * s * (0.8 + 0.2 cos(2 pi t)) (closed)
/// with W the width option and s = strength * min(1, sqrt(L / (30 W))) (short strokes thinner).
/// Deterministic: the same assets and options give the same strokes, in instance order.
/// @param assets as render_scene_preview requires (finite, valid indices, a valid camera)
/// @throws InternalError on an image size outside 1..16384 or a bad instance mesh index
std::vector<Stroke> extract_strokes(const SceneAssets& assets, const StrokeOptions& options = {});

}  // namespace cutaway
