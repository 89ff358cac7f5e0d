#version 330 core
// Cross-section preview (paper §3.2, Fig. 3), fragment stage: the interpolated linear RGB
// vertex colour, unlit and opaque; sRGB encoding happens on the CPU after readback.

in vec3 v_colour;

out vec4 out_colour;  // linear RGB, opaque

void main() {
  out_colour = vec4(v_colour, 1.0);
}
