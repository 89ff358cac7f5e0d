#include "export/gltf_meshes.h"

#include <algorithm>
#include <cmath>
#include <span>
#include <unordered_map>

#include <meshoptimizer.h>

#include "export/vertex_tangents.h"

namespace cutaway::gltf {

namespace {

/// Reorders triangle list `idx` (over `vertices` vertices) for the GPU's post-transform vertex
/// cache (meshoptimizer: Forsyth-style greedy order); `strips`: meshoptimizer's strip-like
/// order instead, a few more cache misses for runs of neighbouring triangles whose vertices
/// the vertex codec then finds in order (gltfpack's order for -cc).
void cache_order(std::vector<uint32_t>& idx, size_t vertices, bool strips) {
  const std::vector<uint32_t> input = idx;
  if (strips) meshopt_optimizeVertexCacheStrip(idx.data(), input.data(), input.size(), vertices);
  else meshopt_optimizeVertexCache(idx.data(), input.data(), input.size(), vertices);
}

/// A triangle list (indices into #V x 3 float `xyz`) simplified by meshoptimizer's edge
/// collapse (Garland-Heckbert quadrics) towards `fraction` of its triangles, the edges on its
/// border locked (meshopt_SimplifyLockBorder: a primitive's border is a cut outline or the seam
/// to the next primitive, so a closed piece stays closed), the error at most `error` of the
/// mesh's extent; then ordered for the vertex cache (cache_order()).
std::vector<uint32_t> simplified(const std::vector<uint32_t>& idx, const std::vector<float>& xyz,
                                 double fraction, double error, bool strips) {
  const size_t vertices = xyz.size() / 3;
  std::vector<uint32_t> out(idx.size());
  const size_t target = static_cast<size_t>(static_cast<double>(idx.size() / 3) * fraction) * 3;
  out.resize(meshopt_simplify(out.data(), idx.data(), idx.size(), xyz.data(), vertices,
                              3 * sizeof(float), target, static_cast<float>(error),
                              meshopt_SimplifyLockBorder, nullptr));
  cache_order(out, vertices, strips);
  return out;
}

/// The vertices of a scene mesh as written: float32 attributes (#V x 3; uv #V x 2, empty when
/// the mesh has none; tangent #V x 4, empty unless a primitive is normal-mapped) and where each
/// of the mesh's vertices went.
struct WrittenVertices {
  std::vector<unsigned> remap;  ///< per mesh vertex, its written index (~0u: not written)
  unsigned count = 0;           ///< #V
  std::vector<float> position, normal, colour, uv, tangent;
};

/// Only the vertices of `mesh` some triangle of `lists` uses, each written once (ordered for
/// fetching by cache_ordered_triangles()): a vertex whose written attributes (float position,
/// normal, colour, uv and, `with_tangents`, its vertex_tangents() one) equal an earlier one's is
/// welded to it (the copies of cut vertices on both sides of a seam that show the same colour).
WrittenVertices welded_vertices(const AssetMesh& mesh,
                                const std::vector<std::span<const glm::uvec3>>& lists,
                                bool with_tangents) {
  const std::vector<glm::dvec4> tangent =
      with_tangents ? vertex_tangents(mesh.position, mesh.normal, mesh.uv, lists)
                    : std::vector<glm::dvec4>{};
  const size_t n = mesh.position.size();
  std::vector<bool> needed(n, false);
  for (const auto& list : lists)
    for (const glm::uvec3& t : list)
      for (int k = 0; k < 3; ++k) needed[t[k]] = true;
  WrittenVertices out;
  out.remap.assign(n, ~0u);
  const size_t key_floats = with_tangents ? 15 : 11;  // the tangent keys only where written
  std::unordered_map<std::string, unsigned> written;
  for (size_t i = 0; i < n; ++i) {
    if (!needed[i]) continue;
    const glm::dvec3& p = mesh.position[i];
    const double len = glm::length(mesh.normal[i]);
    const glm::dvec3 nrm =
        len > 0 && std::isfinite(len) ? mesh.normal[i] / len : glm::dvec3(0, 1, 0);
    const glm::dvec3 c = glm::clamp(mesh.colour[i], 0.0, 1.0);
    float vertex[15] = {};  // position, normal, colour, uv, tangent (with_tangents only)
    for (int k = 0; k < 3; ++k) {
      vertex[k] = static_cast<float>(p[k]);
      vertex[3 + k] = static_cast<float>(nrm[k]);
      vertex[6 + k] = static_cast<float>(c[k]);
    }
    if (!mesh.uv.empty()) {
      const glm::dvec2 q = mesh.uv[i];
      vertex[9] = static_cast<float>(q.x);
      vertex[10] = static_cast<float>(q.y);
    }
    if (with_tangents)
      for (int k = 0; k < 4; ++k) vertex[11 + k] = static_cast<float>(tangent[i][k]);
    for (float& v : vertex) v += 0.0f;  // -0 and +0 write alike
    const auto [it, added] = written.emplace(
        std::string(reinterpret_cast<const char*>(vertex), key_floats * sizeof(float)), out.count);
    out.remap[i] = it->second;
    if (!added) continue;
    ++out.count;
    out.position.insert(out.position.end(), vertex, vertex + 3);
    out.normal.insert(out.normal.end(), vertex + 3, vertex + 6);
    out.colour.insert(out.colour.end(), vertex + 6, vertex + 9);
    if (!mesh.uv.empty()) out.uv.insert(out.uv.end(), vertex + 9, vertex + 11);
    if (with_tangents) out.tangent.insert(out.tangent.end(), vertex + 11, vertex + 15);
  }
  return out;
}

/// Per primitive, its triangles (`lists`) in written vertex indices, reordered for the GPU's
/// post-transform vertex cache (cache_order(), `strips` as there); then the vertices
/// renumbered in the order the primitives first use them (fewer cache misses when vertices are
/// fetched): `vertices`' attributes are reordered to match.
std::vector<std::vector<uint32_t>> cache_ordered_triangles(
    const std::vector<std::span<const glm::uvec3>>& lists, WrittenVertices& vertices, bool strips) {
  const std::vector<unsigned>& remap = vertices.remap;
  const unsigned used = vertices.count;
  std::vector<std::vector<uint32_t>> idx(lists.size());
  std::vector<uint32_t> all;
  for (size_t k = 0; k < lists.size(); ++k) {
    for (const glm::uvec3& t : lists[k])
      idx[k].insert(idx[k].end(), {remap[t.x], remap[t.y], remap[t.z]});
    cache_order(idx[k], used, strips);
    all.insert(all.end(), idx[k].begin(), idx[k].end());
  }
  std::vector<uint32_t> fetch(used);
  meshopt_optimizeVertexFetchRemap(fetch.data(), all.data(), all.size(), used);
  for (std::vector<uint32_t>& list : idx)
    meshopt_remapIndexBuffer(list.data(), std::vector<uint32_t>(list).data(), list.size(),
                             fetch.data());
  for (std::vector<float>* stream :
       {&vertices.position, &vertices.normal, &vertices.colour, &vertices.uv, &vertices.tangent}) {
    if (stream->empty()) continue;
    const std::vector<float> input = *stream;
    meshopt_remapVertexBuffer(stream->data(), input.data(), used,
                              input.size() / used * sizeof(float), fetch.data());
  }
  return idx;
}

/// The vertices one or more primitives of a scene mesh share, as written, and their accessors
/// (positions and normals at once, the others when some primitive first uses them).
struct VertexGroup {
  WrittenVertices vertices;
  int positions = -1, normals = -1, colours = -1, uvs = -1, tangents = -1;
};

/// The levels of detail of one scene mesh, each one glTF mesh, all over the same vertex
/// accessors.
class MeshLevels {
 public:
  /// `primitives` of the mesh, `textured` and `relief` (normal-mapped) per primitive; primitive
  /// k over the vertices of groups[group_of[k]]; `frame` receives the frame of the positions,
  /// one for the whole mesh (about `pivot` when given: SceneBuffers::positions).
  MeshLevels(SceneBuffers& out, const std::vector<AssetPrimitive>& primitives,
             const std::vector<int>& gltf_material, const std::vector<bool>& textured,
             const std::vector<bool>& relief, std::vector<VertexGroup>& groups,
             const std::vector<size_t>& group_of, MeshFrame& frame, const glm::dvec3* pivot)
      : out_(out), primitives_(primitives), gltf_material_(gltf_material), textured_(textured),
        relief_(relief), groups_(groups), group_of_(group_of) {
    std::vector<float> joined;  // the positions the mesh's frame holds, when in several groups
    if (groups.size() > 1)
      for (const VertexGroup& g : groups)
        joined.insert(joined.end(), g.vertices.position.begin(), g.vertices.position.end());
    const std::vector<float>& all = groups.size() > 1 ? joined : groups[0].vertices.position;
    for (VertexGroup& g : groups) {
      g.positions = out.positions(g.vertices.position, all, frame, pivot);
      g.normals = out.normals(g.vertices.normal);
    }
  }

