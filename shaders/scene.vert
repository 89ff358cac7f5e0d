#version 330 core
// Scene preview (render/scene_preview.h), vertex stage: one instance of one mesh, object ->
// view -> clip; lighting happens per fragment in the view frame (scene.frag).

layout(location = 0) in vec3 in_position;  // metres, mesh frame
layout(location = 1) in vec3 in_normal;    // unit shading normal, mesh frame
layout(location = 2) in vec3 in_colour;    // linear RGB albedo
layout(location = 3) in vec2 in_uv;        // texture coordinates (glTF: v down from the top row)

uniform mat4 view_from_object;  // rigid: camera view * instance placement
uniform mat4 clip_from_view;

out vec3 v_position;  // view frame, metres
out vec3 v_normal;    // view frame
out vec3 v_colour;
out vec2 v_uv;

void main() {
  vec4 p = view_from_object * vec4(in_position, 1.0);
  v_position = p.xyz;
  v_normal = mat3(view_from_object) * in_normal;  // rigid: the rotation part maps normals
  v_colour = in_colour;
  v_uv = in_uv;
  gl_Position = clip_from_view * p;
}
