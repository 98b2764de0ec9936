/* rng.cl: Philox4x32-10 (Salmon et al., "Parallel random numbers: as easy as 1, 2, 3", SC11).
 *
 * Counter-based: a random number is addressed, not carried. Every number a path uses is drawn
 * through sampler_uniform4(key, sampler, pixel, sample, dimension) (sampler.cl), which evaluates
 * Philox at a counter made of those, so the image does not depend on the device, the work-group
 * size, the pass split or the execution form. Dimension 0 is the camera sample, 1 + b the
 * scattering at bounce b (1 + b / 2 where one draw serves two bounces: path.cl, scatter_draw),
 * CLPT_DIM_LIGHT + b the light sample (light.cl), and CLPT_DIM_STRATA the jitter sampler's
 * per-16-sample strata shuffle.
 * Written on scalar words (no uint4) so that PoCL can vectorise it across work-items. */
#ifndef CLPT_RNG_CL
#define CLPT_RNG_CL

#include "maths.cl"

#define CLPT_DIM_STRATA 0xffffffffu

typedef struct RngKey {
  uint k0, k1;
  CLPT_ABI_PAD(uint, 3)
} RngKey;

typedef struct Philox4 {
  uint x, y, z, w;
  CLPT_ABI_PAD(uint, 1)
} Philox4;

CLPT_INLINE Philox4 philox4(uint x, uint y, uint z, uint w) {
  Philox4 p;
  p.x = x;
  p.y = y;
  p.z = z;
  p.w = w;
  return p;
}

/* High 32 bits of a 32 x 32-bit product, written as a 64-bit product: PoCL's built-in mul_hi
 * is a software routine on 16-bit halves (four multiplies and as many shifts), while this form
 * compiles to the CPU's widening multiply (vpmuludq). Identical results. */
CLPT_INLINE uint philox_mul_hi(uint a, uint b) { return (uint)(((ulong)a * (ulong)b) >> 32); }

/* One Philox4x32 round. */
CLPT_INLINE Philox4 philox4x32_round(Philox4 c, uint k0, uint k1) {
  const uint hi0 = philox_mul_hi(0xD2511F53u, c.x), lo0 = 0xD2511F53u * c.x;
  const uint hi1 = philox_mul_hi(0xCD9E8D57u, c.z), lo1 = 0xCD9E8D57u * c.z;
  return philox4(hi1 ^ c.y ^ k0, lo1, hi0 ^ c.w ^ k1, lo0);
}

CLPT_INLINE Philox4 philox4x32_10(Philox4 c, uint k0, uint k1) {
#pragma unroll
  for (int round = 0; round < 10; ++round) {
    if (round > 0) {
      k0 += 0x9E3779B9u; /* Weyl key schedule */
      k1 += 0xBB67AE85u;
    }
    c = philox4x32_round(c, k0, k1);
  }
  return c;
}

/* Top 24 bits to [0, 1): every value exactly representable, never 1. */
CLPT_INLINE float rng_to_unit_float(uint bits) { return (float)(bits >> 8) * 0x1.0p-24f; }

typedef struct Uniform4 {
  float u0, u1, u2, u3;
  CLPT_ABI_PAD(float, 1)
} Uniform4;

/* Four independent uniforms in [0, 1) for (pixel, sample, dimension). */
CLPT_INLINE Uniform4 rng_uniform4(RngKey key, uint pixel, uint sample, uint dimension) {
  const Philox4 bits = philox4x32_10(philox4(pixel, sample, dimension, 0u), key.k0, key.k1);
  Uniform4 u;
  u.u0 = rng_to_unit_float(bits.x);
  u.u1 = rng_to_unit_float(bits.y);
  u.u2 = rng_to_unit_float(bits.z);
  u.u3 = rng_to_unit_float(bits.w);
  return u;
}

#endif
