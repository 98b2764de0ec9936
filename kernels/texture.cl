/* texture.cl: texture lookups in plain __global memory (no OpenCL image objects: the same code on
 * PoCL, Oclgrind and every GPU driver) and what a hit's material takes from them.
 *
 * The texturing buffer (types.h, GpuTexturing) holds the texture table, the textured materials,
 * each triangle's texture coordinates and tangents, and the texels: 8-bit, half (decoded from its bits) or
 * float, 1 to 4 channels, rows from the image's top. A lookup at mesh coordinates (u, v) (OBJ's
 * convention, (0, 0) at the image's bottom-left) applies the texture's uv transform, reduces the
 * coordinates by the wrap mode (repeat: mod 1, mirror: mod 2, clamp: to [-1, 2]), reads the texel
 * containing the point (nearest) or the four around it (bilinear, texel centres at i + 0.5),
 * decodes sRGB 8-bit texels per texel before weighting, and expands to RGBA (1 channel: grey,
 * 2: grey and alpha, 3: alpha 1). host/scene/texture.cpp does the same in double
 * (lookup_texture_on_host), which tests/test_textures.cpp compares against.
 *
 * Specialisation (kernel_options.cpp): CLPT_HAS_TEXTURES (a textured material on a mesh or sphere),
 * CLPT_TEXEL_STORAGES (bit 1 << CLPT_TEXEL_* of each storage used), CLPT_TEXEL_CHANNELS (bit
 * 1 << (n - 1) of each channel count), CLPT_TEXTURE_WRAPS (bit 1 << CLPT_WRAP_*),
 * CLPT_HAS_NORMAL_MAPS and CLPT_HAS_EMISSION_TEXTURES; and per material slot the storages its images
 * use, CLPT_BASE_STORAGES (base colour and alpha), CLPT_MR_STORAGES (metallic and roughness),
 * CLPT_NORMAL_STORAGES and CLPT_EMISSION_STORAGES (each a subset of CLPT_TEXEL_STORAGES, or the
 * float storage alone where no image fills the slot): each lookup takes its slot's mask, a
 * constant the compiler folds, so a scene whose base colour is 8-bit and whose normal map is half
 * compiles an 8-bit base colour lookup (with sRGB) and a half normal-map lookup, not every storage
 * in each. A specialised kernel names them only when
 * its scene has textures: absent, they are off there (CLPT_ESTIMATOR fixed) and on in the generic
 * kernel. CLPT_HAS_SPHERE_TEXTURES (a textured material on a sphere: the GpuTexturing.spheres
 * section, read at the spherical mapping's coordinates, sphere_uv) is named only when on, and is
 * on in the generic kernel. */
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
#ifndef CLPT_BASE_STORAGES
#define CLPT_BASE_STORAGES CLPT_TEXEL_STORAGES
#endif
#ifndef CLPT_MR_STORAGES
#define CLPT_MR_STORAGES CLPT_TEXEL_STORAGES
#endif
#ifndef CLPT_NORMAL_STORAGES
#define CLPT_NORMAL_STORAGES CLPT_TEXEL_STORAGES
#endif
#ifndef CLPT_EMISSION_STORAGES
#define CLPT_EMISSION_STORAGES CLPT_TEXEL_STORAGES
#endif
#ifndef CLPT_TEXEL_CHANNELS
#define CLPT_TEXEL_CHANNELS 15
#endif
#ifndef CLPT_TEXTURE_WRAPS
#define CLPT_TEXTURE_WRAPS 7
#endif
#ifndef CLPT_HAS_SPHERE_TEXTURES
#ifdef CLPT_ESTIMATOR
#define CLPT_HAS_SPHERE_TEXTURES 0
#else
#define CLPT_HAS_SPHERE_TEXTURES CLPT_HAS_TEXTURES
#endif
#endif
#if CLPT_HAS_SPHERE_TEXTURES && !CLPT_HAS_TEXTURES
#error "CLPT_HAS_SPHERE_TEXTURES needs the texturing buffer (CLPT_HAS_TEXTURES)"
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

