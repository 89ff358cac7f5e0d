#version 430 core
// PMVC cube maps (render/pmvc_gl.cpp): (colour / r, 1 / r) and material channels / r of the
// nearest sheet, r the
// Euclidean distance from the point. The solid angle joins in the reduction (pmvc_reduce.comp).
// The cube faces are mirror images (det [U V N] = +1), so the renderer sets glFrontFace(GL_CW):
// gl_FrontFacing is then true where the ray meets the sheet's counter-clockwise (front) face.

in vec3 v_offset;
in vec3 v_front;
in vec3 v_back;
in vec2 v_material_front;
in vec2 v_material_back;

layout(location = 0) out vec4 out_weighted;
layout(location = 1) out vec2 out_material;  // (roughness, translucency) / r

void main() {
  const float inv_r = 1.0 / max(length(v_offset), 1e-9);
  out_weighted = vec4((gl_FrontFacing ? v_front : v_back) * inv_r, inv_r);
  out_material = (gl_FrontFacing ? v_material_front : v_material_back) * inv_r;
}
