// Fields that the template, scene and batch formats share (doc/template-format.md,
// doc/scene-format.md, doc/batch-format.md): the format tag, the name and the units of every
// file; lengths in the file's units, whole numbers in a range, cuts and template references.
// Each broken rule is an InputError at the field, as yaml_reader.h describes.
#pragma once

#include <filesystem>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "io/yaml_reader.h"
#include "model/template.h"
#include "pieces/cut_spec.h"

namespace cutaway {

/// Fails at the root's `format` field (required) unless it is `expected`, e.g.
/// "cutaway-scene/1": "unsupported format F (this version of cutaway reads EXPECTED)".
void require_format(const YamlField& root, const std::string& expected);

/// The root's `name` field (required): a plain name (check_name), else fails there.
std::string parse_name(const YamlField& root);

/// A `units` value: mm, cm or m. Returns metres per unit; fails with "must be mm, cm or m".
double parse_units(const YamlField& f);

/// The largest length or coordinate a scene or batch may use, metres: far beyond any table top.
inline constexpr double kMaxSceneMetres = 1000;

/// A number in the file's units (`metres_per_unit` metres each), |value| <= 1 km once in
/// metres. Returns metres.
double parse_coordinate(const YamlField& f, double metres_per_unit);

/// A positive length in the file's units. Returns metres.
double parse_positive_length(const YamlField& f, double metres_per_unit);

/// A whole number in [lo, hi] ("must be a whole number from LO to HI, not V").
int parse_int_in(const YamlField& f, int lo, int hi);

/// A cut mapping: {type: whole | halves}, {type: slices, thickness: LENGTH},
/// {type: wedges, count: 2..64} or {type: dice, size: LENGTH}, lengths in the file's units
/// (at least kMinCutLength_m). `length_field` receives the thickness or size field, so that a
/// caller can refuse a length that makes too many pieces there once the template is known.
CutSpec parse_cut(const YamlField& f, double metres_per_unit,
                  std::optional<YamlField>& length_field);

/// The template file a `template` value names: a value containing '/' or ending in ".yaml" is a
/// path relative to `dir` (the file's folder) or absolute; otherwise a name ([a-z0-9_-]+) looked
/// up as NAME.yaml in `dir`/../templates, then in $CUTAWAY_TEMPLATES (when set), then in the
/// project's templates/ folder. `kind` ("scene", "batch") names the file in messages.
/// @throws InputError at `f` when the value is empty or malformed, or no such file exists
std::string resolve_template(const YamlField& f, const std::filesystem::path& dir,
                             const char* kind);

/// Fails at the `variation` field of a scene or batch `item` when the template's organic
/// deformation (lumps, lopsided, lean) at its amount scaled by `variation` could fold the object
/// over itself (check_organic), naming the template. No such field: nothing to check (the
/// template's own amount passed when it was read).
void check_item_variation(const YamlField& item, const Template& tmpl, double variation);

/// A template file read and parsed once for all the items that name it.
struct LoadedTemplate {
  std::shared_ptr<const Template> tmpl;  ///< as load_template returns it
  ObjectExtents extents;                 ///< template_extents of it
};

/// Reads each template of a file's items once (load_template: a broken template is reported at
/// its own file), and refuses cuts that would make too many pieces of it.
class TemplateCheck {
 public:
  /// Loads the template at `template_path` (once per path) and fails at `length_field` when
  /// `cut` would make more than kMaxPiecesPerCut pieces of it (estimate_piece_count).
  /// @returns the loaded template, valid as long as this TemplateCheck
  /// @throws InputError from load_template, or at `length_field` "too small: would make N
  ///         pieces of template NAME (at most M per object)"
  const LoadedTemplate& check(const std::string& template_path, const CutSpec& cut,
                              const std::optional<YamlField>& length_field);

 private:
  std::map<std::string, LoadedTemplate> loaded_;
};

}  // namespace cutaway
