// The memory total of a scene's objects, checked before any object is cut: each object keeps
// its pieces until the scene is laid out, so their sum, not one object, decides the memory.
#pragma once

#include <functional>

#include "model/ds_model.h"
#include "model/template.h"
#include "scene/scene.h"

namespace cutaway {

/// The most DS-model vertices the objects of one scene may have together, each object counted
/// with the vertices of its template's model (grains left out: they colour the caps, the pieces
/// do not keep them). Measured: 128 halved tomatoes (2.12 M such vertices) took 820 MB, about
/// 390 bytes each; 3 M keep a scene near 1.2 GB, leaving room for its cap textures.
inline constexpr long long kMaxSceneModelVertices = 3'000'000;

/// Called with a template and the DS model built from it.
using ModelVisitor = std::function<void(const Template&, const DsModel&)>;

/// Builds the DS model of each template `scene` names, once per template (side by side, on
/// the TBB threads), and refuses the scene when its objects' model vertices (count x the
/// template model's vertices, over the items in order) pass kMaxSceneModelVertices.
/// `each_model`, when given, is called with each template and its model at the template's
/// first item, in item order (`cutaway check` checks their grain limits there instead of
/// building them again). Errors are those of building the models one by one in item order.
/// @pre the scene was read with load_scene (its templates exist and parse)
/// @returns the total (within the limit)
/// @throws InputError at the item that passes the total ("items[i].count"), as build_model,
///         or as each_model
long long check_scene_model_vertices(const Scene& scene, const ModelVisitor& each_model = {});

}  // namespace cutaway
