/* maths.cl: the scalar vector type and helpers every stage uses.
 *
 * Vec3 is a struct of three floats, not OpenCL's float3: PoCL vectorises a kernel across
 * work-items (8 or 16 per SIMD instruction on a CPU) only when every instruction is scalar, and
 * a single float3 operation stopped it (measured: the same 8-sphere test ran 8x slower written
 * with float3). GPUs compile both the same way. For the same reason no helper returns an OpenCL
 * vector type, and stage functions are always inlined (a call also stops the vectoriser).
 *
 * unit_circle() replaces sin/cos: PoCL's accurate libm sin/cos took two thirds of a naive
 * path-tracing kernel's time (docs/numerics.md). A quadrant reduction plus short Taylor polynomials
 * on [-pi/4, pi/4] is accurate to about 2e-7 absolute and branch-free.
 *
 * Precision presets (host/kernels/kernel_options.cpp decides; README "Precision presets"):
 *   CLPT_PRECISION 0 fast:   real = float, built with -cl-unsafe-math-optimizations; native_* sin and
 *                            cos, the pow polynomial below; the cheaper surface-point intersection
 *                            (intersect.cl)
 *   CLPT_PRECISION 1 robust: real = float, IEEE maths, the polynomials below
 *   CLPT_PRECISION 2 double: real = double everywhere a path computes; library sin, cos, pow
 * Buffers of the scene stay float (camera-relative, so their rounding is relative to distances
 * inside the scene); random numbers stay 24-bit. */
#ifndef CLPT_MATHS_CL
#define CLPT_MATHS_CL

#define CLPT_PRECISION_FAST 0
#define CLPT_PRECISION_ROBUST 1
#define CLPT_PRECISION_DOUBLE 2
#ifndef CLPT_PRECISION
#define CLPT_PRECISION CLPT_PRECISION_ROBUST
#endif

#if CLPT_PRECISION == CLPT_PRECISION_DOUBLE
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
typedef double real;
#else
typedef float real;
#endif

#define CLPT_PI ((real)3.14159265358979323846)
#define CLPT_INLINE inline __attribute__((always_inline))
/* Distance reported for "no hit". Finite on purpose: under -cl-fast-relaxed-math (which implies
 * -cl-finite-math-only) a compiler may fold comparisons with INFINITY. */
#define CLPT_NO_HIT ((real)1e30f)

/* One square root for every preset: under -cl-fast-relaxed-math the compiler may already use an
 * approximate one, and native_sqrt measured no faster on PoCL. */
#define clpt_sqrt(x) sqrt(x)

/* Every small private struct ends with CLPT_ABI_PAD, which makes it larger than 16 bytes. PoCL
 * compiles for the host's ABI, and x86-64 passes a struct of at most 16 bytes in registers, as
 * 2-float vectors ({x, y} of a Vec3) or 64-bit integers (two uints); those pieces survive
 * inlining, and one vector- or 64-bit-typed value in a loop stops PoCL's vectoriser across
 * work-items, or halves its width (measured: the lockstep megakernel ran 6x slower without the
 * pads). A larger struct is passed in memory, which inlining removes without a trace; the pad
 * itself is never read or written, so it costs nothing. */
#define CLPT_ABI_PAD(type, n) type abi_pad_[n];
typedef struct Vec3 {
  real x, y, z;
  CLPT_ABI_PAD(real, 2)
} Vec3;

CLPT_INLINE Vec3 v3(real x, real y, real z) {
  Vec3 v;
  v.x = x;
  v.y = y;
  v.z = z;
  return v;
}
CLPT_INLINE Vec3 v3_splat(real s) { return v3(s, s, s); }

/* v itself, passed through memory that LLVM's SLP vectoriser cannot see through, in the CPU's
 * lockstep megakernel (CLPT_LOCKSTEP_GROUP); elsewhere v unchanged, at no cost. Why: PoCL runs
 * SLP over each work-item's code before it builds the work-item loops, and where SLP pairs the
 * x and y of a value into a <2 x float> (the slab test's per-axis min/max invites it), the
 * vector-typed value travels into the path state, and PoCL's work-item vectoriser refuses every
 * region that holds it (measured on the hierarchy kernel: no region vectorised, 20 with the copy;
 * docs/performance.md "Traversal"). A volatile copy costs three stores and three loads. */
