/* alpha.cl: glTF alphaMode MASK and BLEND as coverage: whether a ray's candidate triangle hit is
 * there at all, decided inside the queries (bvh.cl, triangle_loop.cl) so that every ray, camera,
 * BSDF-sampled and shadow alike, passes through the absent parts and goes on straight, with no
 * bounce counted.
 *
 * A triangle's alpha is its material's `alpha` (glTF baseColorFactor[3]) times the base colour
 * texture's alpha at the hit (1 for a texture without an alpha channel; texture.cl's lookup) times
 * the vertex colours' alpha there (glTF COLOR_0; vertex_colors.cl).
 * MASK: the surface is there where alpha >= alpha_cutoff. BLEND: it is there with probability
 * alpha (Cycles' "alpha hashed": no sorting, no refraction), decided by a hash of the ray's seed
 * and the triangle's index: the seed is a hash of the render's seed, the pixel, the sample, the
 * bounce and whether the ray is the segment's or its shadow ray (alpha_ray_seed), so an image is
 * the same on every device, pass split and work-group size. A shadow ray through BLEND surfaces
 * of alphas a_i is then unblocked with probability prod (1 - a_i): its light's expectation is
 * the transmittance's, and BSDF sampling meets the same surfaces with the same probabilities, so
 * MIS stays unbiased. OPAQUE materials (and every triangle without a texturing record) are
 * always there.
 *
 * Specialisation (kernel_options.cpp): CLPT_HAS_ALPHA, named only when a mesh's material is MASK
 * or BLEND (absent: off in a specialised kernel, on in the generic one); it needs the texturing
 * buffer, which such a scene has (CLPT_HAS_TEXTURES). Without it the queries compile none of
 * this. */
#ifndef CLPT_ALPHA_CL
#define CLPT_ALPHA_CL

#include "types.h"
#include "maths.cl"
#include "texture.cl"
#include "vertex_colors.cl"
#include "triangle.cl"

#ifndef CLPT_HAS_ALPHA
#ifdef CLPT_ESTIMATOR
#define CLPT_HAS_ALPHA 0
#else
#define CLPT_HAS_ALPHA 1
#endif
#endif
#if CLPT_HAS_ALPHA && !CLPT_HAS_TEXTURES
#error "CLPT_HAS_ALPHA needs the texturing buffer (CLPT_HAS_TEXTURES)"
#endif

/* Streams of alpha_ray_seed: a segment's closest-hit ray and its vertex's shadow ray. */
#define CLPT_ALPHA_STREAM_HIT 0u
#define CLPT_ALPHA_STREAM_SHADOW 1u

#if CLPT_HAS_ALPHA
/* A 32-bit integer hash with good avalanche (Wellons' "lowbias32"). */
CLPT_INLINE uint alpha_hash(uint x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

/* The seed of one ray's coverage decisions. */
CLPT_INLINE uint alpha_ray_seed(uint key_lo, uint key_hi, uint pixel, uint sample, uint bounce, uint stream) {
  uint h = alpha_hash(key_lo ^ 0x9e3779b9u);
  h = alpha_hash(h ^ key_hi);
  h = alpha_hash(h ^ pixel);
  h = alpha_hash(h ^ sample);
  return alpha_hash(h ^ (bounce * 2u + stream));
}

/* Whether the ray of seed `seed` passes through triangle `triangle` at the candidate hit of edge
 * functions r (triangle.cl, TriangleTest): the surface is absent there. */
CLPT_INLINE bool alpha_cut(__global const uchar* texturing, uint triangle, TriangleTest r, uint seed) {
  const uint material = triangle_texture_material(texturing, (int)triangle);
  if (material == CLPT_TEXTURE_NONE) return false;
  __global const GpuMaterialTextures* mt = material_textures(texturing, material);
  const uint mode = mt->alpha_mode;
  if (mode == CLPT_ALPHA_OPAQUE) return false;
  float alpha = mt->alpha;
  const uint base = mt->base_color;
  if (base != CLPT_TEXTURE_NONE) {
    const real inv = r.det != (real)0 ? (real)1 / r.det : (real)0;
    float u, v;
    triangle_uv(triangle_texturing(texturing, triangle), (float)(r.u * inv), (float)(r.v * inv), (float)(r.w * inv), &u, &v);
    alpha *= clamp(texture_lookup_alpha(texturing, base, u, v, CLPT_BASE_STORAGES), 0.0f, 1.0f);
  }
#if CLPT_HAS_VERTEX_COLORS
  {
    const real inv = r.det != (real)0 ? (real)1 / r.det : (real)0;
    alpha *= triangle_vertex_color(texturing, triangle, (float)(r.u * inv), (float)(r.v * inv), (float)(r.w * inv)).a;
  }
#endif
  /* MASK: absent below the cutoff. BLEND: absent when a uniform number in (0, 1] exceeds alpha. */
  const float blend_threshold = (float)((alpha_hash(seed ^ alpha_hash(triangle)) >> 8) + 1u) * (1.0f / 16777216.0f);
  return alpha < (mode == CLPT_ALPHA_MASK ? mt->alpha_cutoff : blend_threshold);
}
#endif

#endif
