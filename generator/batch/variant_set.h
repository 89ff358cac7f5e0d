// What `cutaway variants` computes (doc/architecture.md, Batches): a run of seeded variants of
// one template, each DS model encoded as .glb with its manifest record, and the mid-height
// cuts of the first few for their contact sheet (render/image/contact_sheet.h draws it).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "base/outcome.h"
#include "batch/variant_batch.h"
#include "cut/object_cut.h"
#include "model/template.h"
#include "section/cross_section.h"

namespace cutaway {

/// The file name of the variant of `tmpl_name` with `seed`: "NAME-SEED.glb".
std::string variant_file_name(const std::string& tmpl_name, uint64_t seed);

/// Builds the variants of `tmpl` with seeds first_seed + i for i in first..last-1
/// (make_variant), encodes each DS model as .glb (model_to_glb, default options) and hands
/// it to `write` (file name, bytes) as soon as it is made, so that the run holds one model at a
/// time; `progress`, when given, is called with the number of variants done after each.
/// Deterministic: the same template and seeds give the same bytes.
/// @returns one record per variant, in seed order
/// @pre 0 <= first <= last
/// @throws whatever `write` throws; InputError when a variant cannot be built
std::vector<VariantRecord> build_variant_models(
    const Template& tmpl, uint64_t first_seed, int first, int last,
    const std::function<void(const std::string& file, const std::string& glb)>& write,
    const std::function<void(int done)>& progress = {});

/// The horizontal cut of a variant for a contact-sheet tile: the plane y = mid-height of its
/// skin's bounding box, coloured by PMVC with a backend from `diffusion` (`variants` uses 8 x 8
/// texels per cube face, a quarter of the rays of `section`'s default: enough for a
/// thumbnail), template edge length variant.tmpl.edge_m.
/// @returns the section, or the reason there is none (the plane misses the skin)
Outcome<CrossSection> variant_section(const Variant& variant, const DiffusionFactory& diffusion);

}  // namespace cutaway
