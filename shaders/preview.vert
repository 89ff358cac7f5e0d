#version 330 core
// DS model preview (paper Fig. 9): every surface see-through. Vertex stage: object -> view ->
// clip; the rest of the shading happens per fragment in view space (preview.frag).

layout(location = 0) in vec3 in_position;  // metres, object frame
layout(location = 1) in vec3 in_normal;    // smooth vertex normal, object frame (unnormalised)
layout(location = 2) in vec3 in_front;     // linear RGB seen from the front (normal) side
layout(location = 3) in vec3 in_back;      // linear RGB seen from the back side
layout(location = 4) in float in_alpha;    // surface opacity 0..1

uniform mat4 view_from_object;  // rigid
uniform mat4 clip_from_view;

out vec3 v_position;  // view frame
out vec3 v_normal;    // view frame
out vec3 v_front;
out vec3 v_back;
out float v_alpha;

void main() {
  vec4 p = view_from_object * vec4(in_position, 1.0);
  v_position = p.xyz;
  v_normal = mat3(view_from_object) * in_normal;  // rigid: the rotation part maps normals
  v_front = in_front;
  v_back = in_back;
  v_alpha = in_alpha;
  gl_Position = clip_from_view * p;
}
