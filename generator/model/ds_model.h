// The diffusion-surface (DS) model (paper §3.1): triangle meshes whose vertices carry a front and
// a back colour and a blur value, plus per-surface side visibility.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "base/plane.h"

namespace cutaway {

/// OpenMesh traits of a DS mesh: double-precision points (metres, object frame, axis +Y) and
/// the DS attributes on every vertex.
struct DsMeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  VertexAttributes(OpenMesh::Attributes::Normal);
  FaceAttributes(OpenMesh::Attributes::Normal);
  VertexTraits {
    OpenMesh::Vec3d front{0, 0, 0};  ///< linear RGB shown on the front side (normal side)
    OpenMesh::Vec3d back{0, 0, 0};   ///< linear RGB shown on the back side
    double blur = 0;                 ///< metres; the sheets sit at +-blur along the normal
    /// (t_profile, t_section): normalised arc-length parameters of the sweep that made the
    /// vertex (0 for imported meshes); gradients and grain regions use them.
    OpenMesh::Vec2d param{0, 0};
    /// Material channels (roughness, translucency), each 0..1, shown on the front and the back
    /// side (paper §6: material information on DSs besides colours); diffused like colours.
    OpenMesh::Vec2d material_front{0.6, 0}, material_back{0.6, 0};
  };
};

using DsMesh = OpenMesh::TriMesh_ArrayKernelT<DsMeshTraits>;

/// A DS mesh point or vector (OpenMesh, metres) as a GLM vector.
inline glm::dvec3 to_glm(const OpenMesh::Vec3d& v) { return {v[0], v[1], v[2]}; }

/// The smallest blur a DS vertex carries, metres (1 um): the two sheets of a blurred surface sit
/// at +-blur, and sheets closer than this cannot be told apart in single-precision ray casting
/// or placed as distinct points of a cut's triangulation (a blur of 1e-300 m made both loop).
inline constexpr double kMinBlur_m = 1e-6;

/// The most vertices a template's DS model may have over all its surfaces (sweeps and meshes;
/// grains have a budget of their own, kMaxGrains in grains.h): each surface is refused before
/// it is sampled or read when it would take the total beyond it. About 650 bytes of memory per
/// vertex while the model is built and checked, about 1.2 kB while it is cut (a model of 1.87 M
/// vertices took 2.19 GB to cut in halves).
inline constexpr size_t kMaxModelVertices = 1'000'000;

/// `blur_m` as a DS vertex carries it: values below kMinBlur_m are sharp (0).
inline double vertex_blur(double blur_m) { return blur_m < kMinBlur_m ? 0.0 : blur_m; }

/// What a surface is for. The skin is the object's closed outer boundary.
enum class SurfaceRole { Skin, Structure, Grain };

/// One diffusion surface: a triangle mesh with DS attributes. Face winding gives the normal;
/// the normal points to the front side.
struct DsSurface {
  std::string name;
  SurfaceRole role = SurfaceRole::Structure;
  DsMesh mesh;
  bool visible_front = true;  ///< false: the front side is hollow (empty space in cuts)
  bool visible_back = true;   ///< false: the back side is hollow
  /// Closed, and never split by a cut: the whole surface, with everything inside it, goes to one
  /// piece (pieces/rigid_stones.h). Its front is its outside.
  bool rigid = false;
  /// Role Grain: each grain's point on the surface it is scattered over (its dart), metres;
  /// where the skin shows the grains (skin patterns' `grains` layers).
  std::vector<glm::dvec3> grain_sites;
};

/// A whole DS model: all surfaces (skin first), in metres, object frame.
class SpineBend;

/// The bent axis of a model swept about +Y and then carried onto a spine (spine_bend.h):
/// the map, shared by the model's copies, and the straight model's height range, so that
/// cuts along the axis (slices) can follow the spine.
struct BentAxis {
  std::shared_ptr<const SpineBend> bend;
  double y_min = 0, y_max = 0;  ///< the straight model's lowest and highest y, metres
};

