#include "scene/scene_budget.h"

#include <map>
#include <string>

#include "base/error.h"
#include "io/template_parser.h"
#include "model/model_builder.h"

namespace cutaway {

long long check_scene_model_vertices(const Scene& scene) {
  std::map<std::string, long long> vertices_of;  // per template file
  long long total = 0;
  for (const SceneItem& item : scene.items) {
    auto it = vertices_of.find(item.template_path);
    if (it == vertices_of.end()) {
      const DsModel model = build_model(load_template(item.template_path));
      long long vertices = 0;
      for (const DsSurface& s : model.surfaces) vertices += static_cast<long long>(s.mesh.n_vertices());
      it = vertices_of.emplace(item.template_path, vertices).first;
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
