/* texture.cl: texture lookups in plain __global memory (no OpenCL image objects: the same code on
 * PoCL, Oclgrind and every GPU driver) and what a hit's material takes from them.
 *
 * The texturing buffer (types.h, GpuTexturing) holds the texture table, the textured materials,
 * each triangle's texture coordinates and tangents, and the texels: 8-bit, half (vload_half) or
 * float, 1 to 4 channels, rows from the image's top. A lookup at mesh coordinates (u, v) (OBJ's
 * convention, (0, 0) at the image's bottom-left) applies the texture's uv transform, reduces the
 * coordinates by the wrap mode (repeat: mod 1, mirror: mod 2, clamp: to [-1, 2]), reads the texel
 * containing the point (nearest) or the four around it (bilinear, texel centres at i + 0.5),
 * decodes sRGB 8-bit texels per texel before weighting, and expands to RGBA (1 channel: grey,
 * 2: grey and alpha, 3: alpha 1). host/scene/texture.cpp does the same in double
 * (lookup_texture_on_host), which tests/test_textures.cpp compares against.
 *
 * Specialisation (kernel_options.cpp): CLPT_HAS_TEXTURES (a textured material on a mesh),
 * CLPT_TEXEL_STORAGES (bit 1 << CLPT_TEXEL_* of each storage used), CLPT_TEXEL_CHANNELS (bit
 * 1 << (n - 1) of each channel count), CLPT_TEXTURE_WRAPS (bit 1 << CLPT_WRAP_*),
 * CLPT_HAS_NORMAL_MAPS and CLPT_HAS_EMISSION_TEXTURES. A specialised kernel names them only when
 * its scene has textures: absent, they are off there (CLPT_ESTIMATOR fixed) and on in the generic
 * kernel. */
#ifndef CLPT_TEXTURE_CL
#define CLPT_TEXTURE_CL

#include "types.h"
#include "maths.cl"

#ifndef CLPT_HAS_TEXTURES
#ifdef CLPT_ESTIMATOR
#define CLPT_HAS_TEXTURES 0
#else
#define CLPT_HAS_TEXTURES 1
#endif
#endif
#ifndef CLPT_HAS_NORMAL_MAPS
#define CLPT_HAS_NORMAL_MAPS CLPT_HAS_TEXTURES
#endif
#ifndef CLPT_HAS_EMISSION_TEXTURES
#define CLPT_HAS_EMISSION_TEXTURES CLPT_HAS_TEXTURES
#endif
#ifndef CLPT_TEXEL_STORAGES
#define CLPT_TEXEL_STORAGES 7
#endif
#ifndef CLPT_TEXEL_CHANNELS
#define CLPT_TEXEL_CHANNELS 15
#endif
#ifndef CLPT_TEXTURE_WRAPS
#define CLPT_TEXTURE_WRAPS 7
#endif

#if CLPT_HAS_TEXTURES

CLPT_INLINE __global const GpuTexture* texture_at(__global const uchar* texturing, uint index) {
  __global const GpuTexturing* header = (__global const GpuTexturing*)texturing;
  return (__global const GpuTexture*)(texturing + header->textures) + index;
}

/* Linear RGBA, scalars rather than a float4: a vector-typed value in a work-item loop stops PoCL's
 * vectoriser ("instruction return type cannot be vectorized"), and the pad keeps the struct out
 * of registers (maths.cl, CLPT_ABI_PAD). Choices between an integer's values are bit tests
 * (`wrap & 2u`), not comparisons with several constants, which LLVM turns into a switch, which
 * stops the vectoriser too (path.cl, material_eval). */
typedef struct TexelRgba {
  float r, g, b, a;
  CLPT_ABI_PAD(int, 1)
} TexelRgba;

/* The coordinate s (in image widths) reduced to the range its wrap mode reads (CLPT_WRAP_*:
 * repeat 0, clamp 1, mirror 2). */
