#version 430 core
#extension GL_ARB_shader_viewport_layer_array : require
// PMVC cube maps (render/pmvc_gl.cpp): instance i draws all sheets for cube face i % 6 of batch
// point i / 6 into layer i. Clip space: x = q.U, y = q.V, w = q.N for the offset q from the
// point in its cube's turned frame (R^T offset), so NDC (x, y) is the face coordinate (a, b)
// of cube_directions.cpp (direction a U + b V + N, turned by R); z = near, so depth =
// near / w: reversed, infinite far plane.

layout(location = 0) in vec3 in_position;      // metres, object frame
layout(location = 1) in vec3 in_colour_front;  // linear RGB
layout(location = 2) in vec3 in_colour_back;   // linear RGB (= front on a one-colour sheet)
layout(location = 3) in vec2 in_material_front;  // (roughness, translucency)
layout(location = 4) in vec2 in_material_back;   // (= front on a one-colour sheet)

struct BatchPoint {
  vec4 eye;         // xyz: the point, metres
  vec4 to_cube[3];  // xyz: rows of R^T, R the rotation of the point's cube (cube_rotation)
};
layout(std430, binding = 0) readonly buffer Eyes {
  BatchPoint batch[];
};

uniform float near_m;

out vec3 v_offset;  // hit - point, metres
out vec3 v_front;
out vec3 v_back;
out vec2 v_material_front;
out vec2 v_material_back;

// Rows U, V, N per face (+X, -X, +Y, -Y, +Z, -Z): face_point(f, a, b) = a U + b V + N.
const vec3 kU[6] = vec3[6](vec3(0, 0, -1), vec3(0, 0, 1), vec3(1, 0, 0), vec3(1, 0, 0),
                           vec3(1, 0, 0), vec3(-1, 0, 0));
const vec3 kV[6] = vec3[6](vec3(0, 1, 0), vec3(0, 1, 0), vec3(0, 0, -1), vec3(0, 0, 1),
                           vec3(0, 1, 0), vec3(0, 1, 0));
const vec3 kN[6] = vec3[6](vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0),
                           vec3(0, 0, 1), vec3(0, 0, -1));

void main() {
  const int point = gl_InstanceID / 6;
  const int face = gl_InstanceID - 6 * point;
  const vec3 offset = in_position - batch[point].eye.xyz;
  // In the cube's own frame: the ray along R d meets this vertex where d = R^T offset.
  const vec3 q = vec3(dot(batch[point].to_cube[0].xyz, offset),
                      dot(batch[point].to_cube[1].xyz, offset),
                      dot(batch[point].to_cube[2].xyz, offset));
  v_offset = q;
  v_front = in_colour_front;
  v_back = in_colour_back;
  v_material_front = in_material_front;
  v_material_back = in_material_back;
  gl_Position = vec4(dot(q, kU[face]), dot(q, kV[face]), near_m, dot(q, kN[face]));
  gl_Layer = gl_InstanceID;
}
