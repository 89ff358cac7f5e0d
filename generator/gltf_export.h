// glTF 2.0 export of DS models (Khronos glTF 2.0 specification; COLOR_0 is linear RGB).
#pragma once

#include <filesystem>
#include <string>

#include "cross_section.h"
#include "ds_model.h"

namespace cutaway {

/// How a DS model looks in glTF: alpha-blended surfaces so that the inner structure shows
/// (paper Fig. 9).
struct GltfModelOptions {
  double skin_alpha = 0.35;   ///< opacity of the skin, 0..1
  double inner_alpha = 0.7;   ///< opacity of every other surface, 0..1
};

/// Encodes the model as binary glTF (.glb): one mesh per DS surface with two primitives, the
/// front side (its winding, front colours) and the back side (reversed winding, back colours),
/// each single-sided, so a viewer shows each side's own colour; positions in metres (object
/// frame, +Y up), per-vertex normals, COLOR_0 linear RGB; materials alpha-blended.
/// Deterministic: the same model gives the same bytes.
std::string model_to_glb(const DsModel& model, const GltfModelOptions& options);

/// Writes model_to_glb to `path` atomically (temporary file, then rename).
/// @throws std::runtime_error when the file cannot be written
void write_model_glb(const std::filesystem::path& path, const DsModel& model,
                     const GltfModelOptions& options);

/// Encodes a cross-section as binary glTF: one mesh, one double-sided opaque primitive,
/// positions in metres (object frame), the plane normal as NORMAL, COLOR_0 linear RGB.
/// Deterministic.
std::string section_to_glb(const CrossSection& section);

}  // namespace cutaway
