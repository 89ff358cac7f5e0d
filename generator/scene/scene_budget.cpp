#include "scene/scene_budget.h"

#include <exception>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <oneapi/tbb/parallel_for.h>

#include "base/error.h"
#include "model/model_builder.h"

namespace cutaway {

long long check_scene_model_vertices(const Scene& scene, const ModelVisitor& each_model) {
  // Each template's model, built side by side (their error, if any, kept for its item).
  std::map<std::string, size_t> index_of;  // per template file
  std::vector<const SceneItem*> first_item;
  for (const SceneItem& item : scene.items) {
    CUTAWAY_CHECK(item.tmpl);  // load_scene read it
    if (index_of.emplace(item.template_path, first_item.size()).second) first_item.push_back(&item);
  }
  std::vector<std::optional<DsModel>> models(first_item.size());
  std::vector<std::exception_ptr> failed(first_item.size());
  oneapi::tbb::parallel_for(size_t{0}, first_item.size(), [&](size_t k) {
    try {
      models[k] = build_model(*first_item[k]->tmpl);
    } catch (...) {
      failed[k] = std::current_exception();
    }
  });
  // Then the items in order, as if each model were built at its template's first item: the
  // same error, at the same item, whatever finished first.
  long long total = 0;
  for (const SceneItem& item : scene.items) {
    const size_t k = index_of.at(item.template_path);
    if (first_item[k] == &item) {
      if (failed[k]) std::rethrow_exception(failed[k]);
      if (each_model) each_model(*item.tmpl, *models[k]);
    }
    total += item.count * static_cast<long long>(models[k]->vertex_count());
    if (total > kMaxSceneModelVertices) {
      throw InputError(item.loc, item.path + ".count",
                       "the objects up to here have " + std::to_string(total) +
                           " DS-model vertices (at most " + std::to_string(kMaxSceneModelVertices) +
                           " in a scene): fewer objects, or coarser templates");
    }
  }
  return total;
}

}  // namespace cutaway
