/* sampler.cl: where every random number a path uses comes from, chosen by GpuRenderParams.sampler.
 *
 * sampler_uniform4(key, sampler, pixel, sample, dimension) is the one entry point: the camera's
 * sub-pixel position (dimension 0, camera.cl), the scattering at bounce b (1 + b) and the light
 * sample at bounce b (CLPT_DIM_LIGHT + b, light.cl) all call it. Like the Philox draws it
 * replaces, its value depends on (key, pixel, sample, dimension) and nothing else, so images do
 * not depend on the device, the pass split, the launch size or the execution form.
 *
 *  - jitter and grid: four independent Philox uniforms (rng.cl). The grid sampler differs only in
 *    the camera's sub-pixel position (camera.cl).
 *  - sobol and sobol-grid: padded, shuffled, Owen-scrambled Sobol points (sobol-grid differs only
 *    in the camera's sub-pixel position, camera.cl). Each dimension is two 2D pairs, (u0,u1)
 *    and (u2,u3); each pair is the base-2 (0,2)-sequence formed by the first two Sobol dimensions
 *    (the van der Corput radical inverse, and the dimension whose generator matrix is Pascal's
 *    triangle mod 2), read in an order shuffled per (key, pixel, dimension, pair) and then
 *    Owen-scrambled per coordinate with seeds of the same address. The shuffle only changes which
 *    aligned power-of-two block of the sequence the first 2^k samples come from, so every prefix
 *    of 2^k samples of one pair is still a (0,k,2)-net after scrambling (one point in each
 *    elementary interval of area 2^-k); the independent shuffles decorrelate the pairs.
 *
 * Everything is scalar 32-bit integer arithmetic without branches or loops (the sampler is chosen
 * by selects), so that PoCL keeps vectorising the stages across work-items (maths.cl). */
#ifndef CLPT_SAMPLER_CL
#define CLPT_SAMPLER_CL

#include "types.h"
#include "maths.cl"
#include "rng.cl"

/* The sampler in use: GpuRenderParams.sampler, or CLPT_SAMPLER where the host fixes it (every
 * scene-specialised kernel, kernel_options.cpp). Fixed, the other samplers' arithmetic folds
 * away: the selects below keep only one side, and the grid's camera sample needs no draw. */
#ifdef CLPT_SAMPLER
#define CLPT_SAMPLER_IN_USE(sampler) ((void)(sampler), CLPT_SAMPLER)
#else
#define CLPT_SAMPLER_IN_USE(sampler) (sampler)
#endif

/* Reverses the 32 bits of x (OpenCL C 1.2 has no built-in for it): swaps of bits, pairs,
 * nibbles and bytes reverse each 16-bit half, and a rotation by 16 swaps the halves. The last
 * step is the rotate() built-in, not shifts: written with shifts, clang recognises the whole
 * as llvm.bitreverse, an intrinsic Oclgrind cannot run ("Undefined external function"). */
CLPT_INLINE uint sobol_reverse_bits(uint x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
  x = ((x >> 8) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8);
  return rotate(x, 16u);
}

/* A random bijection of 32-bit words, chosen by seed, in which output bit j is input bit j XOR a
 * function of the input bits below j (and of the seed): a nested uniform scramble in which bit 0
 * is the first digit. Each step has that form: adding a word carries only upwards, and
 * x ^= x * m with m even flips bit j by the product's bit j, which depends only on bits below j.
 * The fixed multipliers are the first 32 fraction bits of sqrt(2), sqrt(5), sqrt(7) (made even);
 * the seed enters through the additions and one multiplier, so that different seeds give
 * unrelated scrambles. */
CLPT_INLINE uint sobol_scramble_low_first(uint x, uint seed) {
  x += seed;
  x ^= x * 0x6a09e666u;
  x ^= x * (seed << 1);
  x += seed ^ 0x3c6ef372u;
  x ^= x * 0x3c6ef372u;
  x ^= x * 0xa54ff53au;
  return x;
}

/* Second Sobol dimension of index i, bit-reversed (bit r is the digit of weight 2^-(r+1)). Its
 * generator matrix is Pascal's triangle mod 2: digit r is the parity of the index bits c with
 * binom(c, r) odd, which by Lucas' theorem are the c whose binary digits contain r's. That sum
 * over supersets is taken one index bit at a time, five shift-and-xor steps for 32 digits. */
