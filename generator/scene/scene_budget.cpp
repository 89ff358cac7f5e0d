#include "scene/scene_budget.h"

#include <map>
#include <string>

#include "base/error.h"
#include "model/model_builder.h"

namespace cutaway {

long long check_scene_model_vertices(const Scene& scene, const ModelVisitor& each_model) {
  std::map<std::string, long long> vertices_of;  // per template file
  long long total = 0;
  for (const SceneItem& item : scene.items) {
    auto it = vertices_of.find(item.template_path);
    if (it == vertices_of.end()) {
      CUTAWAY_CHECK(item.tmpl);  // load_scene read it
      const DsModel model = build_model(*item.tmpl);
      if (each_model) each_model(*item.tmpl, model);
      it = vertices_of.emplace(item.template_path, static_cast<long long>(model.vertex_count()))
               .first;
    }
    total += item.count * it->second;
    if (total > kMaxSceneModelVertices) {
      throw InputError(item.loc, item.path + ".count",
                       "the objects up to here have " + std::to_string(total) +
                           " DS-model vertices (at most " +
                           std::to_string(kMaxSceneModelVertices) +
                           " in a scene): fewer objects, or coarser templates");
    }
  }
  return total;
}

}  // namespace cutaway
