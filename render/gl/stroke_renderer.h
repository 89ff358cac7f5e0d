// Drawing silhouette strokes (generator/npr/silhouettes.h) over an OpenGL render: each stroke
// becomes a screen-space triangle strip of its tapered width.
#pragma once

#include <vector>

#include "assets/scene_assets.h"
#include "npr/silhouettes.h"

namespace cutaway {

/// Draws `strokes` into the framebuffer bound on the current context (its viewport
/// `width` x `height` pixels), on top of what is there: no depth test (the strokes' visibility
/// was decided when they were extracted), opaque, in their linear colours. Each stroke is
/// projected with `camera` as render_scene_preview does (aspect width / height); its width at
/// each point is `width_px` times `width_scale`; joints are mitred (a miter at most twice the
/// half width), and points behind the near plane are skipped. Anti-aliasing comes from the
/// multisampled target. Leaves the program, vertex array and buffers it used deleted.
/// @throws EnvironmentError when OpenGL reports an error
void draw_strokes(const std::vector<Stroke>& strokes, const AssetCamera& camera, int width,
                  int height, double width_scale = 1.0);

}  // namespace cutaway
