// glTF materials: plain materials, the scene's PBR materials with the extensions their
// values ask for, and image URIs. A part of the glTF export (gltf_export.h).
#pragma once

#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <tiny_gltf.h>

#include "assets/scene_assets.h"

namespace cutaway::gltf {

/// Appends a material named `name` to `m`: white base colour of alpha `alpha` (blended below
/// 1, else opaque), metallic 0, perceptual `roughness`, single- or `double_sided`. Returns its
/// index.
int add_material(tinygltf::Model& m, const std::string& name, double alpha,
                 bool double_sided = false, double roughness = 0.8);

/// `name` as a relative URI: every byte outside RFC 3986's unreserved set percent-encoded.
std::string uri_encode(const std::string& name);

/// Adds `material` to `m` as an opaque, single-sided metallic-roughness material (white base
/// colour: vertex colours give the colour, metallic 0) with KHR_materials_clearcoat,
/// KHR_materials_sheen and KHR_materials_diffuse_transmission where its values ask for them
/// (each added to extensionsUsed once); its base colour, material map and normal map are glTF
/// textures textures[base_colour_texture] etc. (a height map is not written: glTF has none).
void add_pbr_material(tinygltf::Model& m, const AssetMaterial& material,
                      const std::vector<int>& textures);

/// Gives every texture reference of every material of `m` (the core ones and those inside
/// material extensions) the KHR_texture_transform uv' = `offset` + `scale` * uv, and lists the
/// extension as used and required: the texture coordinates were written as steps that only the
/// transform maps back (SceneBuffers::uv_transform). Source: the KHR_texture_transform spec.
void add_texture_transform(tinygltf::Model& m, const glm::dvec2& offset, const glm::dvec2& scale);

}  // namespace cutaway::gltf
