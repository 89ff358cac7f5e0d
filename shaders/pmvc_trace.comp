#version 430 core
// PMVC by ray casting on the GPU (render/gl/pmvc_gl.cpp): work group p casts the cube-map
// texel rays of batch point p (make_cube_directions, turned by the point's cube_rotation)
// through a BVH of every sheet triangle (build_sheet_bvh), and sums the colour and material
// channels of each ray's nearest hit weighted by the texel's solid angle / hit distance, in
// double precision. With adaptive directions (adaptive_directions.h) the coarse texels are cast
// first, the pairs of neighbouring coarse texels that see different sheets or sides mark both
// refined, and a refined texel is summed from its four fine texels instead. Fixed order: thread
// t takes texels t, t + 256, ... in turn (a refined one's fine texels in their order), then a
// fixed pairwise tree over the 256 threads; the only atomics set refinement bits, so the result
// does not depend on scheduling or on the batch. Semantics are those of the cpu backend
// (pmvc_cpu.cpp).

// 256 threads a point: a round of the adaptive sampler diffuses only tens of points, and its
// latency is that of one work group's rays (6 a thread at cube 16).
layout(local_size_x = 256) in;
const int kThreads = 256;

struct Node {
  vec3 lo;    // box, metres
  int first;  // inner node: first child (second = first + 1); leaf: first triangle
  vec3 hi;
  int count;  // leaf: triangles; inner node: 0
};
struct Triangle {
  vec4 v0;       // xyz: first vertex, metres
  vec4 e1;       // xyz: second vertex - first
  vec4 e2;       // xyz: third vertex - first
  vec4 normal;   // xyz: unit normal of the front face
  uvec4 vertex;  // xyz: its vertices in `vertices`; w: 2 sheet + (1 if the sheet is two-faced)
};
struct Vertex {
  vec4 colour_front;  // rgb: linear
  vec4 colour_back;   // rgb: linear (= front on a sheet that is not two-faced)
  vec4 material;      // xy: front (roughness, translucency), zw: back
};
struct BatchPoint {
  vec4 eye;         // xyz: the point, metres
  vec4 to_world[3];  // xyz: columns of R, the rotation of the point's cube (cube_rotation)
};

layout(std430, binding = 0) readonly buffer Nodes { Node nodes[]; };
layout(std430, binding = 1) readonly buffer Triangles { Triangle triangles[]; };
layout(std430, binding = 2) readonly buffer Vertices { Vertex vertices[]; };
layout(std430, binding = 3) readonly buffer Directions { vec4 direction[]; };  // xyz, unit
layout(std430, binding = 4) readonly buffer SolidAngles { double solid_angle[]; };
layout(std430, binding = 5) readonly buffer Points { BatchPoint batch[]; };
layout(std430, binding = 6) writeonly buffer Sums {
  dvec4 sums[];  // per point p: sums[2p] = (sum colour w, sum w), w = solid angle / r;
                 // sums[2p + 1] = (sum material w, rays cast, 0)
};

// Adaptive directions only: the fine level (n x n) and the coarse pairs compared.
layout(std430, binding = 7) readonly buffer FineDirections { vec4 fine_direction[]; };
layout(std430, binding = 8) readonly buffer FineSolidAngles { double fine_solid_angle[]; };
layout(std430, binding = 9) readonly buffer Pairs { uvec2 pairs[]; };

uniform int direction_count;  // texels of the first level: 6 n^2, or 6 (n/2)^2 when adaptive
uniform int adaptive;         // 1: adaptive directions
uniform int fine_n;           // adaptive: n
uniform int pair_count;       // adaptive: coarse pairs

// Adaptive: at most kMaxCoarse coarse texels (cube 32, uses_adaptive_directions), kPerThread
// each; shared memory stays under the 32 KiB every OpenGL 4.3 implementation has.
const int kMaxCoarse = 1536;
const int kPerThread = kMaxCoarse / kThreads;
shared int seen[kMaxCoarse];                // what each coarse texel's ray hit
shared uint refined[kMaxCoarse / 32];       // bit per coarse texel

