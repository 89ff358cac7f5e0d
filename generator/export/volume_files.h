// An interior volume's files under one stem, as batches and the editor's cutting page write
// them: the flipbooks with their sidecar, and optionally the OpenVDB file.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "base/outcome.h"
#include "volume/interior_volume.h"

namespace cutaway {

/// One file: its name (a plain name, no folder) and its bytes.
using NamedFile = std::pair<std::string, std::string>;

/// `volume`'s files named after `stem`, in this order: STEM.json (the sidecar, volume_sidecar,
/// naming the others), STEM.colour.png, STEM.structure.png, STEM.material.png and, with
/// `with_vdb`, STEM.vdb (encode_vdb). `name` and `seed` are the template's and the variant's
/// (seed < 0: the template itself). None, with the reason, as encode_flipbooks.
Outcome<std::vector<NamedFile>> volume_files(const InteriorVolume& volume, const std::string& stem,
                                             const std::string& name, int64_t seed, bool with_vdb);

}  // namespace cutaway
