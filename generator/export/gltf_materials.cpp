#include "export/gltf_materials.h"

#include <algorithm>
#include <cctype>
#include <cstdio>

#include "model/pbr_material.h"
#include "model/subsurface_scatter.h"

namespace cutaway::gltf {

int add_material(tinygltf::Model& m, const std::string& name, double alpha, bool double_sided,
                 double roughness) {
  tinygltf::Material mat;
  mat.name = name;
  mat.pbrMetallicRoughness.baseColorFactor = {1.0, 1.0, 1.0, alpha};
  mat.pbrMetallicRoughness.metallicFactor = 0.0;
  mat.pbrMetallicRoughness.roughnessFactor = roughness;
  mat.alphaMode = alpha < 1.0 ? "BLEND" : "OPAQUE";
  mat.doubleSided = double_sided;
  m.materials.push_back(mat);
  return static_cast<int>(m.materials.size()) - 1;
}

/// `name` as a relative URI: every byte outside RFC 3986's unreserved set percent-encoded.
std::string uri_encode(const std::string& name) {
  std::string out;
  for (unsigned char c : name) {
    if (std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '~') {
      out += static_cast<char>(c);
    } else {
      char hex[4];
      std::snprintf(hex, sizeof hex, "%%%02X", c);
      out += hex;
    }
  }
  return out;
}

/// Adds `material` to `m` as an opaque, single-sided metallic-roughness material (white base
/// colour: vertex colours give the colour, metallic 0) with KHR_materials_clearcoat,
/// KHR_materials_sheen and KHR_materials_diffuse_transmission where its values ask for them
/// (each added to extensionsUsed once); its base colour, material map and normal map are glTF
/// textures textures[base_colour_texture] etc. (a height map is not written: glTF has none).
void add_pbr_material(tinygltf::Model& m, const AssetMaterial& material,
                      const std::vector<int>& textures) {
  const PbrMaterial& pbr = material.pbr;
  const int index = add_material(m, material.name, 1.0, false, pbr.roughness);
  tinygltf::Material& mat = m.materials[static_cast<size_t>(index)];
  if (material.base_colour_texture >= 0) {
    mat.pbrMetallicRoughness.baseColorTexture.index =
        textures[static_cast<size_t>(material.base_colour_texture)];
    mat.pbrMetallicRoughness.baseColorTexture.texCoord = 0;
  }
  if (material.normal_texture >= 0) {  // the relief: tangents from MikkTSpace (none written)
    mat.normalTexture.index = textures[static_cast<size_t>(material.normal_texture)];
    mat.normalTexture.texCoord = 0;
  }
  const int material_map =
      material.material_texture < 0 ? -1 : textures[static_cast<size_t>(material.material_texture)];
  if (material_map >= 0) {  // the map holds the values: factors 1
    mat.pbrMetallicRoughness.roughnessFactor = 1.0;
    mat.pbrMetallicRoughness.metallicRoughnessTexture.index = material_map;
  }
  auto use = [&m, &mat](const std::string& extension, tinygltf::Value::Object values) {
    mat.extensions[extension] = tinygltf::Value(std::move(values));
    if (std::find(m.extensionsUsed.begin(), m.extensionsUsed.end(), extension) ==
        m.extensionsUsed.end())
      m.extensionsUsed.push_back(extension);
  };
  if (pbr.clearcoat > 0) {
    use("KHR_materials_clearcoat",
        {{"clearcoatFactor", tinygltf::Value(pbr.clearcoat)},
         {"clearcoatRoughnessFactor", tinygltf::Value(pbr.clearcoat_roughness)}});
  }
  if (pbr.sheen != glm::dvec3(0.0)) {
    use("KHR_materials_sheen",
        {{"sheenColorFactor", tinygltf::Value(tinygltf::Value::Array{
                                  tinygltf::Value(pbr.sheen.x), tinygltf::Value(pbr.sheen.y),
                                  tinygltf::Value(pbr.sheen.z)})},
         {"sheenRoughnessFactor", tinygltf::Value(pbr.sheen_roughness)}});
  }
  if (pbr.translucency > 0 && pbr.scatter_m > 0) {
    // glTF has no subsurface radius: the add-on reads it here (doc/blender.md).
    mat.extras = tinygltf::Value(tinygltf::Value::Object{
        {"subsurface_radius_m",
         tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(pbr.scatter_m),
                                                tinygltf::Value(pbr.scatter_m * kScatterGreen),
                                                tinygltf::Value(pbr.scatter_m * kScatterBlue)})}});
  }
  if (material_map >= 0 && pbr.translucency > 0) {
    use("KHR_materials_diffuse_transmission",
        {{"diffuseTransmissionFactor", tinygltf::Value(1.0)},
         {"diffuseTransmissionTexture",
          tinygltf::Value(tinygltf::Value::Object{{"index", tinygltf::Value(material_map)}})}});
  } else if (pbr.translucency > 0) {
    use("KHR_materials_diffuse_transmission",
        {{"diffuseTransmissionFactor", tinygltf::Value(pbr.translucency)}});
  }
}

void add_texture_transform(tinygltf::Model& m, const glm::dvec2& offset, const glm::dvec2& scale) {
  using tinygltf::Value;
  const Value transform(
      Value::Object{{"offset", Value(Value::Array{Value(offset.x), Value(offset.y)})},
                    {"scale", Value(Value::Array{Value(scale.x), Value(scale.y)})}});
  bool any = false;
  auto give = [&](int index, tinygltf::ExtensionMap& extensions) {
    if (index < 0) return;
    extensions["KHR_texture_transform"] = transform;
    any = true;
  };
  for (tinygltf::Material& mat : m.materials) {
    give(mat.pbrMetallicRoughness.baseColorTexture.index,
         mat.pbrMetallicRoughness.baseColorTexture.extensions);
    give(mat.pbrMetallicRoughness.metallicRoughnessTexture.index,
         mat.pbrMetallicRoughness.metallicRoughnessTexture.extensions);
    give(mat.normalTexture.index, mat.normalTexture.extensions);
    give(mat.occlusionTexture.index, mat.occlusionTexture.extensions);
    give(mat.emissiveTexture.index, mat.emissiveTexture.extensions);
    for (auto& [name, extension] : mat.extensions) {  // e.g. diffuseTransmissionTexture
      if (!extension.IsObject()) continue;
      Value::Object fields = extension.Get<Value::Object>();
      for (auto& [key, field] : fields) {
        if (!field.IsObject() || !field.Has("index")) continue;
        Value::Object info = field.Get<Value::Object>();
        info["extensions"] = Value(Value::Object{{"KHR_texture_transform", transform}});
        field = Value(std::move(info));
        any = true;
      }
      extension = Value(std::move(fields));
    }
  }
  if (!any) return;
  m.extensionsUsed.push_back("KHR_texture_transform");
  m.extensionsRequired.push_back("KHR_texture_transform");
}

}  // namespace cutaway::gltf