/* sRGB's decoding curve (IEC 61966-2-1) at the 256 8-bit values, in float (rounded from double):
 * a table, not pow per channel and texel (12 pows per bilinear RGB lookup measured as much as the
 * rest of a path's shading on PoCL). */
__constant float kSrgbToLinear[256] = {
    0.000000000e+00f, 3.035269835e-04f, 6.070539671e-04f, 9.105809506e-04f, 1.214107934e-03f, 1.517634918e-03f, 1.821161901e-03f, 2.124688885e-03f,
    2.428215868e-03f, 2.731742852e-03f, 3.035269835e-03f, 3.346535764e-03f, 3.676507324e-03f, 4.024717018e-03f, 4.391442037e-03f, 4.776953481e-03f,
    5.181516702e-03f, 5.605391624e-03f, 6.048833023e-03f, 6.512090793e-03f, 6.995410187e-03f, 7.499032043e-03f, 8.023192985e-03f, 8.568125618e-03f,
    9.134058702e-03f, 9.721217320e-03f, 1.032982303e-02f, 1.096009401e-02f, 1.161224518e-02f, 1.228648836e-02f, 1.298303234e-02f, 1.370208305e-02f,
    1.444384360e-02f, 1.520851442e-02f, 1.599629337e-02f, 1.680737575e-02f, 1.764195449e-02f, 1.850022013e-02f, 1.938236096e-02f, 2.028856306e-02f,
    2.121901038e-02f, 2.217388479e-02f, 2.315336618e-02f, 2.415763245e-02f, 2.518685963e-02f, 2.624122189e-02f, 2.732089164e-02f, 2.842603950e-02f,
    2.955683444e-02f, 3.071344373e-02f, 3.189603307e-02f, 3.310476657e-02f, 3.433980681e-02f, 3.560131488e-02f, 3.688945040e-02f, 3.820437160e-02f,
    3.954623528e-02f, 4.091519691e-02f, 4.231141062e-02f, 4.373502926e-02f, 4.518620439e-02f, 4.666508634e-02f, 4.817182423e-02f, 4.970656598e-02f,
    5.126945837e-02f, 5.286064702e-02f, 5.448027644e-02f, 5.612849005e-02f, 5.780543019e-02f, 5.951123816e-02f, 6.124605423e-02f, 6.301001765e-02f,
    6.480326669e-02f, 6.662593864e-02f, 6.847816984e-02f, 7.036009570e-02f, 7.227185068e-02f, 7.421356838e-02f, 7.618538148e-02f, 7.818742181e-02f,
    8.021982031e-02f, 8.228270713e-02f, 8.437621154e-02f, 8.650046204e-02f, 8.865558629e-02f, 9.084171118e-02f, 9.305896285e-02f, 9.530746663e-02f,
    9.758734714e-02f, 9.989872825e-02f, 1.022417331e-01f, 1.046164841e-01f, 1.070231030e-01f, 1.094617108e-01f, 1.119324278e-01f, 1.144353738e-01f,
    1.169706678e-01f, 1.195384280e-01f, 1.221387722e-01f, 1.247718176e-01f, 1.274376804e-01f, 1.301364767e-01f, 1.328683216e-01f, 1.356333297e-01f,
    1.384316150e-01f, 1.412632911e-01f, 1.441284709e-01f, 1.470272665e-01f, 1.499597898e-01f, 1.529261520e-01f, 1.559264637e-01f, 1.589608351e-01f,
    1.620293756e-01f, 1.651321945e-01f, 1.682694002e-01f, 1.714411007e-01f, 1.746474037e-01f, 1.778884160e-01f, 1.811642442e-01f, 1.844749945e-01f,
    1.878207723e-01f, 1.912016827e-01f, 1.946178304e-01f, 1.980693196e-01f, 2.015562538e-01f, 2.050787364e-01f, 2.086368701e-01f, 2.122307574e-01f,
    2.158605001e-01f, 2.195261997e-01f, 2.232279573e-01f, 2.269658735e-01f, 2.307400485e-01f, 2.345505822e-01f, 2.383975738e-01f, 2.422811225e-01f,
    2.462013267e-01f, 2.501582847e-01f, 2.541520943e-01f, 2.581828529e-01f, 2.622506575e-01f, 2.663556048e-01f, 2.704977910e-01f, 2.746773121e-01f,
    2.788942635e-01f, 2.831487404e-01f, 2.874408377e-01f, 2.917706498e-01f, 2.961382708e-01f, 3.005437944e-01f, 3.049873141e-01f, 3.094689228e-01f,
    3.139887134e-01f, 3.185467781e-01f, 3.231432091e-01f, 3.277780981e-01f, 3.324515363e-01f, 3.371636150e-01f, 3.419144249e-01f, 3.467040564e-01f,
    3.515325995e-01f, 3.564001441e-01f, 3.613067798e-01f, 3.662525956e-01f, 3.712376805e-01f, 3.762621230e-01f, 3.813260114e-01f, 3.864294338e-01f,
    3.915724777e-01f, 3.967552307e-01f, 4.019777798e-01f, 4.072402119e-01f, 4.125426135e-01f, 4.178850708e-01f, 4.232676700e-01f, 4.286904966e-01f,
    4.341536362e-01f, 4.396571738e-01f, 4.452011945e-01f, 4.507857828e-01f, 4.564110232e-01f, 4.620769997e-01f, 4.677837961e-01f, 4.735314961e-01f,
    4.793201831e-01f, 4.851499401e-01f, 4.910208498e-01f, 4.969329951e-01f, 5.028864580e-01f, 5.088813209e-01f, 5.149176654e-01f, 5.209955732e-01f,
    5.271151257e-01f, 5.332764040e-01f, 5.394794890e-01f, 5.457244614e-01f, 5.520114015e-01f, 5.583403896e-01f, 5.647115057e-01f, 5.711248295e-01f,
    5.775804404e-01f, 5.840784179e-01f, 5.906188409e-01f, 5.972017884e-01f, 6.038273389e-01f, 6.104955708e-01f, 6.172065624e-01f, 6.239603917e-01f,
    6.307571363e-01f, 6.375968740e-01f, 6.444796820e-01f, 6.514056374e-01f, 6.583748173e-01f, 6.653872983e-01f, 6.724431570e-01f, 6.795424696e-01f,
    6.866853124e-01f, 6.938717613e-01f, 7.011018919e-01f, 7.083757799e-01f, 7.156935005e-01f, 7.230551289e-01f, 7.304607401e-01f, 7.379104088e-01f,
    7.454042095e-01f, 7.529422168e-01f, 7.605245047e-01f, 7.681511472e-01f, 7.758222183e-01f, 7.835377915e-01f, 7.912979403e-01f, 7.991027380e-01f,
    8.069522577e-01f, 8.148465722e-01f, 8.227857544e-01f, 8.307698768e-01f, 8.387990117e-01f, 8.468732315e-01f, 8.549926081e-01f, 8.631572135e-01f,
    8.713671192e-01f, 8.796223969e-01f, 8.879231179e-01f, 8.962693534e-01f, 9.046611744e-01f, 9.130986518e-01f, 9.215818563e-01f, 9.301108584e-01f,
    9.386857285e-01f, 9.473065367e-01f, 9.559733532e-01f, 9.646862479e-01f, 9.734452904e-01f, 9.822505503e-01f, 9.911020971e-01f, 1.000000000e+00f,
};


