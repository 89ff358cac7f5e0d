#version 330 core
// Silhouette strokes (render/gl/stroke_renderer.h), vertex stage: the strip's corners are already
// in pixels (x right, y down from the top row); this maps them to clip space.

layout(location = 0) in vec2 in_pixel;
layout(location = 1) in vec3 in_colour;  // linear RGB

uniform vec2 image_size;  // pixels

out vec3 v_colour;

void main() {
  v_colour = in_colour;
  gl_Position = vec4(2.0 * in_pixel.x / image_size.x - 1.0, 1.0 - 2.0 * in_pixel.y / image_size.y,
                     0.0, 1.0);
}
