// Reads and validates scene files (doc/scene-format.md, all of it). Every broken rule is an
// InputError "FILE:LINE:COL: field.path: rule"; templates a scene names are found (and, by
// load_scene, read and checked) here, so that layout and export never see YAML.
#pragma once

#include <string>
#include <string_view>

#include "scene/scene.h"

namespace cutaway {

/// Parses and validates scene text, and resolves every item's template file.
///
/// Units: lengths in the file are in its `units` (mm, cm or m; default mm) and come out in
/// metres (container sizes, camera eye and target, slice thickness, dice size); colours are sRGB
/// ("#rrggbb" or [r, g, b] in 0..1) and come out linear RGB.
///
/// Defaults: seed 0; units mm; no container (type none) when `container` is absent; bowl
/// 240 x 80 mm "#f3efe6", plate 260 x 20 mm "#fafafa", board 360 x 240 x 20 mm "#c49a6c";
/// an item's count 1, cut whole, keep 1, variation 1; no camera; render 1280 x 960, perlin 1,
/// silhouettes 1.
///
/// Template resolution: a value containing '/' or ending in ".yaml" is a path relative to the
/// scene file's directory (or absolute); otherwise it is a name ([a-z0-9_-]+) looked up as
/// NAME.yaml in `<scene dir>/../templates`, then in `$CUTAWAY_TEMPLATES` (when set), then in the
/// project's templates/ folder. The template files are not read (see load_scene).
///
/// @param text  the file's bytes (YAML 1.2 or JSON, UTF-8)
/// @param file  the scene's path: names it in messages, and relative template paths and
///              names are resolved from its directory
/// @return the scene (Scene::file = `file`)
/// @throws InputError for any rule of the format the text breaks (syntax, unknown or repeated
///         fields, types, ranges, a template that cannot be found), at the offending node
Scene parse_scene(std::string_view text, const std::string& file);

/// Parses `text` as parse_scene and reads every template it names, as load_scene does for the
/// text of a file (templates resolved from `file`'s directory).
/// @throws InputError as load_scene
Scene parse_scene_and_templates(std::string_view text, const std::string& file);

/// Reads the scene file at `path`, parses it as parse_scene, and reads every template it names
/// with load_template, so that a broken template is reported (at its own file, line and column).
/// Also refuses a cut that would make more than kMaxPiecesPerCut pieces of one object, estimated
/// from the template's extents (estimate_piece_count), at the cut's thickness or size.
/// @throws InputError as parse_scene, for the templates as load_template, and when the file
///         cannot be read
/// Also holds the scene to the totals of scene.h (kMaxSceneObjects, kMaxScenePieces at the
/// item's count that passes them; kMaxRenderPixels at render) and its cut faces to
/// kMaxCapTexels (check_cap_texels of scene_cut_area): without render.texels_per_mm a scene
/// that passes it is baked at the density that fits (fitting_texels_per_mm; the default kept in
/// render.fitted_from_texels_per_mm), a written one is refused there (or at the last item when
/// not even 0.1 texels per mm fits).
/// Refuses, at the count of the item that passes it, pieces whose heap (estimate_object_volume
/// x count x keep over kHeapPacking) is larger than the container holds (heap_capacity): every
/// piece asked for is placed, so a request the container cannot hold is refused before work.
Scene load_scene(const std::string& path);

/// An upper bound of the cut-face area of all `scene`'s objects, m^2: each item's count times
/// its cut_area_m2 (0 for a scene whose templates were not read).
double scene_cut_area(const Scene& scene);

/// What fitting the texel density did to `scene`, in words for a warning: the estimate at the
/// default density, the limit and the density used (render.fitted_from_texels_per_mm); empty
/// when the density was not lowered.
std::string texel_fit_note(const Scene& scene);

}  // namespace cutaway