  /// Adds the glTF mesh `name` with `lists` (per primitive, its triangles' indices into its
  /// group); returns its index.
  int add(const std::string& name, const std::vector<std::vector<uint32_t>>& lists) {
    tinygltf::Model& m = out_.model();
    tinygltf::Mesh gm;
    gm.name = name;
    for (size_t k = 0; k < primitives_.size(); ++k) {
      VertexGroup& g = groups_[group_of_[k]];
      tinygltf::Primitive prim;
      prim.mode = TINYGLTF_MODE_TRIANGLES;
      prim.material = gltf_material_[static_cast<size_t>(primitives_[k].material)];
      prim.attributes["POSITION"] = g.positions;
      prim.attributes["NORMAL"] = g.normals;
      // A textured material takes its colour from TEXCOORD_0, never also from COLOR_0 (glTF
      // would multiply the two).
      if (textured_[k]) {
        if (g.uvs < 0) g.uvs = out_.uvs(g.vertices.uv);
        prim.attributes["TEXCOORD_0"] = g.uvs;
      } else {
        if (g.colours < 0) g.colours = out_.colours(g.vertices.colour);
        prim.attributes["COLOR_0"] = g.colours;
      }
      if (relief_[k]) {
        if (g.tangents < 0) g.tangents = out_.tangents(g.vertices.tangent);
        prim.attributes["TANGENT"] = g.tangents;
      }
      prim.indices = out_.indices(lists[k], g.vertices.count);
      gm.primitives.push_back(prim);
    }
    m.meshes.push_back(gm);
    return static_cast<int>(m.meshes.size()) - 1;
  }

