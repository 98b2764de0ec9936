/* probe_texture.cl: texture lookups (kernels/texture.cl) on inputs from the host, for
 * tests/test_textures.cpp to compare with the host's lookups in double. Built without
 * CLPT_ESTIMATOR, so every storage, channel count and wrap mode is compiled in. */
#include "types.h"
#include "maths.cl"
#include "texture.cl"

/* out[i] = the RGBA lookup of texture (uint)in[i].z at mesh coordinates (in[i].x, in[i].y). */
__kernel void probe_texture(__global const uchar* texturing, __global const float4* in, __global float4* out) {
  const size_t i = get_global_id(0);
  const float4 q = in[i];
  const TexelRgba c = texture_lookup(texturing, (uint)q.z, q.x, q.y, CLPT_TEXEL_STORAGES);
  out[i] = (float4)(c.r, c.g, c.b, c.a);
}

/* out[i] = channels 0 to 3 of the same lookup, each by texture_lookup_channel (the scalar
 * parameters' one-sample lookups), which must equal probe_texture's. */
__kernel void probe_texture_channels(__global const uchar* texturing, __global const float4* in, __global float4* out) {
  const size_t i = get_global_id(0);
  const float4 q = in[i];
  const uint t = (uint)q.z;
  out[i] = (float4)(texture_lookup_channel(texturing, t, 0u, q.x, q.y, CLPT_TEXEL_STORAGES),
                    texture_lookup_channel(texturing, t, 1u, q.x, q.y, CLPT_TEXEL_STORAGES),
                    texture_lookup_channel(texturing, t, 2u, q.x, q.y, CLPT_TEXEL_STORAGES),
                    texture_lookup_channel(texturing, t, 3u, q.x, q.y, CLPT_TEXEL_STORAGES));
}
