// The sheets that colour diffusion sees (paper §3.1, Fig. 2; doc/algorithms.md §2, Blur):
// each blurred DS becomes two sheets moved apart along the normals by the blur, each showing
// one side's colour on both faces; an unblurred DS stays one sheet whose colour depends on the
// face a ray meets.
#pragma once

#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "model/ds_model.h"

namespace cutaway {

/// One triangle mesh as the diffusion sees it. Positions in metres (object frame).
struct DiffusionSheet {
  std::vector<glm::vec3> position;     ///< #V
  std::vector<glm::uvec3> triangle;    ///< #F, counter-clockwise seen from the front side
  std::vector<glm::vec3> face_normal;  ///< #F unit normals (front side)
  /// Per vertex, linear RGB. `two_faced`: colour_front where a ray meets the front face,
  /// colour_back where it meets the back face. Otherwise colour_front on both faces.
  std::vector<glm::vec3> colour_front, colour_back;
  /// Per vertex, material channels (roughness, translucency), shown like the colours.
  std::vector<glm::vec2> material_front, material_back;
  bool two_faced = false;
};

/// The sheets of every surface of `model`. A surface whose blur is 0 at every vertex gives one
/// two-faced sheet; any other gives a front sheet (blur_sheet_point, side +1) showing the
/// front colour and a back sheet (side -1) showing the back colour.
std::vector<DiffusionSheet> make_diffusion_sheets(const DsModel& model);

/// Every surface of `model` as one two-faced sheet where it lies (no blur offset), sheet k
/// being surface k: for finding which surface a ray meets first and on which side, as the
/// interior volume does (volume/interior_volume.h).
std::vector<DiffusionSheet> surface_sheets(const DsModel& model);

}  // namespace cutaway
