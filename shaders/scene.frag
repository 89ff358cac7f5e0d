#version 330 core
// Scene preview (render/scene_preview.h), fragment stage: two-sided shading in linear RGB,
// hemisphere ambient + Lambert + glTF's specular reflection per light and one light's soft shadow,
// with the albedo from the vertex colour or the material's base colour texture and the normal
// tilted by the material's normal map (the skin's relief). The constants, the highlight of each
// roughness and the light mapping are documented at render_scene_preview().

const int kMaxLights = 16;  // render/scene_preview.cpp: kMaxLights
const float kSky = 1.0;     // ambient from straight above (+Y), of the sky's radiance
const float kGround = 0.4;  // ambient from straight below
const float kDiffuse = 1.0;
const float kF0 = 0.04;     // glTF's dielectric reflectance at normal incidence (IOR 1.5)
const float kPi = 3.14159265;

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
// The light's angular radius, radians (a directional light's source size; 0: a point).
uniform float light_radius[kMaxLights];
uniform vec3 up_view;          // scene +Y in the view frame
uniform float ambient_scale;   // the sky's radiance (ambient_lux / (683 pi)) times the exposure
// The material: its base colour texture (sRGB, so samples are linear) when `textured` is
// non-zero, else the vertex colour; its perceptual roughness (the reflection's, lobe()).
uniform int textured;
uniform sampler2D base_colour;
uniform float roughness;
// The clear layer on top (KHR_materials_clearcoat: the wet film on cut flesh, wax on a skin):
// its weight 0..1 and perceptual roughness; it has the surface's own normal.
uniform float clearcoat;
uniform float clearcoat_roughness;
// The relief: a tangent-space normal map (linear; X along +u, Y toward the top row, Z out of
// the surface: glTF's normalTexture) when `relief` is non-zero.
uniform int relief;
uniform sampler2D normal_map;
// The roughness per texel instead, when `roughness_mapped` is non-zero: the G channel of the
// material map (linear RGBA: glTF's metallicRoughnessTexture).
uniform int roughness_mapped;
uniform sampler2D material_map;

// The shadow of light `shadow_light` (-1: none; render_scene_preview() documents the map): its
// depth seen from the light, 0..1 over shadow_depth_m metres, square, shadow_width_m a side;
// shadow_from_view maps the view frame to the map's texture coordinates and depth.
uniform int shadow_light;
uniform sampler2D shadow_map;
uniform mat4 shadow_from_view;
uniform float shadow_depth_m;
uniform float shadow_width_m;
uniform float shadow_softness;  // tan of the light's angular radius: penumbra per metre

const float kShadowBias_m = 4e-4;      // depth a receiver may lie behind its own surface
const float kBlockerSearch_m = 0.012;  // radius searched for occluders, and widest penumbra
const int kBlockerTaps = 16, kFilterTaps = 32;

out vec4 out_colour;  // linear RGB, opaque

// Point k of n on a Vogel spiral filling the unit disc evenly (golden angle).
vec2 spiral(int k, int n) {
  float r = sqrt((float(k) + 0.5) / float(n));
  float a = 2.39996323 * float(k);
  return r * vec2(cos(a), sin(a));
}

// How much of the shadow light reaches the fragment (0..1) whose normal is n and direction to
// the light l: percentage-closer soft shadows (Fernando 2005), the occluders' mean depth found
// within kBlockerSearch_m, the penumbra as wide as the gap to them times shadow_softness.
// Depths are compared against the receiver's plane tilted by its slope to the light, so a
// surface does not shadow itself.
float lit_fraction(vec3 n, vec3 l) {
  vec3 s = (shadow_from_view * vec4(v_position, 1.0)).xyz;
  if (any(lessThan(s, vec3(0.0))) || any(greaterThan(s, vec3(1.0)))) return 1.0;
  float ndl = clamp(dot(n, l), 1e-3, 1.0);
  float slope = min(sqrt(1.0 - ndl * ndl) / ndl, 4.0);
  float texel_m = shadow_width_m / float(textureSize(shadow_map, 0).x);
  float receiver = s.z * shadow_depth_m;
  float blockers = 0.0;
  int found = 0;
  for (int k = 0; k < kBlockerTaps; ++k) {
    vec2 offset = kBlockerSearch_m * spiral(k, kBlockerTaps);
    float d = texture(shadow_map, s.xy + offset / shadow_width_m).r * shadow_depth_m;
    if (d < receiver - kShadowBias_m - (texel_m + length(offset)) * slope) {
      blockers += d;
      ++found;
    }
  }
  if (found == 0) return 1.0;
  float gap = receiver - blockers / float(found);
  float penumbra = clamp(gap * shadow_softness, texel_m, kBlockerSearch_m);
  float lit = 0.0;
  for (int k = 0; k < kFilterTaps; ++k) {
    vec2 offset = penumbra * spiral(k, kFilterTaps);
    float d = texture(shadow_map, s.xy + offset / shadow_width_m).r * shadow_depth_m;
    if (d >= receiver - kShadowBias_m - (texel_m + length(offset)) * slope) lit += 1.0;
  }
  return lit / float(kFilterTaps);
}