shared dvec4 partial[kThreads];
shared dvec3 partial_material[kThreads];  // xy: material, z: rays cast

/// Entry distance of the ray into node `i`'s box, or +inf when it misses or enters at or beyond
/// `best` (slab test; inv = 1 / direction with no zero components).
float enter(int i, vec3 origin, vec3 inv, float best) {
  const vec3 a = (nodes[i].lo - origin) * inv;
  const vec3 b = (nodes[i].hi - origin) * inv;
  const vec3 near = min(a, b), far = max(a, b);
  const float t0 = max(max(near.x, near.y), max(near.z, 0.0));
  const float t1 = min(min(far.x, far.y), far.z);
  return t0 <= t1 && t0 < best ? t0 : 1.0 / 0.0;
}

/// The nearest triangle hit along origin + t d, t >= 0: its index (-1: none), t, and the
/// barycentric coordinates (u, v) of the second and third vertex (Moller-Trumbore, with the
/// barycentric bounds widened by 1e-6 so that rays along shared edges do not slip through).
int trace(vec3 origin, vec3 d, out float best, out vec2 uv) {
  const float kEdge = 1e-6;
  vec3 safe = d;  // no zero components, so that the slab distances stay finite
  for (int k = 0; k < 3; ++k)
    if (abs(safe[k]) < 1e-20) safe[k] = safe[k] < 0.0 ? -1e-20 : 1e-20;
  const vec3 inv = 1.0 / safe;
  best = 1.0 / 0.0;
  uv = vec2(0.0);
  int hit = -1;
  int stack[64];
  float stack_t[64];
  int sp = 0;
  int node = 0;
  if (enter(0, origin, inv, best) == 1.0 / 0.0) return -1;
  while (true) {
    if (nodes[node].count > 0) {
      const int end = nodes[node].first + nodes[node].count;
      for (int k = nodes[node].first; k < end; ++k) {
        const vec3 e1 = triangles[k].e1.xyz, e2 = triangles[k].e2.xyz;
        const vec3 p = cross(d, e2);
        const float det = dot(e1, p);
        if (det == 0.0) continue;
        const float inv_det = 1.0 / det;
        const vec3 s = origin - triangles[k].v0.xyz;
        const float u = dot(s, p) * inv_det;
        if (u < -kEdge || u > 1.0 + kEdge) continue;
        const vec3 q = cross(s, e1);
        const float v = dot(d, q) * inv_det;
        if (v < -kEdge || u + v > 1.0 + kEdge) continue;
        const float t = dot(e2, q) * inv_det;
        if (t >= 0.0 && t < best) {
          best = t;
          uv = vec2(u, v);
          hit = k;
        }
      }
    } else {
      const int a = nodes[node].first;
      float ta = enter(a, origin, inv, best), tb = enter(a + 1, origin, inv, best);
      int near_node = a, far_node = a + 1;
      if (tb < ta) {
        const float t = ta;
        ta = tb;
        tb = t;
        near_node = a + 1;
        far_node = a;
      }
      if (ta < best) {
        if (tb < best && sp < 64) {  // depth of build_sheet_bvh trees: far below 64
          stack[sp] = far_node;
          stack_t[sp] = tb;
          ++sp;
        }
        node = near_node;
        continue;
      }
    }
    // Next: the nearest pending node that may still hold a nearer hit.
    bool found = false;
    while (sp > 0) {
      --sp;
      if (stack_t[sp] < best) {
        node = stack[sp];
        found = true;
        break;
      }
    }
    if (!found) return hit;
  }
}

