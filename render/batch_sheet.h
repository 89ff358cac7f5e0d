// The contact sheet of a merged asset batch (`cutaway batch merge`, doc/batch-format.md): the
// thumbnails of the batch's sample, labelled, on one sheet.
#pragma once

#include <filesystem>

#include "base/outcome.h"
#include "batch/batch_manifest.h"
#include "render/image/image.h"

namespace cutaway {

/// A batch's contact sheet and how many assets it shows (0: the sample has no thumbnails, and
/// there is no sheet).
struct BatchSheet {
  Image image;
  int assets = 0;
};

/// The contact sheet of the assets of `index` marked as the sample: each thumbnail (read from
/// `dir`) labelled TEMPLATE-SEED and its cut, in batch order, in about 4:3 as many columns as
/// rows (sheet_columns).
/// @pre report.complete() (one record per indexed asset, in the index's order)
/// @returns the sheet, or none naming a thumbnail that cannot be read as a PNG image (what to
///          do about it included)
Outcome<BatchSheet> batch_contact_sheet(const BatchIndex& index, const MergeReport& report,
                                        const std::filesystem::path& dir);

}  // namespace cutaway
