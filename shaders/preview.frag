#version 330 core
// DS model preview (paper Fig. 9), fragment stage: the side's colour (front when the face is
// seen from the side its normal points to, CCW winding = front), lit two-sided in linear RGB by
// ambient + a key light near the eye, with a faint highlight; blended see-through, with the
// opacity rising toward silhouettes (like Fresnel) so that the outlines of nested surfaces read.

in vec3 v_position;
in vec3 v_normal;
in vec3 v_front;
in vec3 v_back;
in float v_alpha;

out vec4 out_colour;  // linear RGB, straight (not premultiplied) alpha

const vec3 kKeyDirection = normalize(vec3(-0.35, 0.55, 1.0));  // toward the light, view frame
const float kAmbient = 0.25;
const float kKey = 0.85;
const float kSpecular = 0.12;
const float kShininess = 40.0;
const float kRimOpacity = 0.6;

void main() {
  vec3 view = normalize(-v_position);  // toward the eye
  vec3 n = normalize(v_normal);
  if (!gl_FrontFacing) n = -n;
  if (dot(n, view) < 0.0) n = reflect(n, view);  // smooth normals can lean away at silhouettes
  vec3 albedo = gl_FrontFacing ? v_front : v_back;

  float lambert = max(dot(n, kKeyDirection), 0.0);
  float highlight = pow(max(dot(n, normalize(kKeyDirection + view)), 0.0), kShininess);
  float rim = pow(1.0 - clamp(dot(n, view), 0.0, 1.0), 3.0);

  vec3 colour = albedo * (kAmbient + kKey * lambert) + vec3(kSpecular * highlight);
  float alpha = mix(v_alpha, 1.0, kRimOpacity * rim);
  out_colour = vec4(colour, alpha);
}