/* An IEEE 754 binary16 value from its bits, by integer operations and selects: vload_half is not
 * declared by every OpenCL implementation's headers (libclc for nvptx64 lacks it), and this form
 * vectorises on PoCL. Subnormals are mant x 2^-24; exponent 31 is infinity or NaN. */
CLPT_INLINE float half_bits_to_float(uint h) {
  const uint sign = (h & 0x8000u) << 16;
  const uint exponent = (h >> 10) & 0x1fu;
  const uint mantissa = h & 0x3ffu;
  const uint subnormal = as_uint((float)mantissa * 5.9604644775390625e-8f) | sign;
  const uint normal = sign | ((exponent + 112u) << 23) | (mantissa << 13);
  const uint special = sign | 0x7f800000u | (mantissa << 13);
  return as_float(exponent == 0u ? subnormal : (exponent == 31u ? special : normal));
}

/* Sample `at` of the texels (CLPT_TEXEL_*: 8-bit 0, half 1, float 2). `storages`: the storages the
 * lookup can meet (a compile-time constant: its slot's mask). A lookup of one storage reads it
 * typed. One of several reads the aligned 32-bit word holding the
 * sample (byte offset at << storage: the storage's value is log2 of its size) and takes the
 * sample's bits out of it: one read per sample rather than one per storage, which in a bilinear
 * RGBA lookup is 16 gathers rather than 48, and a third of the code, PoCL's cold compile of the
 * widest texture kernels included (docs/textures.md, "Cost"). The host starts every image's texels
 * on a 16-byte boundary and pads them to one (device_textures.cpp), so the word lies in the
 * image's own bytes; texels are little-endian, as on every OpenCL device clpt runs on. */