CLPT_INLINE float texture_reduce(float s, uint wrap) {
  float r = s - floor(s); /* repeat */
#if CLPT_TEXTURE_WRAPS & (1 << CLPT_WRAP_MIRROR)
  r = (wrap & 2u) != 0u ? s - 2.0f * floor(0.5f * s) : r;
#endif
#if CLPT_TEXTURE_WRAPS & (1 << CLPT_WRAP_CLAMP)
  r = (wrap & 1u) != 0u ? clamp(s, -1.0f, 2.0f) : r;
#endif
  (void)wrap;
  return r;
}

/* Texel index i (from a reduced coordinate: in [-1, 2n + 1]) wrapped into [0, n). */
CLPT_INLINE uint texture_wrap_index(int i, int n, uint wrap) {
  int r = i < 0 ? i + n : (i >= n ? i - n : i); /* repeat */
#if CLPT_TEXTURE_WRAPS & (1 << CLPT_WRAP_MIRROR)
  const int m = i < 0 ? i + 2 * n : (i >= 2 * n ? i - 2 * n : i);
  r = (wrap & 2u) != 0u ? (m < n ? m : 2 * n - 1 - m) : r;
#endif
#if CLPT_TEXTURE_WRAPS & (1 << CLPT_WRAP_CLAMP)
  r = (wrap & 1u) != 0u ? i : r; /* clamped below */
#endif
  (void)wrap;
  return (uint)clamp(r, 0, n - 1); /* also guards the buffer against any rounding surprise */
}

/* sRGB's decoding curve (IEC 61966-2-1). */
CLPT_INLINE float srgb_decode(float c) { return c <= 0.04045f ? c * (1.0f / 12.92f) : pow((c + 0.055f) * (1.0f / 1.055f), 2.4f); }

/* Sample `at` of the texels (CLPT_TEXEL_*: 8-bit 0, half 1, float 2). */
CLPT_INLINE float texel_sample(__global const uchar* texels, uint storage, uint at) {
  float v = 0.0f;
#if CLPT_TEXEL_STORAGES & (1 << CLPT_TEXEL_U8)
  v = (float)texels[at] * (1.0f / 255.0f);
#endif
#if CLPT_TEXEL_STORAGES & (1 << CLPT_TEXEL_HALF)
#if CLPT_TEXEL_STORAGES == (1 << CLPT_TEXEL_HALF)
  v = vload_half(at, (__global const half*)texels);
#else
  v = (storage & 1u) != 0u ? vload_half(at, (__global const half*)texels) : v;
#endif
#endif
#if CLPT_TEXEL_STORAGES & (1 << CLPT_TEXEL_FLOAT)
#if CLPT_TEXEL_STORAGES == (1 << CLPT_TEXEL_FLOAT)
  v = ((__global const float*)texels)[at];
#else
  v = (storage & 2u) != 0u ? ((__global const float*)texels)[at] : v;
#endif
#endif
  (void)storage;
  return v;
}

/* The texel (x, y) as linear RGBA. Every read stays inside the texel's own channels (channel k
 * reads min(k, channels - 1)). */
CLPT_INLINE TexelRgba texel_fetch(__global const uchar* texturing, __global const GpuTexture* t, uint x, uint y) {
  __global const uchar* texels = texturing + t->texels;
  const uint channels = t->channels;
  const uint storage = t->storage;
  const uint last = channels - 1u;
  const uint first = (y * t->width + x) * channels;
  const float c0 = texel_sample(texels, storage, first);
#if CLPT_TEXEL_CHANNELS == 1
  const float c1 = c0, c2 = c0, c3 = c0;
#else
  const float c1 = texel_sample(texels, storage, first + min(1u, last));
  const float c2 = texel_sample(texels, storage, first + min(2u, last));
  const float c3 = texel_sample(texels, storage, first + min(3u, last));
#endif
  const bool colour = channels >= 3u;          /* 3, 4: RGB; 1, 2: grey */
  const bool alpha = (channels & 1u) == 0u;    /* 2, 4 */
  TexelRgba rgba;
  rgba.r = c0;
  rgba.g = colour ? c1 : c0;
  rgba.b = colour ? c2 : c0;
  rgba.a = alpha ? (colour ? c3 : c1) : 1.0f;
#if CLPT_TEXEL_STORAGES & (1 << CLPT_TEXEL_U8)
  const bool srgb = (t->flags & CLPT_TEXTURE_SRGB) != 0u;
  rgba.r = srgb ? srgb_decode(rgba.r) : rgba.r;
  rgba.g = srgb ? srgb_decode(rgba.g) : rgba.g;
  rgba.b = srgb ? srgb_decode(rgba.b) : rgba.b;
#endif
  return rgba;
}