// `n` (unit, the side seen) tilted by the normal map, in the tangent frame the screen-space
// derivatives of position and uv give (Mikkelsen 2010, "Bump Mapping Unparametrized Surfaces on
// the GPU"; three.js's perturbNormal2Arb): T along +u, B along +v (down the rows), so the map's
// Y, which points up the rows, is taken negated.
vec3 tilted_by_relief(vec3 n) {
  vec3 q0 = dFdx(v_position), q1 = dFdy(v_position);
  vec2 st0 = dFdx(v_uv), st1 = dFdy(v_uv);
  vec3 q1perp = cross(q1, n), q0perp = cross(n, q0);
  vec3 t = q1perp * st0.x + q0perp * st1.x;
  vec3 b = q1perp * st0.y + q0perp * st1.y;
  float det = max(dot(t, t), dot(b, b));
  if (det <= 0.0) return n;
  vec3 m = texture(normal_map, v_uv).xyz * 2.0 - 1.0;
  vec3 tilted = (t * m.x - b * m.y) * inversesqrt(det) + n * m.z;
  return dot(tilted, tilted) > 0.0 ? normalize(tilted) : n;
}

// The direction within the disc of angular radius `radius` (radians) around the direction `l`
// toward a light that lies closest to `mirror` (the view direction mirrored about the normal):
// the representative point of Karis 2013 ("Real Shading in Unreal Engine 4", area lights), which
// stands for the whole disc in lobe(). `mirror` itself where it falls inside the disc.
vec3 toward_disc(vec3 mirror, vec3 l, float radius) {
  if (radius <= 0.0) return l;
  float c = dot(mirror, l);
  if (c >= cos(radius)) return mirror;
  vec3 across = mirror - c * l;
  return dot(across, across) > 1e-12 ? cos(radius) * l + sin(radius) * normalize(across) : l;
}

// The specular lobe toward the eye of a light seen at `l` (toward_disc() of its disc of angular
// radius `radius`), per unit of the light's display scale (its E / (683 pi)) and before Fresnel:
// glTF 2.0's metal-rough BRDF (Appendix B: the Trowbridge-Reitz (GGX) distribution of
// alpha = roughness^2, Smith's height-correlated visibility) times E cos, its peak lowered by
// (alpha / alpha')^2 with alpha' = alpha + radius / 2 (Karis 2013), so that a smooth face mirrors
// the disc at about the disc's own radiance and a rough one keeps its broad sheen. `vdh` returns
// the cosine Schlick's Fresnel takes.
float lobe(vec3 n, vec3 view, vec3 l, float radius, float r, out float vdh) {
  vdh = 1.0;
  float alpha = max(r * r, 2e-3);
  float widened = min(alpha + 0.5 * radius, 1.0);
  float ndl = dot(n, l), ndv = max(dot(n, view), 1e-4);
  if (ndl <= 0.0) return 0.0;
  vec3 h = normalize(l + view);
  float ndh = max(dot(n, h), 0.0);
  vdh = max(dot(view, h), 0.0);
  float a2 = alpha * alpha;
  float d = a2 / (kPi * pow(ndh * ndh * (a2 - 1.0) + 1.0, 2.0));
  float vis = 0.5 / (ndl * sqrt(ndv * ndv * (1.0 - a2) + a2) +
                     ndv * sqrt(ndl * ndl * (1.0 - a2) + a2));
  return vis * d * (alpha / widened) * (alpha / widened) * kPi * ndl;
}

// Schlick's Fresnel of a dielectric of reflectance kF0 at normal incidence, at cosine c.
float fresnel(float c) { return kF0 + (1.0 - kF0) * pow(1.0 - c, 5.0); }

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
  if (relief != 0) n = tilted_by_relief(n);

  float r = roughness_mapped != 0 ? texture(material_map, v_uv).g : roughness;

  float hemisphere = mix(kGround, kSky, 0.5 + 0.5 * dot(n, up_view));
  vec3 diffuse = vec3(hemisphere * ambient_scale);
  vec3 specular = vec3(0.0), coat = vec3(0.0);
  vec3 mirror = reflect(-view, n);
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
    if (i == shadow_light) scale *= lit_fraction(n, l);
    diffuse += scale * (kDiffuse * lambert);
    // The disc's point that both lobes see (it depends on the light and the normal alone).
    vec3 seen = toward_disc(mirror, l, light_radius[i]);
    float vdh;
    float base = lobe(n, view, seen, light_radius[i], r, vdh);
    specular += scale * (fresnel(vdh) * base);
    if (clearcoat > 0.0)
      coat += scale * lobe(n, view, seen, light_radius[i], clearcoat_roughness, vdh);
  }
  // The layering of KHR_materials_clearcoat: the coat's Fresnel at the view angle takes its share.
  float coated = clearcoat * fresnel(max(dot(n, view), 0.0));
  out_colour = vec4((albedo * diffuse + specular) * (1.0 - coated) + coated * coat, 1.0);
}
