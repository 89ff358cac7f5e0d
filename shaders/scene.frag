#version 330 core
// Scene preview (render/scene_preview.h), fragment stage: two-sided shading in linear RGB,
// hemisphere ambient + Lambert + a Blinn-Phong highlight per light, with the albedo from the
// vertex colour or the material's base colour texture. The constants, the highlight of each
// roughness and the light mapping are documented at render_scene_preview().

const int kMaxLights = 16;  // render/scene_preview.cpp: kMaxLights
const float kSky = 0.25;     // ambient from straight above (+Y)
const float kGround = 0.10;  // ambient from straight below
const float kDiffuse = 0.75;

in vec3 v_position;
in vec3 v_normal;
in vec3 v_colour;
in vec2 v_uv;

uniform int light_count;
// xyz: the direction toward the light (w = 0, directional) or its position (w = 1, point),
// view frame, metres.
uniform vec4 light_vector[kMaxLights];
// colour * relative illuminance * exposure; a point light's is at 1 m and falls off as 1/d^2.
uniform vec3 light_scale[kMaxLights];
uniform vec3 up_view;          // scene +Y in the view frame
uniform float ambient_scale;   // exposure
// The material: its base colour texture (sRGB, so samples are linear) when `textured` is
// non-zero, else the vertex colour; the Blinn-Phong exponent and weight of its highlight.
uniform int textured;
uniform sampler2D base_colour;
uniform float shininess;
uniform float specular_weight;

out vec4 out_colour;  // linear RGB, opaque

void main() {
  vec3 albedo = textured != 0 ? texture(base_colour, v_uv).rgb : v_colour;
  vec3 view = normalize(-v_position);  // toward the eye
  // The triangle's own normal, toward the eye: stands in for a zero shading normal.
  vec3 flat_normal = cross(dFdx(v_position), dFdy(v_position));
  vec3 n;
  if (dot(v_normal, v_normal) > 1e-12) {
    n = normalize(v_normal);
    if (!gl_FrontFacing) n = -n;                   // two-sided
    if (dot(n, view) < 0.0) n = reflect(n, view);  // smooth normals can lean away at silhouettes
  } else {
    n = dot(flat_normal, flat_normal) > 0.0 ? normalize(flat_normal) : view;
    if (dot(n, view) < 0.0) n = -n;
  }

  float hemisphere = mix(kGround, kSky, 0.5 + 0.5 * dot(n, up_view));
  vec3 diffuse = vec3(hemisphere * ambient_scale);
  vec3 specular = vec3(0.0);
  for (int i = 0; i < light_count; ++i) {
    vec3 l = light_vector[i].xyz;
    vec3 scale = light_scale[i];
    if (light_vector[i].w > 0.5) {
      l -= v_position;
      float d2 = max(dot(l, l), 1e-8);
      scale /= d2;
    }
    l = normalize(l);
    float lambert = dot(n, l);
    if (lambert <= 0.0) continue;
    diffuse += scale * (kDiffuse * lambert);
    specular += scale * (specular_weight * pow(max(dot(n, normalize(l + view)), 0.0), shininess));
  }
  out_colour = vec4(albedo * diffuse + specular, 1.0);
}
