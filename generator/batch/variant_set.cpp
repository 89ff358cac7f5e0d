#include "batch/variant_set.h"

#include "base/error.h"
#include "export/gltf_export.h"
#include "variation/variation.h"

namespace cutaway {

std::string variant_file_name(const std::string& tmpl_name, uint64_t seed) {
  return tmpl_name + "-" + std::to_string(seed) + ".glb";
}

std::vector<VariantRecord> build_variant_models(
    const Template& tmpl, uint64_t first_seed, int first, int last,
    const std::function<void(const std::string& file, const std::string& glb)>& write,
    const std::function<void(int done)>& progress) {
  if (first < 0 || last < first)
    throw InternalError("build_variant_models: the range " + std::to_string(first) + ".." +
                        std::to_string(last) + " is empty or negative");
  std::vector<VariantRecord> records;
  for (int i = first; i < last; ++i) {
    const uint64_t seed = first_seed + static_cast<uint64_t>(i);
    const Variant v = make_variant(tmpl, seed);
    const std::string glb = model_to_glb(v.model, GltfModelOptions{});
    const std::string file = variant_file_name(tmpl.name, seed);
    write(file, glb);
    records.push_back({file, seed, fnv1a64(glb), v.model.face_count(), v.tmpl.folds});
    if (progress) progress(i - first + 1);
  }
  return records;
}

Outcome<CrossSection> variant_section(const Variant& variant, const DiffusionFactory& diffusion) {
  if (!diffusion) throw InternalError("variant_section: no diffusion backend");
  return make_cross_section(variant.model, mid_height_plane(variant.model),
                            *diffusion(variant.model), {variant.tmpl.edge_m});
}

}  // namespace cutaway
