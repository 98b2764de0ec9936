/* maths.cl: small vector helpers shared by every stage.
 *
 * unit_circle() replaces sin/cos: PoCL's accurate libm sin/cos took two thirds of a naive
 * path-tracing kernel's time (numerics.md). A quadrant reduction plus short Taylor polynomials
 * on [-pi/4, pi/4] is accurate to about 2e-7 absolute, branch-free and vectorisable. */
#ifndef CLPT_MATHS_CL
#define CLPT_MATHS_CL

#define CLPT_PI 3.14159265358979323846f

/* Stage functions are inlined into every kernel: PoCL vectorises a kernel across work-items only
 * when its body has no calls left, and GPUs avoid the call overhead. */
#define CLPT_INLINE inline __attribute__((always_inline))

CLPT_INLINE float3 load_float3(const float v[3]) { return (float3)(v[0], v[1], v[2]); }
CLPT_INLINE float3 load_global_float3(__global const float* v) { return (float3)(v[0], v[1], v[2]); }

/* (cos 2 pi u, sin 2 pi u) for u in [0, 1]. */
CLPT_INLINE float2 unit_circle(float u) {
  const float quadrant = rint(u * 4.0f);
  const float x = 2.0f * CLPT_PI * (u - 0.25f * quadrant); /* in [-pi/4, pi/4] */
  const float x2 = x * x;
  const float s =
      x * (1.0f + x2 * (-1.0f / 6 + x2 * (1.0f / 120 + x2 * (-1.0f / 5040 + x2 * (1.0f / 362880)))));
  const float c =
      1.0f + x2 * (-0.5f + x2 * (1.0f / 24 + x2 * (-1.0f / 720 + x2 * (1.0f / 40320 +
                                                                          x2 * (-1.0f / 3628800)))));
  const int q = ((int)quadrant) & 3;
  /* Rotate (c, s) by q quarter turns. */
  const float cos_out = q == 0 ? c : (q == 1 ? -s : (q == 2 ? -c : s));
  const float sin_out = q == 0 ? s : (q == 1 ? c : (q == 2 ? -s : -c));
  return (float2)(cos_out, sin_out);
}

/* Orthonormal basis around unit n (Duff et al., JCGT 2017): branch-free, continuous except
 * across n.z = 0's sign. Returns tangent in *t and bitangent in *b, (t, b, n) right-handed. */
CLPT_INLINE void orthonormal_basis(float3 n, float3* t, float3* b) {
  const float sign = copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float bxy = n.x * n.y * a;
  *t = (float3)(1.0f + sign * n.x * n.x * a, sign * bxy, -sign * n.x);
  *b = (float3)(bxy, sign + n.y * n.y * a, -n.y);
}

/* Local direction (x, y, z around n) to world. */
CLPT_INLINE float3 to_world(float3 local_dir, float3 n) {
  float3 t, b;
  orthonormal_basis(n, &t, &b);
  return local_dir.x * t + local_dir.y * b + local_dir.z * n;
}

/* NaN/Inf test on the representation: survives -cl-fast-relaxed-math, under which compilers
 * may fold `x != x` to false (numerics.md). */
CLPT_INLINE bool is_finite_bits(float x) { return (as_uint(x) & 0x7f800000u) != 0x7f800000u; }
CLPT_INLINE bool all_finite3(float3 v) {
  return is_finite_bits(v.x) && is_finite_bits(v.y) && is_finite_bits(v.z);
}

#endif
