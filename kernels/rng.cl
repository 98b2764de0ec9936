/* rng.cl: Philox4x32-10 (Salmon et al., "Parallel random numbers: as easy as 1, 2, 3", SC11).
 *
 * Counter-based: a random number is addressed, not carried. Every number a path uses is
 * rng_uniform4(key, pixel, sample, dimension), so the image does not depend on the device, the
 * work-group size, the pass split or the execution form. Dimension 0 is the camera sample,
 * 1 + b the scattering at bounce b, and CLPT_DIM_STRATA the per-16-sample strata shuffle. */
#ifndef CLPT_RNG_CL
#define CLPT_RNG_CL

#include "maths.cl"

#define CLPT_DIM_STRATA 0xffffffffu

typedef struct RngKey {
  uint k0, k1;
} RngKey;

CLPT_INLINE uint philox_mulhilo(uint a, uint b, uint* hi) {
  *hi = mul_hi(a, b);
  return a * b;
}

/* One Philox4x32 round; the 10-round function below is the standard Philox4x32-10. */
CLPT_INLINE uint4 philox4x32_round(uint4 ctr, uint k0, uint k1) {
  uint hi0, hi1;
  const uint lo0 = philox_mulhilo(0xD2511F53u, ctr.x, &hi0);
  const uint lo1 = philox_mulhilo(0xCD9E8D57u, ctr.z, &hi1);
  return (uint4)(hi1 ^ ctr.y ^ k0, lo1, hi0 ^ ctr.w ^ k1, lo0);
}

CLPT_INLINE uint4 philox4x32_10(uint4 ctr, uint k0, uint k1) {
#pragma unroll
  for (int round = 0; round < 10; ++round) {
    if (round > 0) {
      k0 += 0x9E3779B9u; /* Weyl key schedule */
      k1 += 0xBB67AE85u;
    }
    ctr = philox4x32_round(ctr, k0, k1);
  }
  return ctr;
}

/* Top 24 bits to [0, 1): every value exactly representable, never 1. */
CLPT_INLINE float rng_to_unit_float(uint bits) { return (float)(bits >> 8) * 0x1.0p-24f; }

/* Four independent uniforms in [0, 1) for (pixel, sample, dimension). */
CLPT_INLINE float4 rng_uniform4(RngKey key, uint pixel, uint sample, uint dimension) {
  const uint4 bits = philox4x32_10((uint4)(pixel, sample, dimension, 0u), key.k0, key.k1);
  return (float4)(rng_to_unit_float(bits.x), rng_to_unit_float(bits.y),
                  rng_to_unit_float(bits.z), rng_to_unit_float(bits.w));
}

#endif