/* Texture `index` at mesh coordinates (u, v): linear RGBA. */
CLPT_INLINE TexelRgba texture_lookup(__global const uchar* texturing, uint index, float u, float v) {
  __global const GpuTexture* t = texture_at(texturing, index);
  const float tu = t->transform[0] * u + t->transform[1] * v + t->transform[2];
  const float tv = t->transform[3] * u + t->transform[4] * v + t->transform[5];
  const int w = (int)t->width, h = (int)t->height;
  const float x = texture_reduce(tu, t->wrap_u) * (float)w;
  const float y = (1.0f - texture_reduce(tv, t->wrap_v)) * (float)h;
  const bool nearest = (t->flags & CLPT_TEXTURE_NEAREST) != 0u;
  const float fx = nearest ? x : x - 0.5f, fy = nearest ? y : y - 0.5f;
  const float x0 = floor(fx), y0 = floor(fy);
  const float wx = nearest ? 0.0f : fx - x0, wy = nearest ? 0.0f : fy - y0;
  const int ix = (int)x0, iy = (int)y0;
  const uint ix0 = texture_wrap_index(ix, w, t->wrap_u), ix1 = texture_wrap_index(ix + 1, w, t->wrap_u);
  const uint iy0 = texture_wrap_index(iy, h, t->wrap_v), iy1 = texture_wrap_index(iy + 1, h, t->wrap_v);
  const TexelRgba a = texel_fetch(texturing, t, ix0, iy0), b = texel_fetch(texturing, t, ix1, iy0);
  const TexelRgba c = texel_fetch(texturing, t, ix0, iy1), d = texel_fetch(texturing, t, ix1, iy1);
  const float w00 = (1.0f - wx) * (1.0f - wy), w10 = wx * (1.0f - wy), w01 = (1.0f - wx) * wy, w11 = wx * wy;
  TexelRgba out;
  out.r = w00 * a.r + w10 * b.r + w01 * c.r + w11 * d.r;
  out.g = w00 * a.g + w10 * b.g + w01 * c.g + w11 * d.g;
  out.b = w00 * a.b + w10 * b.b + w01 * c.b + w11 * d.b;
  out.a = w00 * a.a + w10 * b.a + w01 * c.a + w11 * d.a;
  return out;
}

/* Channel `channel` (0 to 3) of an RGBA value, by bit tests. */
CLPT_INLINE float rgba_channel(TexelRgba c, uint channel) {
  const float low = (channel & 1u) != 0u ? c.g : c.r;
  const float high = (channel & 1u) != 0u ? c.a : c.b;
  return (channel & 2u) != 0u ? high : low;
}

/* A triangle's texturing record. */
CLPT_INLINE __global const GpuTriangleTexturing* triangle_texturing(__global const uchar* texturing, uint triangle) {
  __global const GpuTexturing* header = (__global const GpuTexturing*)texturing;
  return (__global const GpuTriangleTexturing*)(texturing + header->triangles) + triangle;
}

CLPT_INLINE __global const GpuMaterialTextures* material_textures(__global const uchar* texturing, uint material) {
  __global const GpuTexturing* header = (__global const GpuTexturing*)texturing;
  return (__global const GpuMaterialTextures*)(texturing + header->materials) + material;
}

