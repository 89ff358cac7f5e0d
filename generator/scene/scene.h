// The parsed scene (doc/scene-format.md): plain data, lengths in metres, colours linear RGB.
// Parsing and validation live in io/scene_parser.h; layout and export never see YAML, and
// nothing after load_scene reads a file.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "base/error.h"
#include "model/template.h"
#include "pieces/cut_spec.h"
#include "placement/container.h"

namespace cutaway {

/// The totals a scene is held to, over all its items (doc/scene-format.md, Totals), so that
/// what check accepts stays within memory: objects, pieces (as estimate_piece_count counts
/// them, before `keep`) and the pixels of a render (4K UHD: the preview takes about 80 bytes a
/// pixel, and the market at 4096 x 4096 took 2.46 GB); its cap textures are held to
/// kMaxCapTexels (cut_spec.h).
inline constexpr long long kMaxSceneObjects = 1024;
inline constexpr long long kMaxScenePieces = 8192;
inline constexpr long long kMaxRenderPixels = 3840LL * 2160;

/// One entry of `items`: `count` seeded variants of one template, each cut the same way.
struct SceneItem {
  std::string template_name;  ///< as written (a name from templates/ or a relative path)
  std::string template_path;  ///< the resolved template file
  /// The parsed template (load_scene reads each file once; items naming it share it), null
  /// after parse_scene alone
  std::shared_ptr<const Template> tmpl;
  int count = 1;           ///< whole objects, >= 1
  CutSpec cut;             ///< lengths already in metres
  double keep = 1.0;       ///< fraction of the pieces placed, in (0, 1]
  double variation = 1.0;  ///< scales the template's variation amount, >= 0
  /// Its `arrange`, else the scene's, else the container's default (scatter on a board or on
  /// the floor, pile in a bowl or on a plate).
  Arrangement arrange = Arrangement::Pile;
  /// Upper bound of one object's cut-face area, m^2 (estimate_cut_area; set by load_scene,
  /// 0 when the templates were not read)
  double cut_area_m2 = 0;
  FileLoc loc;       ///< where the item is written
  std::string path;  ///< field path prefix for errors, e.g. "items[2]"
};

/// A camera given in the scene file (metres, scene frame: +Y up, the container's base at y = 0).
struct SceneCamera {
  glm::dvec3 eye{0.0}, target{0.0};
  double fov_deg = 40;  ///< vertical field of view, degrees
};

/// How a picture is drawn (doc/npr.md, Style): realistic pictures have no ink strokes;
/// illustrations draw the silhouettes and the outlines inside cut faces, as the paper does.
enum class RenderStyle { Realistic, Illustration };

/// The silhouette stroke strength a style draws when none is given: 0 realistic, 1 illustration.
inline double default_silhouettes(RenderStyle style) {
  return style == RenderStyle::Illustration ? 1.0 : 0.0;
}

/// Output settings of the scene file's `render` block.
struct RenderSettings {
  int width = 1280, height = 960;  ///< pixels
  double perlin = 1.0;             ///< NPR Perlin colour modulation strength, 0 turns it off
  RenderStyle style = RenderStyle::Realistic;  ///< `style`
  bool silhouettes_given = false;              ///< whether `silhouettes` was written
  /// NPR silhouette stroke strength, 0 turns them off; default_silhouettes(style) unless given
  double silhouettes = 0.0;
  /// Texel density of the baked cut-face textures, texels per millimetre (0.1..100): about
  /// twice the pixels per millimetre the closest cut face gets in the pictures wanted.
  double texels_per_mm = 8.6;
  /// Whether `texels_per_mm` was written. Unwritten, a scene whose cut faces would pass
  /// kMaxCapTexels at the default gets the density that fits (fitting_texels_per_mm), and
  /// fitted_from_texels_per_mm says from which; written, it is refused.
  bool texels_per_mm_given = false;
  double fitted_from_texels_per_mm = 0;  ///< the density fitting lowered, 0: none lowered
};

/// What a scene stands on in pictures (doc/scene-format.md, Backdrop): a paper sweep (a floor
/// curving up into a wall behind the food, assets/backdrop.h) or nothing (a plain background).
struct Backdrop {
  bool sweep = true;  ///< `type`: sweep (default in the realistic style) or none (illustration)
  /// `color`, linear RGB: #b0a89e (a warm grey linen) by default
  glm::dvec3 colour{0.43415363617474895, 0.39157247774972326, 0.34191442490866092};
};

/// A whole parsed, validated scene.
struct Scene {
  std::string name;
  std::string file;   ///< path it was read from
  uint64_t seed = 0;  ///< default seed (the command line's --seed overrides it)
  double metres_per_unit = 1e-3;
  Container container;
  std::vector<SceneItem> items;
  std::optional<SceneCamera> camera;  ///< absent: the layout frames the scene
  RenderSettings render;
  Backdrop backdrop;  ///< after `render`: its default follows the style
};

}  // namespace cutaway
