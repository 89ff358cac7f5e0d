// Sweeps of the paper's sketching interface (§4.1; doc/algorithms.md §1): a profile curve in
// the vertical plane and a section loop in the horizontal plane become a DS triangle mesh.
#pragma once

#include "model/ds_model.h"
#include "model/template.h"

namespace cutaway {

/// Type I sweep (`around`): the section loop, scaled about the axis so that its radius at angle
/// 0 equals the profile's r(t), at every profile height (Snyder and Kajiya 1992).
/// Point (t, s) = (r(t) rho(s)/rho0 cos phi(s), y(t), -r(t) rho(s)/rho0 sin phi(s)).
/// A grid of (#profile samples) x (#section samples) vertices; a profile end on the axis
/// becomes a pole (triangle fan). Normals point away from the axis (front side).
/// Sample counts follow tmpl.edge_m (metres); in an N-fold template the section count is a
/// multiple of N, so identical folds get identical samples. Vertex params: (t_profile,
/// t_section), both normalised arc length (section from angle 0, counter-clockwise seen from +Y).
/// @pre spec.kind == Around and the spec passed check_template_curves
/// @param max_vertices the vertices left of the model's budget (kMaxModelVertices)
/// @throws InputError at resolution.edge when the surface would exceed max_vertices
DsSurface sweep_around(const SurfaceSpec& spec, const Template& tmpl,
                       size_t max_vertices = kMaxModelVertices);

/// Type II sweep (`within`), one closed component per fold: the closed profile is split at its
/// lowest and highest points into inner and outer rails r_in(y), r_out(y); at each height the
/// fold's section loop (in its fold frame: u along the fold centre, w across) is placed with
/// the uniform scale k = (r_out - r_in)/(u_max - u_min), u_min on the inner rail, w scaled
/// about the fold centre line; poles close the top and bottom. Normals point outwards.
/// Vertex params: t_section from the loop's outermost point (largest u), counter-clockwise
/// seen from +Y; t_profile interpolated between the two rails' profile parameters (the closed
/// profile's parameter runs from its lowest point, counter-clockwise in the profile plane).
/// @pre spec.kind == Within, tmpl.symmetry == NFold, the spec passed check_template_curves
/// @throws InputError at the section when a placed loop leaves its fold, or at resolution.edge
///         when the surface would exceed max_vertices (the vertices left of kMaxModelVertices)
DsSurface sweep_within(const SurfaceSpec& spec, const Template& tmpl,
                       size_t max_vertices = kMaxModelVertices);

}  // namespace cutaway