CLPT_INLINE Vec3 v3_unpaired(Vec3 v) {
#if defined(CLPT_LOCKSTEP_GROUP) && CLPT_LOCKSTEP_GROUP
  volatile real c[3];
  c[0] = v.x;
  c[1] = v.y;
  c[2] = v.z;
  return v3(c[0], c[1], c[2]);
#else
  return v;
#endif
}
CLPT_INLINE Vec3 v3_load(const float v[3]) { return v3(v[0], v[1], v[2]); }
CLPT_INLINE Vec3 v3_load_global(__global const float* v) { return v3(v[0], v[1], v[2]); }
CLPT_INLINE Vec3 v3_add(Vec3 a, Vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
CLPT_INLINE Vec3 v3_sub(Vec3 a, Vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
CLPT_INLINE Vec3 v3_mul(Vec3 a, Vec3 b) { return v3(a.x * b.x, a.y * b.y, a.z * b.z); }
CLPT_INLINE Vec3 v3_scale(Vec3 a, real s) { return v3(a.x * s, a.y * s, a.z * s); }
CLPT_INLINE Vec3 v3_neg(Vec3 a) { return v3(-a.x, -a.y, -a.z); }
CLPT_INLINE real v3_dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
/* a + s b */
CLPT_INLINE Vec3 v3_add_scaled(Vec3 a, Vec3 b, real s) { return v3(a.x + s * b.x, a.y + s * b.y, a.z + s * b.z); }
CLPT_INLINE Vec3 v3_normalize(Vec3 a) { return v3_scale(a, (real)1 / clpt_sqrt(v3_dot(a, a))); }
/* Component-wise choice. Never write `c ? vec_a : vec_b` on Vec3: a select of a whole struct
 * stops PoCL's vectoriser ("instruction return type cannot be vectorized"). */
CLPT_INLINE Vec3 v3_select(bool c, Vec3 a, Vec3 b) { return v3(c ? a.x : b.x, c ? a.y : b.y, c ? a.z : b.z); }
CLPT_INLINE bool v3_is_zero(Vec3 a) { return a.x == 0.0f && a.y == 0.0f && a.z == 0.0f; }

typedef struct Float2 {
  real x, y;
  CLPT_ABI_PAD(real, 3)
} Float2;

CLPT_INLINE Float2 f2(real x, real y) {
  Float2 v;
  v.x = x;
  v.y = y;
  return v;
}

/* (cos 2 pi u, sin 2 pi u) for u in [0, 1]. */
#if CLPT_PRECISION == CLPT_PRECISION_FAST
CLPT_INLINE Float2 unit_circle(float u) { return f2(native_cos(2.0f * CLPT_PI * u), native_sin(2.0f * CLPT_PI * u)); }
#elif CLPT_PRECISION == CLPT_PRECISION_DOUBLE
CLPT_INLINE Float2 unit_circle(real u) { return f2(cos(2.0 * CLPT_PI * u), sin(2.0 * CLPT_PI * u)); }
#else
CLPT_INLINE Float2 unit_circle(float u) {
  const float quadrant = rint(u * 4.0f);
  const float x = 2.0f * CLPT_PI * (u - 0.25f * quadrant); /* in [-pi/4, pi/4] */
  const float x2 = x * x;
  const float s =
      x * (1.0f + x2 * (-1.0f / 6 + x2 * (1.0f / 120 + x2 * (-1.0f / 5040 + x2 * (1.0f / 362880)))));
  const float c =
      1.0f + x2 * (-0.5f + x2 * (1.0f / 24 + x2 * (-1.0f / 720 + x2 * (1.0f / 40320 +
                                                                          x2 * (-1.0f / 3628800)))));
  /* Rotate (c, s) by q quarter turns, with selects rather than branches. */
  const int q = ((int)quadrant) & 3;
  const float odd_c = (q & 1) ? -s : c; /* q = 1: (-s, c); q = 3: (s, -c) after the sign below */
  const float odd_s = (q & 1) ? c : s;
  const float sign = (q & 2) ? -1.0f : 1.0f;
  return f2(sign * odd_c, sign * odd_s);
}
#endif

/* u^a for u in [0, 1] and a > 0, to about 3e-7 relative: log2 from the exponent bits and an
 * atanh series, exp2 from a Taylor polynomial and the exponent bits. The library pow is a call
 * PoCL cannot vectorise and its exp2/log2 use 2-wide vectors internally, which stop the vectoriser;
 * PoCL's native_powr likewise (the fast preset's Phong scenes ran 11x slower with it), so the fast
 * preset uses this polynomial too. */
#if CLPT_PRECISION == CLPT_PRECISION_DOUBLE
CLPT_INLINE real pow_unit(real u, real a) { return u <= 0.0 ? 0.0 : pow(u, a); }
#else
CLPT_INLINE float pow_unit(float u, float a) {
  const uint bits = as_uint(u);
  int e = (int)(bits >> 23) - 127;
  float m = as_float((bits & 0x007fffffu) | 0x3f800000u); /* [1, 2) */
  const bool high = m > 1.41421356f;
  m = high ? 0.5f * m : m;
  e = high ? e + 1 : e;
  const float f = (m - 1.0f) / (m + 1.0f); /* |f| <= 0.1716 */
  const float f2 = f * f;
  const float ln_m = 2.0f * f * (1.0f + f2 * (1.0f / 3 + f2 * (1.0f / 5 + f2 * (1.0f / 7 + f2 * (1.0f / 9)))));
  const float y = a * ((float)e + ln_m * 1.44269504f); /* a log2(u) <= 0 */
  const float whole = floor(y);
  const float z = (y - whole) * 0.693147181f; /* 2^(y - whole) = e^z, z in [0, ln 2) */
  const float exp_z =
      1.0f + z * (1.0f + z * (0.5f + z * (1.0f / 6 + z * (1.0f / 24 + z * (1.0f / 120 + z * (1.0f / 720 +
      z * (1.0f / 5040 + z * (1.0f / 40320 + z * (1.0f / 362880)))))))));
  const int k = (int)whole;
  const float scale = as_float((uint)(max(k, -126) + 127) << 23);
  return (u <= 0.0f || k < -126) ? 0.0f : exp_z * scale;
}
#endif

/* Orthonormal basis around unit n (Duff et al., JCGT 2017): branch-free. Returns the tangent in
 * *t and the bitangent in *b, (t, b, n) right-handed. */
CLPT_INLINE void orthonormal_basis(Vec3 n, Vec3* t, Vec3* b) {
  const real sign = copysign((real)1, n.z);
  const real a = (real)-1 / (sign + n.z);
  const real bxy = n.x * n.y * a;
  *t = v3(1.0f + sign * n.x * n.x * a, sign * bxy, -sign * n.x);
  *b = v3(bxy, sign + n.y * n.y * a, -n.y);
}

/* Local direction (x, y, z around n) to world. */
CLPT_INLINE Vec3 to_world(Vec3 local_dir, Vec3 n) {
  Vec3 t, b;
  orthonormal_basis(n, &t, &b);
  return v3_add(v3_add(v3_scale(t, local_dir.x), v3_scale(b, local_dir.y)), v3_scale(n, local_dir.z));
}

/* NaN/Inf test on the representation: survives -cl-fast-relaxed-math, under which compilers
 * may fold `x != x` to false (docs/numerics.md). */
CLPT_INLINE bool is_finite_bits(float x) { return (as_uint(x) & 0x7f800000u) != 0x7f800000u; }
#if CLPT_PRECISION == CLPT_PRECISION_DOUBLE
CLPT_INLINE bool is_finite_real(double x) {
  return (as_ulong(x) & 0x7ff0000000000000ul) != 0x7ff0000000000000ul;
}
#else
#define is_finite_real is_finite_bits
#endif
CLPT_INLINE bool v3_all_finite(Vec3 v) {
  return is_finite_real(v.x) && is_finite_real(v.y) && is_finite_real(v.z);
}

#endif
