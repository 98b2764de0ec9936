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
 *   CLPT_PRECISION 2 double: real = double everywhere a path computes; double polynomials for
 *                            sin, cos and pow (to the library's accuracy, and vectorisable)
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
/* CLPT_NO_FAST_GATHER (kernel_options.cpp): 1 for a PoCL CPU whose LLVM tuning has no fast
 * gathers, in a specialised kernel whose spheres are all in the loop (none in the hierarchy). Its
 * compiler costs every per-lane indexed read as one scalar load per lane and then keeps the
 * shading scalar, so the kernels read the hit sphere by selects over the loop's spheres
 * (intersect.cl, path.cl) and the lockstep megakernel keeps its state in local memory
 * (megakernel.cl); docs/performance.md, "CPUs without fast gathers". */
#ifndef CLPT_NO_FAST_GATHER
#define CLPT_NO_FAST_GATHER 0
#endif
/* CLPT_MATERIAL_BY_SELECT (kernel_options.cpp): the hit sphere's material is picked by selects
 * over the loop's spheres (path.cl, sphere_material) rather than gathered: with CLPT_NO_FAST_GATHER,
 * and in the lockstep megakernel that carries the hit sphere's centre (intersect.cl), where it
 * measured 1.05-1.25x (docs/performance.md, "What limits the speed"). */
#ifndef CLPT_MATERIAL_BY_SELECT
#define CLPT_MATERIAL_BY_SELECT CLPT_NO_FAST_GATHER
#endif

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
/* The y component of a float[3] in a buffer or in the parameters, v[1]. The double preset reads
 * it through a choice the compiler cannot resolve: get_global_size(1) is 1 (every clpt kernel is
 * launched over one dimension, host/cl/cl_context.cpp, and OpenCL gives an unused dimension the
 * size 1), so it is always v[1], and the other load costs a cached read. Why: PoCL runs LLVM's
 * SLP vectoriser on each work-item's code before it builds the work-item loops, and for doubles
 * SLP pairs the x and y of two adjacent float loads, widened to double, into <2 x double> (one
 * 128-bit load and convert); from there the pairs spread through the path's arithmetic and its
 * loop state, and a work-item loop holding vector-typed values is not vectorised ("instruction
 * return type cannot be vectorized"). With y no longer a plain load next to x, SLP finds no
 * profitable tree and the work-item loop vectoriser runs 4 double paths per 256-bit instruction
 * (docs/performance.md, "Presets"). A choice rather than a computed index: an index unknown at
 * compile time puts a private array (the camera in the parameters) in scratch memory on a GPU.
 * Float loads are not paired (SLP finds no profitable <2 x float> tree there), so the float
 * presets read v[1] directly; floats are paired where a reduction invites it (v3_unpaired). */
#define CLPT_Y_APART(v) (get_global_size(1) == 1 ? (v)[1] : (v)[2])
#if CLPT_PRECISION == CLPT_PRECISION_DOUBLE
#define CLPT_Y_OF(v) CLPT_Y_APART(v)
#else
#define CLPT_Y_OF(v) ((v)[1])
#endif
CLPT_INLINE Vec3 v3_load(const float v[3]) { return v3(v[0], CLPT_Y_OF(v), v[2]); }
/* v3_load with y read apart in every preset, for the camera's vectors (camera.cl): with the
 * sampler fixed at compile time (CLPT_SAMPLER), SLP pairs the x and y of the sensor's three
 * vectors and of the ray direction built from them into <2 x float>, which stops the lockstep
 * megakernel's work-item loop as above. They are the same for every work-item, so the extra read
 * is one per work-group, not a gather. */
CLPT_INLINE Vec3 v3_load_apart(const float v[3]) { return v3(v[0], CLPT_Y_APART(v), v[2]); }
/* A scene buffer's float[3] (a sphere's, a material's, a triangle's) as v3_load_global, with y read
 * apart where the kernels pick a sphere's fields
 * by selects (CLPT_NO_FAST_GATHER, CLPT_MATERIAL_BY_SELECT): the picks' reads are the same for
 * every work-item, and SLP pairs adjacent ones as it pairs the camera's. Likewise in the kernels
 * of a small mesh in the triangle loop (CLPT_TRIANGLE_COUNT, triangle_loop.cl), whose shading
 * reads the hit triangle's material in a vectorised region: SLP pairs its reflectance's x and y. */
#if CLPT_NO_FAST_GATHER || CLPT_MATERIAL_BY_SELECT || (defined(CLPT_TRIANGLE_COUNT) && CLPT_TRIANGLE_COUNT > 0)
#define v3_load_sphere_field(v) v3((v)[0], CLPT_Y_APART(v), (v)[2])
#else
#define v3_load_sphere_field(v) v3_load_global(v)
#endif
CLPT_INLINE Vec3 v3_load_global(__global const float* v) { return v3(v[0], CLPT_Y_OF(v), v[2]); }

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
/* `&`, not `&&`: a short-circuit puts the later components' reads behind a branch, and a load
 * under a branch is a masked load to PoCL's vectoriser (costed as a gather, docs/performance.md
 * "CPUs without fast gathers"). */
CLPT_INLINE bool v3_is_zero(Vec3 a) { return (a.x == 0.0f) & (a.y == 0.0f) & (a.z == 0.0f); }

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
#else
/* sin x and cos x for |x| <= pi/4 (x2 = x^2), Taylor polynomials. Float: to x^9 and x^10, about
 * 2e-7 absolute. Double: to x^17 and x^18, whose first omitted terms are below 1e-19, so the
 * result is as accurate as the library's; the library's sin and cos are calls (with a large-
 * argument reduction) that PoCL cannot vectorise across work-items. */
#if CLPT_PRECISION == CLPT_PRECISION_DOUBLE
CLPT_INLINE real sin_quarter_turn(real x, real x2) {
  return x * (1.0 + x2 * (-1.0 / 6 + x2 * (1.0 / 120 + x2 * (-1.0 / 5040 + x2 * (1.0 / 362880 +
         x2 * (-1.0 / 39916800 + x2 * (1.0 / 6227020800.0 + x2 * (-1.0 / 1307674368000.0 +
         x2 * (1.0 / 355687428096000.0)))))))));
}
CLPT_INLINE real cos_quarter_turn(real x2) {
  return 1.0 + x2 * (-0.5 + x2 * (1.0 / 24 + x2 * (-1.0 / 720 + x2 * (1.0 / 40320 + x2 * (-1.0 / 3628800 +
         x2 * (1.0 / 479001600 + x2 * (-1.0 / 87178291200.0 + x2 * (1.0 / 20922789888000.0 +
         x2 * (-1.0 / 6402373705728000.0)))))))));
}
#else
CLPT_INLINE float sin_quarter_turn(float x, float x2) {
  return x * (1.0f + x2 * (-1.0f / 6 + x2 * (1.0f / 120 + x2 * (-1.0f / 5040 + x2 * (1.0f / 362880)))));
}
CLPT_INLINE float cos_quarter_turn(float x2) {
  return 1.0f + x2 * (-0.5f + x2 * (1.0f / 24 + x2 * (-1.0f / 720 + x2 * (1.0f / 40320 + x2 * (-1.0f / 3628800)))));
}
#endif
/* A quadrant reduction, then the polynomials on [-pi/4, pi/4]; branch-free. */
CLPT_INLINE Float2 unit_circle(real u) {
  const real quadrant = rint(u * (real)4);
  const real x = (real)2 * CLPT_PI * (u - (real)0.25 * quadrant); /* in [-pi/4, pi/4] */
  const real x2 = x * x;
  const real s = sin_quarter_turn(x, x2);
  const real c = cos_quarter_turn(x2);
  /* Rotate (c, s) by q quarter turns, with selects rather than branches. */
  const int q = ((int)quadrant) & 3;
  const real odd_c = (q & 1) ? -s : c; /* q = 1: (-s, c); q = 3: (s, -c) after the sign below */
  const real odd_s = (q & 1) ? c : s;
  const real sign = (q & 2) ? (real)-1 : (real)1;
  return f2(sign * odd_c, sign * odd_s);
}
#endif

/* u^a for u in [0, 1] and a > 0: log2 from the exponent bits and an atanh series, exp2 from a
 * Taylor polynomial and the exponent bits; about 3e-7 relative in float, 1e-15 in double. The
 * library pow is a call PoCL cannot vectorise (its float exp2/log2 also use 2-wide vectors
 * internally, which stop the vectoriser); PoCL's native_powr likewise (the fast preset's Phong
 * scenes ran 11x slower with it), so every preset uses this. The series per precision: */
#if CLPT_PRECISION == CLPT_PRECISION_DOUBLE
typedef ulong real_bits;
#define clpt_real_as_bits as_ulong
#define clpt_bits_as_real as_double
#define CLPT_MANTISSA_BITS 52
#define CLPT_EXPONENT_BIAS 1023
#define CLPT_MANTISSA_MASK 0x000fffffffffffffUL
#define CLPT_SQRT2 1.4142135623730951
#define CLPT_LOG2_E 1.4426950408889634
#define CLPT_LN_2 0.6931471805599453
/* ln m = 2 atanh f for |f| <= 0.1716: to f^21 (the next term is below 1e-18). */
CLPT_INLINE real ln_atanh_series(real f, real f2) {
  return 2.0 * f * (1.0 + f2 * (1.0 / 3 + f2 * (1.0 / 5 + f2 * (1.0 / 7 + f2 * (1.0 / 9 + f2 * (1.0 / 11 +
         f2 * (1.0 / 13 + f2 * (1.0 / 15 + f2 * (1.0 / 17 + f2 * (1.0 / 19 + f2 * (1.0 / 21)))))))))));
}
/* e^z for z in [0, ln 2): to z^17 (the next term is below 1e-18). */
CLPT_INLINE real exp_taylor(real z) {
  return 1.0 + z * (1.0 + z * (0.5 + z * (1.0 / 6 + z * (1.0 / 24 + z * (1.0 / 120 + z * (1.0 / 720 +
         z * (1.0 / 5040 + z * (1.0 / 40320 + z * (1.0 / 362880 + z * (1.0 / 3628800 + z * (1.0 / 39916800 +
         z * (1.0 / 479001600 + z * (1.0 / 6227020800.0 + z * (1.0 / 87178291200.0 + z * (1.0 / 1307674368000.0 +
         z * (1.0 / 20922789888000.0 + z * (1.0 / 355687428096000.0)))))))))))))))));
}
#else
typedef uint real_bits;
#define clpt_real_as_bits as_uint
#define clpt_bits_as_real as_float
#define CLPT_MANTISSA_BITS 23
#define CLPT_EXPONENT_BIAS 127
#define CLPT_MANTISSA_MASK 0x007fffffu
#define CLPT_SQRT2 1.41421356f
#define CLPT_LOG2_E 1.44269504f
#define CLPT_LN_2 0.693147181f
CLPT_INLINE real ln_atanh_series(real f, real f2) {
  return 2.0f * f * (1.0f + f2 * (1.0f / 3 + f2 * (1.0f / 5 + f2 * (1.0f / 7 + f2 * (1.0f / 9)))));
}
CLPT_INLINE real exp_taylor(real z) {
  return 1.0f + z * (1.0f + z * (0.5f + z * (1.0f / 6 + z * (1.0f / 24 + z * (1.0f / 120 + z * (1.0f / 720 +
         z * (1.0f / 5040 + z * (1.0f / 40320 + z * (1.0f / 362880)))))))));
}
#endif
CLPT_INLINE real pow_unit(real u, real a) {
  const real_bits bits = clpt_real_as_bits(u);
  int e = (int)(bits >> CLPT_MANTISSA_BITS) - CLPT_EXPONENT_BIAS;
  real m = clpt_bits_as_real((bits & CLPT_MANTISSA_MASK) | ((real_bits)CLPT_EXPONENT_BIAS << CLPT_MANTISSA_BITS)); /* [1, 2) */
  const bool high = m > CLPT_SQRT2;
  m = high ? (real)0.5 * m : m;
  e = high ? e + 1 : e;
  const real f = (m - (real)1) / (m + (real)1); /* |f| <= 0.1716 */
  const real ln_m = ln_atanh_series(f, f * f);
  const real y = a * ((real)e + ln_m * CLPT_LOG2_E); /* a log2(u) <= 0 */
  const real whole = floor(y);
  const real exp_z = exp_taylor((y - whole) * CLPT_LN_2); /* 2^(y - whole) = e^z, z in [0, ln 2) */
  const int k = (int)whole;
  const int min_exponent = 1 - CLPT_EXPONENT_BIAS;
  const real scale = clpt_bits_as_real((real_bits)(max(k, min_exponent) + CLPT_EXPONENT_BIAS) << CLPT_MANTISSA_BITS);
  return (u <= (real)0 || k < min_exponent) ? (real)0 : exp_z * scale;
}

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

/* a / b for a in [0, 2^31) and b in [1, 2^30), exact, by float estimates and integer corrections
 * (the kernels divide job and pixel indices, under 2^28: render/limits.h bounds a launch). Why not
 * a / b: CPUs have no vector integer division, so a division in the code before the lockstep
 * megakernel's loop (the job's pixel, sample, row and column) made LLVM's cost model keep that
 * whole region scalar (docs/performance.md, "What limits the speed"). The first estimate is
 * within q 2^-22 + 1 of q = floor(a / b); the remainder it leaves, under 2^10 + 2 b in size,
 * gives a second estimate within 1; the last step is exact integer arithmetic. Holds with fast
 * maths too, whose float errors are a few ulp. */
CLPT_INLINE uint clpt_udiv(uint a, uint b) {
  const float fb = (float)b;
  uint q = (uint)((float)a / fb);
  q += (uint)(int)((float)(int)(a - q * b) / fb);
  const int r = (int)(a - q * b);
  q = r < 0 ? q - 1u : q;
  q = r >= (int)b ? q + 1u : q;
  return q;
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
