#include "gltf_export.h"

#include <cstring>
#include <sstream>

#include <tiny_gltf.h>

#include "atomic_file.h"

namespace cutaway {

namespace {

/// Appends raw data to buffer 0 as a new buffer view (4-byte aligned); returns the view index.
int add_view(tinygltf::Model& m, const void* data, size_t bytes, int target) {
  auto& buf = m.buffers[0].data;
  while (buf.size() % 4) buf.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buf.size();
  view.byteLength = bytes;
  view.target = target;
  const auto* p = static_cast<const unsigned char*>(data);
  buf.insert(buf.end(), p, p + bytes);
  m.bufferViews.push_back(view);
  return static_cast<int>(m.bufferViews.size()) - 1;
}

int add_vec3_accessor(tinygltf::Model& m, const std::vector<float>& xyz, bool with_bounds) {
  tinygltf::Accessor a;
  a.bufferView = add_view(m, xyz.data(), xyz.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
  a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  a.type = TINYGLTF_TYPE_VEC3;
  a.count = xyz.size() / 3;
  if (with_bounds) {
    a.minValues = {xyz[0], xyz[1], xyz[2]};
    a.maxValues = a.minValues;
    for (size_t i = 0; i < xyz.size(); ++i) {
      a.minValues[i % 3] = std::min<double>(a.minValues[i % 3], xyz[i]);
      a.maxValues[i % 3] = std::max<double>(a.maxValues[i % 3], xyz[i]);
    }
  }
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size()) - 1;
}

int add_index_accessor(tinygltf::Model& m, const std::vector<uint32_t>& idx) {
  tinygltf::Accessor a;
  a.bufferView = add_view(m, idx.data(), idx.size() * sizeof(uint32_t),
                          TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  a.type = TINYGLTF_TYPE_SCALAR;
  a.count = idx.size();
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size()) - 1;
}

int add_material(tinygltf::Model& m, const std::string& name, double alpha,
                 bool double_sided = false) {
  tinygltf::Material mat;
  mat.name = name;
  mat.pbrMetallicRoughness.baseColorFactor = {1.0, 1.0, 1.0, alpha};
  mat.pbrMetallicRoughness.metallicFactor = 0.0;
  mat.pbrMetallicRoughness.roughnessFactor = 0.8;
  mat.alphaMode = alpha < 1.0 ? "BLEND" : "OPAQUE";
  mat.doubleSided = double_sided;
  m.materials.push_back(mat);
  return static_cast<int>(m.materials.size()) - 1;
}

/// An empty glTF 2.0 model with one (empty) buffer and scene 0 as the default.
tinygltf::Model new_model() {
  tinygltf::Model m;
  m.asset.version = "2.0";
  m.asset.generator = "cutaway";
  m.buffers.emplace_back();
  m.defaultScene = 0;
  return m;
}

/// The model as .glb bytes.
std::string to_glb(tinygltf::Model& m) {
  std::ostringstream out;
  tinygltf::TinyGLTF writer;
  writer.WriteGltfSceneToStream(&m, out, false, true);
  return out.str();
}

}  // namespace

std::string model_to_glb(const DsModel& model, const GltfModelOptions& options) {
  tinygltf::Model m = new_model();
  const int skin_mat = add_material(m, "skin", options.skin_alpha);
  const int inner_mat = add_material(m, "inner", options.inner_alpha);
  tinygltf::Scene scene;
  scene.name = model.name;
  for (const DsSurface& s : model.surfaces) {
    const DsMesh& mesh = s.mesh;
    std::vector<float> pos, front, back;
    for (auto vh : mesh.vertices()) {
      const auto& p = mesh.point(vh);
      const auto& d = mesh.data(vh);
      for (int k = 0; k < 3; ++k) {
        pos.push_back(static_cast<float>(p[k]));
        front.push_back(static_cast<float>(d.front[k]));
        back.push_back(static_cast<float>(d.back[k]));
      }
    }
    std::vector<float> normals, flipped;
    for (glm::dvec3 n : vertex_normals(mesh)) {
      if (n == glm::dvec3(0.0)) n = {0, 1, 0};  // glTF normals must be unit length
      for (int k = 0; k < 3; ++k) {
        normals.push_back(static_cast<float>(n[k]));
        flipped.push_back(static_cast<float>(-n[k]));
      }
    }
    std::vector<uint32_t> idx, rev;
    for (auto fh : mesh.faces()) {
      std::array<uint32_t, 3> v;
      int k = 0;
      for (auto vh : mesh.fv_range(fh)) v[k++] = static_cast<uint32_t>(vh.idx());
      idx.insert(idx.end(), {v[0], v[1], v[2]});
      rev.insert(rev.end(), {v[0], v[2], v[1]});
    }
    const int apos = add_vec3_accessor(m, pos, true);
    const int mat = s.role == SurfaceRole::Skin ? skin_mat : inner_mat;
    tinygltf::Mesh gm;
    gm.name = s.name;
    for (int side = 0; side < 2; ++side) {
      tinygltf::Primitive prim;
      prim.mode = TINYGLTF_MODE_TRIANGLES;
      prim.material = mat;
      prim.attributes["POSITION"] = apos;
      prim.attributes["NORMAL"] = add_vec3_accessor(m, side == 0 ? normals : flipped, false);
      prim.attributes["COLOR_0"] = add_vec3_accessor(m, side == 0 ? front : back, false);
      prim.indices = add_index_accessor(m, side == 0 ? idx : rev);
      gm.primitives.push_back(prim);
    }
    m.meshes.push_back(gm);
    tinygltf::Node node;
    node.name = s.name;
    node.mesh = static_cast<int>(m.meshes.size()) - 1;
    m.nodes.push_back(node);
    scene.nodes.push_back(static_cast<int>(m.nodes.size()) - 1);
  }
  m.scenes.push_back(scene);
  return to_glb(m);
}

std::string section_to_glb(const CrossSection& section) {
  tinygltf::Model m = new_model();
  std::vector<float> pos, normal, colour;
  for (size_t i = 0; i < section.position.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      pos.push_back(static_cast<float>(section.position[i][k]));
      normal.push_back(static_cast<float>(section.plane.normal[k]));
      colour.push_back(static_cast<float>(section.colour[i][k]));
    }
  }
  std::vector<uint32_t> idx;
  for (const glm::uvec3& t : section.triangle) idx.insert(idx.end(), {t.x, t.y, t.z});
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.material = add_material(m, "cut face", 1.0, true);
  prim.attributes["POSITION"] = add_vec3_accessor(m, pos, true);
  prim.attributes["NORMAL"] = add_vec3_accessor(m, normal, false);
  prim.attributes["COLOR_0"] = add_vec3_accessor(m, colour, false);
  prim.indices = add_index_accessor(m, idx);
  tinygltf::Mesh mesh;
  mesh.name = "cross-section";
  mesh.primitives.push_back(prim);
  m.meshes.push_back(mesh);
  tinygltf::Node node;
  node.name = "cross-section";
  node.mesh = 0;
  m.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  m.scenes.push_back(scene);
  return to_glb(m);
}

void write_model_glb(const std::filesystem::path& path, const DsModel& model,
                     const GltfModelOptions& options) {
  write_file_atomically(path, model_to_glb(model, options));
}

}  // namespace cutaway
