/* probe_stages.cl: thin kernels that call the renderer's own stage functions on inputs from the
 * host, so unit tests check the device code itself (not a host copy of it). */
#include "types.h"
#include "maths.cl"
#include "rng.cl"
#include "camera.cl"
#include "intersect.cl"
#include "bsdf.cl"

/* Philox4x32-10 of (counter[i], key): 4 words per counter. */
__kernel void probe_philox(__global const uint4* counters, uint k0, uint k1, __global uint4* out) {
  const size_t i = get_global_id(0);
  out[i] = philox4x32_10(counters[i], k0, k1);
}

/* Closest hit of ray i (origin with the sphere to skip in .w, unit direction) against spheres. */
__kernel void probe_intersect(__global const GpuSphere* spheres, uint count,
                              __global const float4* rays, float t_min, __global float2* out) {
  const size_t i = get_global_id(0);
  const float3 o = rays[2 * i].xyz;
  const float3 d = rays[2 * i + 1].xyz;
  const Hit hit = scene_intersect(spheres, count, o, d, t_min, (int)rays[2 * i].w);
  out[i] = (float2)(hit.t, (float)hit.sphere);
}

/* Camera direction for pixel (col,row) with a given sub-pixel offset. */
__kernel void probe_camera(const GpuRenderParams params, __global const float4* requests,
                           __global float4* out) {
  const size_t i = get_global_id(0);
  const float4 r = requests[i]; /* col, row, subpixel x, subpixel y */
  const float3 d = camera_ray_direction(&params.camera, params.width, params.height, (uint)r.x,
                                        (uint)r.y, r.zw);
  out[i] = (float4)(d, 0.0f);
}

/* Fresnel reflectance for (eta, cos_i) pairs; cos_t from Snell, -1 marks total internal reflection. */
__kernel void probe_fresnel(__global const float2* in, __global float* out) {
  const size_t i = get_global_id(0);
  const float eta = in[i].x, cos_i = in[i].y;
  const float sin2_t = eta * eta * (1.0f - cos_i * cos_i);
  out[i] = sin2_t >= 1.0f ? -1.0f : fresnel_dielectric(eta, cos_i, sqrt(1.0f - sin2_t));
}

/* Glass scattering of direction d at normal n with uniforms u: new direction and weight. */
__kernel void probe_glass(__global const float4* in, float ior, __global float4* out) {
  const size_t i = get_global_id(0);
  float3 weight;
  const float3 dir = bsdf_glass_sample(in[3 * i].xyz, in[3 * i + 1].xyz, (float3)(1.0f), ior,
                                       in[3 * i + 2], &weight);
  out[2 * i] = (float4)(dir, 0.0f);
  out[2 * i + 1] = (float4)(weight, 0.0f);
}

/* n directions: mode 0 cosine hemisphere around +z, mode 1 Phong lobe (exponent) around +z,
 * using the renderer's RNG stream (key, sample i, dimension 1). */
__kernel void probe_sample_directions(uint mode, float exponent, uint k0, uint k1,
                                      __global float4* out) {
  const uint i = (uint)get_global_id(0);
  RngKey key;
  key.k0 = k0;
  key.k1 = k1;
  const float4 u = rng_uniform4(key, 0u, i, 1u);
  const float3 axis = (float3)(0.0f, 0.0f, 1.0f);
  const float3 d = mode == 0u ? sample_cosine_hemisphere(axis, u.xy) : sample_phong_lobe(axis, exponent, u.xy);
  out[i] = (float4)(d, 0.0f);
}

/* unit_circle(u) for each u. */
__kernel void probe_unit_circle(__global const float* u, __global float2* out) {
  const size_t i = get_global_id(0);
  out[i] = unit_circle(u[i]);
}
