#include "export/engine_profile.h"

#include <string>

#include "base/error.h"

namespace cutaway {

void apply_engine_profile(std::string_view name, GltfSceneOptions& options) {
  if (name == "godot") {
    options.compression = GltfCompression::None;
    options.collision = GltfCollision::GodotRigid;
    options.pivot_at_centre_of_mass = true;
    options.backdrop = false;
  } else if (name == "unreal") {
    options.compression = GltfCompression::None;
    options.collision = GltfCollision::Unreal;
    options.pivot_at_centre_of_mass = true;
    options.backdrop = false;
  } else if (name == "unity") {
    options.compression = GltfCompression::Quantize;
    options.collision = GltfCollision::None;
    options.pivot_at_centre_of_mass = true;
    options.backdrop = false;
  } else if (name == "web") {
    options.compression = GltfCompression::Meshopt;
    options.collision = GltfCollision::None;
    options.backdrop = false;
  } else if (name == "blender") {
    options.compression = GltfCompression::Quantize;
    options.collision = GltfCollision::None;
  } else {
    throw InternalError("unknown engine profile '" + std::string(name) +
                        "' (godot, unreal, unity, web or blender)");
  }
}

}  // namespace cutaway
