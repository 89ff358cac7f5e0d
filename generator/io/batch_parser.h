// Reads and validates batch files (doc/batch-format.md, all of it). Every broken rule is an
// InputError "FILE:LINE:COL: field.path: rule", as for templates and scenes.
#pragma once

#include <string>
#include <string_view>

#include "batch/batch.h"

namespace cutaway {

/// Parses and validates batch text. Templates are resolved as in scene files (a name, or a
/// path relative to the batch file's folder; format_fields.h resolve_template) but not read.
///
/// Units: cut lengths in the file's `units` (mm, cm or m; default mm) come out in metres.
/// Defaults: seed 0 (an item's seed: the batch's); units mm; an item's count 1, cuts
/// [{type: halves}], variation 1; outputs model false, thumbnails false, thumbnail_size 256,
/// sample 12; export compress none, lods 0, textures jpeg, texels_per_mm 8.6, perlin 1,
/// cube kDefaultCubeSize (diffusion.h).
/// Refused besides types and ranges: seeds above 9e15 (YamlField::integer) and items whose
/// last seed (seed + count - 1) is above 2^53.
/// @param text  the file's bytes (YAML 1.2 or JSON, UTF-8)
/// @param file  the batch's path (messages; templates are resolved from its folder)
/// @throws InputError for any rule the text breaks, at the offending node
Batch parse_batch(std::string_view text, const std::string& file);

/// Reads the batch file at `path`, parses it as parse_batch, and reads every template it names
/// (load_template: a broken template is reported at its own file), filling each item's
/// tmpl and template_name; refuses a cut that would make more than kMaxPiecesPerCut
/// pieces of one object, at the cut's length, the same cut twice in one item, and two items
/// that make assets of one name (the same template, an overlapping seed range and the same
/// cut), at the later item's seed (or the item).
/// @throws InputError as parse_batch, for the templates, and when a file cannot be read
Batch load_batch(const std::string& path);

}  // namespace cutaway
