#include "render/batch_sheet.h"

#include <algorithm>
#include <string>
#include <vector>

#include "base/atomic_file.h"
#include "base/error.h"
#include "render/image/contact_sheet.h"

namespace cutaway {

Outcome<BatchSheet> batch_contact_sheet(const BatchIndex& index, const MergeReport& report,
                                        const std::filesystem::path& dir) {
  CUTAWAY_CHECK(report.complete() && report.records.size() == index.assets.size());
  std::vector<Image> tiles;
  for (size_t i = 0; i < report.records.size(); ++i) {
    const AssetRecord& r = report.records[i];
    if (!index.assets[i].sample || r.thumbnail.empty()) continue;
    const std::filesystem::path thumbnail = dir / r.thumbnail;
    Image picture;
    try {
      picture = decode_png(read_file_bytes(thumbnail));
    } catch (const EnvironmentError& e) {
      return Outcome<BatchSheet>::none("the thumbnail " + thumbnail.string() + " cannot be used (" +
                                       e.what() +
                                       "); remove it and its asset and run that shard again");
    }
    tiles.push_back(labelled_tile(picture, r.template_name + "-" + std::to_string(r.seed), r.cut,
                                  std::max(1, picture.width / 160)));
  }
  BatchSheet sheet;
  sheet.assets = static_cast<int>(tiles.size());
  if (!tiles.empty()) sheet.image = compose_grid(tiles, sheet_columns(tiles.size()));
  return sheet;
}

}  // namespace cutaway