CLPT_INLINE float texel_sample(__global const uchar* texels, uint storage, uint at, const uint storages) {
  if (storages == (1u << CLPT_TEXEL_U8)) return (float)texels[at] * (1.0f / 255.0f);
  if (storages == (1u << CLPT_TEXEL_HALF)) return half_bits_to_float(((__global const ushort*)texels)[at]);
  if (storages == (1u << CLPT_TEXEL_FLOAT)) return ((__global const float*)texels)[at];
  const uint byte = at << storage;
  const uint word = ((__global const uint*)texels)[byte >> 2];
  const uint bits = word >> ((byte & 3u) * 8u);
  float v = (float)(bits & 0xffu) * (1.0f / 255.0f);
  if ((storages & (1u << CLPT_TEXEL_HALF)) != 0u) v = (storage & 1u) != 0u ? half_bits_to_float(bits & 0xffffu) : v;
  if ((storages & (1u << CLPT_TEXEL_FLOAT)) != 0u) v = (storage & 2u) != 0u ? as_float(word) : v;
  return v;
}

/* The texel (x, y) as linear RGBA. Every read stays inside the texel's own channels (channel k
 * reads min(k, channels - 1)). */
CLPT_INLINE TexelRgba texel_fetch(__global const uchar* texturing, __global const GpuTexture* t, uint x, uint y,
                                  const uint storages) {
  __global const uchar* texels = texturing + t->texels;
  const uint channels = t->channels;
  const uint storage = t->storage;
  const uint last = channels - 1u;
  const uint first = (y * t->width + x) * channels;
  const float c0 = texel_sample(texels, storage, first, storages);
#if CLPT_TEXEL_CHANNELS == 1
  const float c1 = c0, c2 = c0, c3 = c0;
#else
  const float c1 = texel_sample(texels, storage, first + min(1u, last), storages);
  const float c2 = texel_sample(texels, storage, first + min(2u, last), storages);
  const float c3 = texel_sample(texels, storage, first + min(3u, last), storages);
#endif
  const bool colour = channels >= 3u;          /* 3, 4: RGB; 1, 2: grey */
  const bool alpha = (channels & 1u) == 0u;    /* 2, 4 */
  TexelRgba rgba;
  rgba.r = c0;
  rgba.g = colour ? c1 : c0;
  rgba.b = colour ? c2 : c0;
  rgba.a = alpha ? (colour ? c3 : c1) : 1.0f;
  if ((storages & (1u << CLPT_TEXEL_U8)) != 0u) {
    /* An sRGB texel is 8-bit: its value v / 255 indexes the table (the rounding recovers v). */
    const bool srgb = (t->flags & CLPT_TEXTURE_SRGB) != 0u;
    rgba.r = srgb ? kSrgbToLinear[(uint)(rgba.r * 255.0f + 0.5f) & 255u] : rgba.r;
    rgba.g = srgb ? kSrgbToLinear[(uint)(rgba.g * 255.0f + 0.5f) & 255u] : rgba.g;
    rgba.b = srgb ? kSrgbToLinear[(uint)(rgba.b * 255.0f + 0.5f) & 255u] : rgba.b;
  }
  return rgba;
}

