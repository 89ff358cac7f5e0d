#include "app/edit/edit_pictures.h"

#include <utility>
#include <vector>

#include "render/image/contact_sheet.h"
#include "render/image/image.h"
#include "render/model_preview.h"
#include "render/section_preview.h"

namespace cutaway {

EditRenderers opengl_edit_pictures() {
  EditRenderers renderers;
  renderers.model_png = [](const DsModel& model) {
    PreviewOptions o;
    o.width = o.height = 640;
    return encode_png(render_model_preview(model, o));
  };
  renderers.section_png = [](const CrossSection& section) {
    SectionPreviewOptions o;
    o.width = o.height = 480;
    return encode_png(render_section_preview(section, o));
  };
  renderers.variants_png = [](std::vector<Outcome<CrossSection>> sections) {
    SectionTileOptions o;
    o.tile_px = 160;
    const int columns = static_cast<int>(sections.size());  // one row: a strip
    return encode_png(section_sheet(std::move(sections), o, columns));
  };
  return renderers;
}

}  // namespace cutaway
