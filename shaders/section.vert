#version 330 core
// Cross-section preview (paper §3.2, Fig. 3): the cut face seen head-on, orthographic. Vertex
// stage: in-plane coordinates -> clip by one scale per axis; the colour passes through for
// Gouraud interpolation (section.frag).

layout(location = 0) in vec2 in_section;  // (u, v) metres, relative to the image centre
layout(location = 1) in vec3 in_colour;   // linear RGB

uniform vec2 clip_from_section;  // per-axis scale, 1/metres (x along u, y along v)

out vec3 v_colour;

void main() {
  v_colour = in_colour;
  gl_Position = vec4(in_section * clip_from_section, 0.0, 1.0);
}