/* The four texels a lookup reads and their bilinear weights (nearest: weight 1 on (ix0, iy0)). */
typedef struct TexelFootprint {
  uint ix0, ix1, iy0, iy1;
  float w00, w10, w01, w11;
  CLPT_ABI_PAD(int, 1)
} TexelFootprint;

/* Where texture t is read at mesh coordinates (u, v): its uv transform, the wrap modes, the filter. */
CLPT_INLINE TexelFootprint texture_footprint(__global const GpuTexture* t, float u, float v) {
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
  TexelFootprint f;
  f.ix0 = texture_wrap_index(ix, w, t->wrap_u);
  f.ix1 = texture_wrap_index(ix + 1, w, t->wrap_u);
  f.iy0 = texture_wrap_index(iy, h, t->wrap_v);
  f.iy1 = texture_wrap_index(iy + 1, h, t->wrap_v);
  f.w00 = (1.0f - wx) * (1.0f - wy);
  f.w10 = wx * (1.0f - wy);
  f.w01 = (1.0f - wx) * wy;
  f.w11 = wx * wy;
  return f;
}

/* Texture `index` at mesh coordinates (u, v): linear RGBA. `storages`: the slot's mask (above). */
CLPT_INLINE TexelRgba texture_lookup(__global const uchar* texturing, uint index, float u, float v, const uint storages) {
  __global const GpuTexture* t = texture_at(texturing, index);
  const TexelFootprint f = texture_footprint(t, u, v);
  const uint ix0 = f.ix0, ix1 = f.ix1, iy0 = f.iy0, iy1 = f.iy1;
  const TexelRgba a = texel_fetch(texturing, t, ix0, iy0, storages), b = texel_fetch(texturing, t, ix1, iy0, storages);
  const TexelRgba c = texel_fetch(texturing, t, ix0, iy1, storages), d = texel_fetch(texturing, t, ix1, iy1, storages);
  const float w00 = f.w00, w10 = f.w10, w01 = f.w01, w11 = f.w11;
  TexelRgba out;
  out.r = w00 * a.r + w10 * b.r + w01 * c.r + w11 * d.r;
  out.g = w00 * a.g + w10 * b.g + w01 * c.g + w11 * d.g;
  out.b = w00 * a.b + w10 * b.b + w01 * c.b + w11 * d.b;
  out.a = w00 * a.a + w10 * b.a + w01 * c.a + w11 * d.a;
  return out;
}

/* Channel `channel` (0 to 3) of texel (x, y) as linear RGBA: rgba_channel(texel_fetch(...),
 * channel), reading one sample rather than four (a scalar parameter's lookup). */
CLPT_INLINE float texel_channel(__global const uchar* texturing, __global const GpuTexture* t, uint x, uint y,
                                uint channel, const uint storages) {
  const uint channels = t->channels;
  const bool colour = channels >= 3u;       /* 3, 4: RGB; 1, 2: grey */
  const bool alpha = (channels & 1u) == 0u; /* 2, 4 */
  const bool wants_alpha = channel == 3u;
  /* RGB's channel k is sample k, grey's sample 0; alpha is the last sample, or 1 without one. */
  const uint sample = colour ? channel : (wants_alpha ? 1u : 0u);
  const float c =
      texel_sample(texturing + t->texels, t->storage, (y * t->width + x) * channels + min(sample, channels - 1u), storages);
  float decoded = c;
  if ((storages & (1u << CLPT_TEXEL_U8)) != 0u) {
    const bool srgb = (t->flags & CLPT_TEXTURE_SRGB) != 0u && !wants_alpha;
    decoded = srgb ? kSrgbToLinear[(uint)(c * 255.0f + 0.5f) & 255u] : c;
  }
  return wants_alpha ? (alpha ? c : 1.0f) : decoded;
}