/// The axis halves and wedges cut along where a variant's organic deformation leaned it
/// (organic_deformation.h): the line through `point` along `direction` (unit). Absent: the
/// straight +Y axis through the origin.
struct CutAxis {
  glm::dvec3 point{0.0};
  glm::dvec3 direction{0, 1, 0};
};

/// The knife's small wobble under a variant's halves cut (knife_wobble.h): the plane through the
/// axis leans by `lean_rad` about its line across the axis at mid-height, and moves by
/// `offset_m` along its normal, so that the two halves of one object differ as a real knife's
/// do. Zero (the template's own model): the exact plane through the axis.
struct KnifeWobble {
  double lean_rad = 0.0;
  double offset_m = 0.0;
};

struct DsModel {
  std::string name;
  std::vector<DsSurface> surfaces;
  glm::dvec3 bbox_min{0.0}, bbox_max{0.0};  ///< axis-aligned bounds of all surfaces, metres
  std::optional<BentAxis> bent_axis;        ///< set where the template has a spine
  bool halves_across = false;               ///< the template's `halves: across` (cut_cells.h)
  std::optional<CutAxis> cut_axis;          ///< set where a variant's axis leans
  KnifeWobble knife;                        ///< a variant's; zero for the template's model

  /// Total triangle count over all surfaces (the paper's "DS faces").
  size_t face_count() const;
  /// Total vertex count over all surfaces.
  size_t vertex_count() const;
  /// The skin (surfaces[0]).
  const DsSurface& skin() const { return surfaces.front(); }
};

/// Sets the material channels (roughness, translucency; 0..1) of every vertex of `mesh`: one
/// value per side.
void set_material(DsMesh& mesh, const glm::dvec2& front, const glm::dvec2& back);

/// Recomputes `model.bbox_min/max` from the surfaces' vertices.
void update_bounds(DsModel& model);

/// The axis-aligned bounding box of `mesh`'s vertices (lowest corner, highest corner), metres.
/// @pre the mesh has vertices
std::pair<glm::dvec3, glm::dvec3> mesh_bounds(const DsMesh& mesh);

/// The signed volume `mesh`'s triangles enclose (divergence theorem: the sum of det(a, b, c) /
/// 6), cubic metres: positive for a closed surface whose front is its outside.
double signed_volume(const DsMesh& mesh);

/// The skin's axis-aligned bounding box (lowest corner, highest corner), metres: the object's
/// own extent, which grains standing proud of the skin do not move.
/// @pre the model has a skin with vertices
std::pair<glm::dvec3, glm::dvec3> skin_bounds(const DsModel& model);

/// The horizontal plane (normal +Y) halfway between the lowest and the highest vertex of the
/// skin, metres: the mid-height cut of the contact sheets, the variants strip and the tests.
/// The skin's range, not the model's bounds, so that grains standing proud of the skin do not
/// move it. @pre the model has a skin with vertices
Plane mid_height_plane(const DsModel& model);

/// Unit vertex normals of `mesh` (#V): the area-weighted sum of the incident faces' normals
/// (counter-clockwise winding = front side); zero where that sum vanishes.
std::vector<glm::dvec3> vertex_normals(const DsMesh& mesh);

/// Smallest offset of a blurred surface's sheets (metres): where the blur falls to 0 the two
/// sheets stay this far apart, so the nearer one is always the one on the ray's side.
inline constexpr double kMinSheetOffset_m = 1e-6;

/// Whether any vertex of `mesh` has a blur above 0: such a surface is drawn as two one-sided
/// sheets instead of one two-faced one (paper §4.2, "blur").
bool is_blurred(const DsMesh& mesh);

/// Where vertex `vh` of a blurred surface lies on its blur sheet `side` (+1: the front sheet,
/// -1: the back sheet, 0: the surface itself): moved by `side * max(blur, kMinSheetOffset_m)`
/// metres along `normals[vh]` (the surface's vertex_normals). The one rule for the sheets'
/// positions, used by PMVC's sheets and by the crossing test that keeps grains off them.
glm::dvec3 blur_sheet_point(const DsMesh& mesh, const std::vector<glm::dvec3>& normals,
                            DsMesh::VertexHandle vh, int side);

}  // namespace cutaway