 private:
  SceneBuffers& out_;
  const std::vector<AssetPrimitive>& primitives_;
  const std::vector<int>& gltf_material_;
  const std::vector<bool>& textured_;
  const std::vector<bool>& relief_;
  std::vector<VertexGroup>& groups_;
  const std::vector<size_t>& group_of_;
};

}  // namespace

/// Adds mesh `mesh` through `out` (one primitive per AssetPrimitive, sharing the vertex
/// attributes; material k of the assets is glTF material gltf_material[k]), and `lods` coarser
/// levels over the same vertices: level l has about 2^-l of each primitive's triangles
/// (simplified(), error at most 2^(l-1) % of the mesh's extent, so a level may keep more).
/// `pivot_at_centroid`: the positions about the mesh's volume_centroid (GltfSceneOptions).
AddedMesh add_asset_mesh(SceneBuffers& out, const AssetMesh& mesh,
                         const std::vector<int>& gltf_material, int lods, bool pivot_at_centroid) {
  const tinygltf::Model& m = out.model();
  const std::vector<AssetPrimitive> plain{{0, mesh.triangle.size(), 0, {}}};
  const std::vector<AssetPrimitive>& primitives = mesh.primitives.empty() ? plain : mesh.primitives;
  // Per primitive: textured or not, and its triangles (the coarse ones of a textured primitive
  // that has them: its colour is in the texture).
  std::vector<bool> textured, relief;
  std::vector<std::span<const glm::uvec3>> lists;
  for (const AssetPrimitive& p : primitives) {
    const tinygltf::Material& material =
        m.materials[static_cast<size_t>(gltf_material[static_cast<size_t>(p.material)])];
    textured.push_back(material.pbrMetallicRoughness.baseColorTexture.index >= 0);
    relief.push_back(material.normalTexture.index >= 0 && !mesh.uv.empty());
    lists.push_back(primitive_triangles(mesh, p, textured.back()));
  }
  // One vertex group for all primitives; with meshopt one per primitive, numbered from 0 as
  // its own (meshoptimizer's index codec stores a vertex it meets first in order, the next
  // number, in a few bits: a second primitive over shared vertices would start far from 0).
  const bool strips = out.compression() == GltfCompression::Meshopt;
  std::vector<VertexGroup> groups;
  std::vector<size_t> group_of;
  std::vector<std::vector<uint32_t>> idx;
  if (strips) {
    for (size_t k = 0; k < lists.size(); ++k) {
      groups.push_back({welded_vertices(mesh, {lists[k]}, relief[k])});
      idx.push_back(cache_ordered_triangles({lists[k]}, groups.back().vertices, strips)[0]);
      group_of.push_back(k);
    }
  } else {
    const bool with_tangents = std::find(relief.begin(), relief.end(), true) != relief.end();
    groups.push_back({welded_vertices(mesh, lists, with_tangents)});
    idx = cache_ordered_triangles(lists, groups[0].vertices, strips);
    group_of.assign(lists.size(), 0);
  }

  AddedMesh added;
  const glm::dvec3 centroid = pivot_at_centroid ? volume_centroid(mesh) : glm::dvec3(0.0);
  MeshLevels levels(out, primitives, gltf_material, textured, relief, groups, group_of, added.frame,
                    pivot_at_centroid ? &centroid : nullptr);
  added.index = levels.add(mesh.name, idx);
  for (int level = 1; level <= lods; ++level) {
    std::vector<std::vector<uint32_t>> coarser(idx.size());
    for (size_t k = 0; k < idx.size(); ++k)
      coarser[k] = simplified(idx[k], groups[group_of[k]].vertices.position,
                              std::ldexp(1.0, -level), 0.01 * std::ldexp(1.0, level - 1), strips);
    added.lods.push_back(levels.add(mesh.name + "_LOD" + std::to_string(level), coarser));
  }
  return added;
}

}  // namespace cutaway::gltf