/* Channel `channel` (0 to 3) of texture `index`'s linear RGBA at mesh coordinates (u, v):
 * rgba_channel(texture_lookup(...), channel), reading one sample of each of the four texels (the
 * metallic and roughness lookups: a quarter of the reads and table lookups, and of the code PoCL
 * compiles for them, docs/performance.md "Fixed costs"). */
CLPT_INLINE float texture_lookup_channel(__global const uchar* texturing, uint index, uint channel, float u, float v,
                                         const uint storages) {
  __global const GpuTexture* t = texture_at(texturing, index);
  const TexelFootprint f = texture_footprint(t, u, v);
  const float a = texel_channel(texturing, t, f.ix0, f.iy0, channel, storages),
              b = texel_channel(texturing, t, f.ix1, f.iy0, channel, storages);
  const float c = texel_channel(texturing, t, f.ix0, f.iy1, channel, storages),
              d = texel_channel(texturing, t, f.ix1, f.iy1, channel, storages);
  return f.w00 * a + f.w10 * b + f.w01 * c + f.w11 * d;
}

/* The alpha of texel (x, y): its last channel for 2 or 4 channels, else 1 (texel_fetch's .a,
 * without reading the colour channels). */
CLPT_INLINE float texel_alpha(__global const uchar* texturing, __global const GpuTexture* t, uint x, uint y,
                              const uint storages) {
  const uint channels = t->channels;
  if ((channels & 1u) != 0u) return 1.0f;
  return texel_sample(texturing + t->texels, t->storage, (y * t->width + x) * channels + channels - 1u, storages);
}

/* Texture `index`'s alpha at mesh coordinates (u, v): texture_lookup's .a, reading one channel
 * of the four texels (alpha.cl's test runs inside the ray queries, for every candidate hit). */
