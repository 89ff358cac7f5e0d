// The pictures of the template editor's server (app/edit/edit_server.h), drawn by the
// OpenGL previews: the see-through model, a cut face head-on, and the variants' strip. Shared
// by `cutaway edit` and the editor's benchmark.
#pragma once

#include "app/edit/edit_server.h"

namespace cutaway {

/// PNG renderers for EditServer: the model 640 x 640 (render_model_preview), a cut 480 x 480
/// (render_section_preview), the variants' cuts as one row of 160-pixel tiles (section_sheet).
/// @throws (when called) EnvironmentError when rendering fails
EditRenderers opengl_edit_pictures();

}  // namespace cutaway
