#version 330 core
// Silhouette strokes (render/gl/stroke_renderer.h), fragment stage: flat linear colour; the
// multisampled target smooths the edges.

in vec3 v_colour;
out vec4 out_colour;

void main() { out_colour = vec4(v_colour, 1.0); }