CLPT_INLINE float texture_lookup_alpha(__global const uchar* texturing, uint index, float u, float v,
                                       const uint storages) {
  __global const GpuTexture* t = texture_at(texturing, index);
  const TexelFootprint f = texture_footprint(t, u, v);
  return f.w00 * texel_alpha(texturing, t, f.ix0, f.iy0, storages) + f.w10 * texel_alpha(texturing, t, f.ix1, f.iy0, storages) +
         f.w01 * texel_alpha(texturing, t, f.ix0, f.iy1, storages) + f.w11 * texel_alpha(texturing, t, f.ix1, f.iy1, storages);
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

/* A triangle's textured-material index (into the GpuMaterialTextures section), or
 * CLPT_TEXTURE_NONE: for an untextured triangle, for no triangle (triangle < 0), and for every
 * triangle when the buffer holds no texturing at all (the zeroed header of a scene without
 * textures: its triangles section is at offset 0, which a packed buffer never uses). Only the
 * generic kernel meets that header; reading a record from it would run past its 32 bytes. */
CLPT_INLINE uint triangle_texture_material(__global const uchar* texturing, int triangle) {
  __global const GpuTexturing* header = (__global const GpuTexturing*)texturing;
  if (triangle < 0 || header->triangles == 0u) return CLPT_TEXTURE_NONE;
  return triangle_texturing(texturing, (uint)triangle)->material;
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
  const uint material = triangle_texture_material(texturing, (int)triangle);
  Vec3 s = v3_splat((real)1);
  if (material != CLPT_TEXTURE_NONE) {
    const uint index = material_textures(texturing, material)->emission;
    if (index != CLPT_TEXTURE_NONE) {
      __global const GpuTriangleTexturing* r = triangle_texturing(texturing, triangle);
      float u, v;
      triangle_uv(r, (float)b0, (float)b1, (float)b2, &u, &v);
      const TexelRgba c = texture_lookup(texturing, index, u, v, CLPT_EMISSION_STORAGES);
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
  const TexelRgba c = texture_lookup(texturing, index, u, v, CLPT_NORMAL_STORAGES);
  const real x = (real)((2.0f * c.r - 1.0f) * scale), y = (real)((2.0f * c.g - 1.0f) * scale), z = (real)(2.0f * c.b - 1.0f);
  const Vec3 m = v3_add(v3_add(v3_scale(t, x), v3_scale(b, y)), v3_scale(n, z));
  const real m2 = v3_dot(m, m);
  const bool usable = length2 > (real)1e-12f && m2 > (real)1e-12f && is_finite_real(m2);
  return v3_select(usable, v3_scale(m, (real)1 / clpt_sqrt(usable ? m2 : (real)1)), n);
}
#endif

#if CLPT_HAS_SPHERE_TEXTURES
/* A sphere's textured-material index (GpuTexturing.spheres, in the sphere buffer's order), or
 * CLPT_TEXTURE_NONE: for an untextured sphere, for no sphere (sphere < 0), and for every sphere
 * when the buffer has no sphere section (offset 0: no sphere is textured, or no texturing at all). */
CLPT_INLINE uint sphere_texture_material(__global const uchar* texturing, int sphere) {
  __global const GpuTexturing* header = (__global const GpuTexturing*)texturing;
  if (sphere < 0 || header->spheres == 0u) return CLPT_TEXTURE_NONE;
  return ((__global const uint*)(texturing + header->spheres))[sphere];
}

/* The spherical mapping (docs/textures.md) at the unit outward normal n = (p - c) / r, in the
 * sphere's own frame (+Y up): u = 1/2 - atan2(n.x, -n.z) / (2 pi), v = 1 - acos(n.y) / pi, Blender's
 * sphere projection (Cycles' map_to_sphere) with Blender's +Z up as +Y and its +Y as -Z (what its
 * glTF exchange maps): the image's centre faces -Z, its left and right edges meet at +Z, its top row
 * is the north pole (+Y), and it reads unmirrored from outside. host/scene/texture.cpp,
 * sphere_texture_coordinates, is the same in double. */
CLPT_INLINE void sphere_uv(Vec3 n, float* u, float* v) {
  const float x = (float)n.x, y = (float)n.y, z = (float)n.z;
  *u = 0.5f - atan2(x, -z) * (0.5f * M_1_PI_F);
  *v = 1.0f - acos(clamp(y, -1.0f, 1.0f)) * M_1_PI_F;
}

#if CLPT_HAS_EMISSION_TEXTURES
/* A sphere's emission factor at the point with outward normal n: its emission texture's RGB, or 1
 * (light.cl: a sampled point of a sphere light, as path.cl scales a BSDF hit's emission). */
CLPT_INLINE Vec3 sphere_emission_scale(__global const uchar* texturing, int sphere, Vec3 n) {
  const uint material = sphere_texture_material(texturing, sphere);
  Vec3 s = v3_splat((real)1);
  if (material != CLPT_TEXTURE_NONE) {
    const uint index = material_textures(texturing, material)->emission;
    if (index != CLPT_TEXTURE_NONE) {
      float u, v;
      sphere_uv(n, &u, &v);
      const TexelRgba c = texture_lookup(texturing, index, u, v, CLPT_EMISSION_STORAGES);
      s = v3(fmax(c.r, 0.0f), fmax(c.g, 0.0f), fmax(c.b, 0.0f));
    }
  }
  return s;
}
#endif
#endif /* CLPT_HAS_SPHERE_TEXTURES */

#endif /* CLPT_HAS_TEXTURES */
#endif