/* The texture coordinates at barycentrics (b0, b1, b2) of a triangle: *u, *v. */
CLPT_INLINE void triangle_uv(__global const GpuTriangleTexturing* r, float b0, float b1, float b2, float* u, float* v) {
  *u = b0 * r->uv0[0] + b1 * r->uv1[0] + b2 * r->uv2[0];
  *v = b0 * r->uv0[1] + b1 * r->uv1[1] + b2 * r->uv2[1];
}

#if CLPT_HAS_EMISSION_TEXTURES
/* A triangle's emission factor at barycentrics (b0, b1, b2): its emission texture's RGB, or 1. */
CLPT_INLINE Vec3 triangle_emission_scale(__global const uchar* texturing, uint triangle, real b0, real b1, real b2) {
  __global const GpuTriangleTexturing* r = triangle_texturing(texturing, triangle);
  Vec3 s = v3_splat((real)1);
  if (r->material != CLPT_TEXTURE_NONE) {
    const uint index = material_textures(texturing, r->material)->emission;
    if (index != CLPT_TEXTURE_NONE) {
      float u, v;
      triangle_uv(r, (float)b0, (float)b1, (float)b2, &u, &v);
      const TexelRgba c = texture_lookup(texturing, index, u, v);
      s = v3(fmax(c.r, 0.0f), fmax(c.g, 0.0f), fmax(c.b, 0.0f));
    }
  }
  return s;
}
#endif

#if CLPT_HAS_NORMAL_MAPS
/* The normal map `index` at uv on a triangle with barycentrics (1 - b1 - b2, b1, b2) and unit
 * shading normal n: the triangle's interpolated tangent made orthogonal to n (Gram-Schmidt), the
 * bitangent w n x t (w: the tangent's sign), and the map's value 2 c - 1 in that frame, its x and
 * y times `scale` (glTF normalTexture.scale). n itself where the frame or the result degenerates. */
CLPT_INLINE Vec3 normal_mapped(__global const uchar* texturing, uint triangle, uint index, float scale, float u, float v,
                               real b1, real b2, Vec3 n) {
  __global const GpuTexturing* header = (__global const GpuTexturing*)texturing;
  __global const GpuTriangleTangents* tg = (__global const GpuTriangleTangents*)(texturing + header->tangents) + triangle;
  const real b0 = (real)1 - b1 - b2;
  const Vec3 t0 = v3(tg->t0[0], tg->t0[1], tg->t0[2]), t1 = v3(tg->t1[0], tg->t1[1], tg->t1[2]),
             t2 = v3(tg->t2[0], tg->t2[1], tg->t2[2]);
  const Vec3 interpolated = v3_add(v3_add(v3_scale(t0, b0), v3_scale(t1, b1)), v3_scale(t2, b2));
  const Vec3 along = v3_sub(interpolated, v3_scale(n, v3_dot(n, interpolated)));
  const real length2 = v3_dot(along, along);
  const real sign = b0 * tg->t0[3] + b1 * tg->t1[3] + b2 * tg->t2[3] < (real)0 ? (real)-1 : (real)1;
  const Vec3 t = v3_scale(along, (real)1 / clpt_sqrt(length2 > (real)0 ? length2 : (real)1));
  const Vec3 b = v3_scale(v3(n.y * t.z - n.z * t.y, n.z * t.x - n.x * t.z, n.x * t.y - n.y * t.x), sign);
  const TexelRgba c = texture_lookup(texturing, index, u, v);
  const real x = (real)((2.0f * c.r - 1.0f) * scale), y = (real)((2.0f * c.g - 1.0f) * scale), z = (real)(2.0f * c.b - 1.0f);
  const Vec3 m = v3_add(v3_add(v3_scale(t, x), v3_scale(b, y)), v3_scale(n, z));
  const real m2 = v3_dot(m, m);
  const bool usable = length2 > (real)1e-12f && m2 > (real)1e-12f && is_finite_real(m2);
  return v3_select(usable, v3_scale(m, (real)1 / clpt_sqrt(usable ? m2 : (real)1)), n);
}
#endif

#endif /* CLPT_HAS_TEXTURES */
#endif