CLPT_INLINE uint sobol_pascal_reversed(uint i) {
  i ^= (i >> 1) & 0x55555555u;
  i ^= (i >> 2) & 0x33333333u;
  i ^= (i >> 4) & 0x0F0F0F0Fu;
  i ^= (i >> 8) & 0x00FF00FFu;
  i ^= (i >> 16) & 0x0000FFFFu;
  return i;
}

typedef struct SobolPoint {
  uint x, y; /* 32-bit fractions: value / 2^32 in [0, 1) */
  CLPT_ABI_PAD(uint, 3)
} SobolPoint;

/* Point of the 2D (0,2)-sequence for sample `sample`, given sample's bit reversal (shared by the
 * pairs of one draw), read in the order chosen by shuffle_seed and scrambled by seed_x, seed_y.
 * The shuffle is a nested uniform scramble of the index with its top bit as first digit: for
 * samples 0 .. 2^k - 1 it fixes the bits above k to a constant and permutes the low k bits, so
 * those samples are one aligned block of 2^k sequence points, which is a (0,k,2)-net. */
CLPT_INLINE SobolPoint sobol_point(uint sample_reversed, uint shuffle_seed, uint seed_x, uint seed_y) {
  const uint index = sobol_reverse_bits(sobol_scramble_low_first(sample_reversed, shuffle_seed));
  SobolPoint p;
  /* Owen scrambling of a fraction (its top bit the first digit) is reverse, scramble low bits
   * first, reverse. The radical inverse of index is reverse(index), so for x the first two
   * reversals cancel; y's digits come out of sobol_pascal_reversed already reversed. */
  p.x = sobol_reverse_bits(sobol_scramble_low_first(index, seed_x));
  p.y = sobol_reverse_bits(sobol_scramble_low_first(sobol_pascal_reversed(index), seed_y));
  return p;
}

/* The draw for (pixel, sample, dimension) from the chosen sampler: four uniforms in [0, 1), each
 * with 24 random bits. One Philox evaluation serves both samplers: jitter's is addressed by
 * (pixel, sample, dimension, 0), the same numbers as before the Sobol sampler existed; Sobol's
 * seeds by (pixel, stream, dimension, 1), which no jitter draw uses. The stream is the sample
 * index's top bit (CLPT_SAMPLE_STREAM_BIT): the host puts the passes of its second half-film
 * there (render/pass_schedule.h), and the Sobol points of stream 1 are an independent
 * randomisation (own shuffles and scrambles) of the same sequence, read from its start, so the
 * two half-films are independent estimates whose difference measures the error honestly
 * (render/error_estimate.h). Sobol's second pair takes its
 * shuffle seed from the fourth word, independent of the first pair's seeds, and its scramble
 * seeds from the first pair's mixed with that word through bijections, so each is uniform
 * (they are not independent of the first pair's, but the independent shuffle already
 * decorrelates the two pairs). */
CLPT_INLINE Uniform4 sampler_uniform4(RngKey key, uint sampler, uint pixel, uint sample, uint dimension) {
  const uint in_use = CLPT_SAMPLER_IN_USE(sampler);
  const bool sobol = in_use == CLPT_SAMPLER_SOBOL || in_use == CLPT_SAMPLER_SOBOL_GRID;
  const Philox4 bits = philox4x32_10(
      philox4(pixel, sobol ? sample >> CLPT_SAMPLE_STREAM_BIT : sample, dimension, sobol ? 1u : 0u), key.k0, key.k1);
  const uint reversed = sobol_reverse_bits(sample & ((1u << CLPT_SAMPLE_STREAM_BIT) - 1u));
  const SobolPoint a = sobol_point(reversed, bits.x, bits.y, bits.z);
  const SobolPoint b = sobol_point(reversed, bits.w, (bits.y ^ bits.w) * 0x9E3779B9u,
                                   bits.z + bits.w * 0xBB67AE85u);
  Uniform4 u;
  u.u0 = rng_to_unit_float(sobol ? a.x : bits.x);
  u.u1 = rng_to_unit_float(sobol ? a.y : bits.y);
  u.u2 = rng_to_unit_float(sobol ? b.x : bits.z);
  u.u3 = rng_to_unit_float(sobol ? b.y : bits.w);
  return u;
}

#endif
