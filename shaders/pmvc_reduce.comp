#version 430 core
// PMVC reduction (render/pmvc_gl.cpp): work group p sums the 6 n^2 texels of batch point p,
// layers 6p .. 6p+5, each times its texel's solid angle, in double precision. Fixed order:
// thread t sums texels t, t + 64, ... in turn, then a fixed pairwise tree over the 64 threads;
// no atomics, so the result does not depend on scheduling or on the batch.

layout(local_size_x = 64) in;

layout(binding = 0) uniform sampler2DArray cube;  // RGBA32F (colour / r, 1 / r); 0 = no hit
layout(binding = 1) uniform sampler2DArray material;  // RG32F (material channels / r)

layout(std430, binding = 1) readonly buffer SolidAngles {
  double solid_angle[];  // 6 n^2, face-major, rows, columns (cube_directions.h)
};
layout(std430, binding = 2) writeonly buffer Sums {
  dvec4 sums[];  // per point p: sums[2p] = (sum colour w, sum w), w = solid angle / r;
                 // sums[2p + 1] = (sum material w, 0, 0)
};

uniform int n;

shared dvec4 partial[64];
shared dvec2 partial_material[64];

void main() {
  const int point = int(gl_WorkGroupID.x);
  const int t = int(gl_LocalInvocationID.x);
  const int per_face = n * n;
  dvec4 sum = dvec4(0.0);
  dvec2 sum_material = dvec2(0.0);
  for (int i = t; i < 6 * per_face; i += 64) {
    const int face = i / per_face;
    const int rest = i - face * per_face;
    const int row = rest / n;
    const int col = rest - row * n;
    const ivec3 texel = ivec3(col, row, 6 * point + face);
    sum += dvec4(texelFetch(cube, texel, 0)) * solid_angle[i];
    sum_material += dvec2(texelFetch(material, texel, 0).xy) * solid_angle[i];
  }
  partial[t] = sum;
  partial_material[t] = sum_material;
  barrier();
  for (int s = 32; s > 0; s >>= 1) {
    if (t < s) {
      partial[t] += partial[t + s];
      partial_material[t] += partial_material[t + s];
    }
    barrier();
  }
  if (t == 0) {
    sums[2 * point] = partial[0];
    sums[2 * point + 1] = dvec4(partial_material[0], 0.0, 0.0);
  }
}