/// One ray of the point: its contribution (colour w, w) and (material w) with w = solid angle /
/// distance, zero when it misses, and what it saw: 2 sheet + (1 on a two-faced sheet's back),
/// -1 for nothing.
int cast_ray(int point, vec3 c, double solid_angle, out dvec4 sum, out dvec2 sum_material) {
  const vec3 origin = batch[point].eye.xyz;
  const vec3 d = c.x * batch[point].to_world[0].xyz + c.y * batch[point].to_world[1].xyz +
                 c.z * batch[point].to_world[2].xyz;
  sum = dvec4(0.0);
  sum_material = dvec2(0.0);
  float r;
  vec2 uv;
  const int k = trace(origin, d, r, uv);
  if (k < 0) return -1;
  const uvec4 v = triangles[k].vertex;
  const float w0 = 1.0 - uv.x - uv.y;
  const bool front = dot(d, triangles[k].normal.xyz) < 0.0;
  const vec3 colour =
      front ? w0 * vertices[v.x].colour_front.rgb + uv.x * vertices[v.y].colour_front.rgb +
                  uv.y * vertices[v.z].colour_front.rgb
            : w0 * vertices[v.x].colour_back.rgb + uv.x * vertices[v.y].colour_back.rgb +
                  uv.y * vertices[v.z].colour_back.rgb;
  const vec4 m = w0 * vertices[v.x].material + uv.x * vertices[v.y].material +
                 uv.y * vertices[v.z].material;
  const double weight = solid_angle / max(double(r), 1e-9);
  sum = dvec4(dvec3(colour), 1.0) * weight;
  sum_material = dvec2(front ? m.xy : m.zw) * weight;
  const bool two_faced = (v.w & 1u) != 0u;
  return int(v.w & ~1u) + (two_faced && !front ? 1 : 0);
}

void main() {
  const int point = int(gl_WorkGroupID.x);
  const int t = int(gl_LocalInvocationID.x);
  dvec4 sum = dvec4(0.0);
  dvec2 sum_material = dvec2(0.0);
  int rays = 0;
  dvec4 ray_sum;
  dvec2 ray_material;
  if (adaptive == 0) {
    for (int i = t; i < direction_count; i += kThreads) {
      cast_ray(point, direction[i].xyz, solid_angle[i], ray_sum, ray_material);
      ++rays;
      sum += ray_sum;
      sum_material += ray_material;
    }
  } else {
    // Coarse rays, kept per thread until the refinement is known.
    dvec4 coarse_sum[kPerThread];
    dvec2 coarse_material[kPerThread];
    for (int i = t; i < kMaxCoarse / 32; i += kThreads) refined[i] = 0u;
    for (int i = t, j = 0; i < direction_count; i += kThreads, ++j) {
      seen[i] = cast_ray(point, direction[i].xyz, solid_angle[i], coarse_sum[j],
                         coarse_material[j]);
      ++rays;
    }
    memoryBarrierShared();
    barrier();
    for (int i = t; i < pair_count; i += kThreads) {
      const uvec2 p = pairs[i];
      if (seen[p.x] != seen[p.y]) {
        atomicOr(refined[p.x / 32u], 1u << (p.x % 32u));
        atomicOr(refined[p.y / 32u], 1u << (p.y % 32u));
      }
    }
    memoryBarrierShared();
    barrier();
    const int m = fine_n / 2;
    for (int i = t, j = 0; i < direction_count; i += kThreads, ++j) {
      if ((refined[i / 32] & (1u << (i % 32))) == 0u) {
        sum += coarse_sum[j];
        sum_material += coarse_material[j];
        continue;
      }
      // The four fine texels tiling coarse texel i (AdaptiveDirections::children).
      const int face = i / (m * m), row = (i / m) % m, column = i % m;
      const int first = face * fine_n * fine_n + 2 * row * fine_n + 2 * column;
      const int fine[4] = int[4](first, first + 1, first + fine_n, first + fine_n + 1);
      for (int f = 0; f < 4; ++f) {
        cast_ray(point, fine_direction[fine[f]].xyz, fine_solid_angle[fine[f]], ray_sum,
                 ray_material);
        ++rays;
        sum += ray_sum;
        sum_material += ray_material;
      }
    }
  }
  partial[t] = sum;
  partial_material[t] = dvec3(sum_material, double(rays));
  barrier();
  for (int s = kThreads / 2; s > 0; s >>= 1) {
    if (t < s) {
      partial[t] += partial[t + s];
      partial_material[t] += partial_material[t + s];
    }
    barrier();
  }
  if (t == 0) {
    sums[2 * point] = partial[0];
    sums[2 * point + 1] = dvec4(partial_material[0], 0.0);
  }
}
