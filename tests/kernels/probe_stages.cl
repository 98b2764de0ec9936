/* probe_stages.cl: thin kernels that call the renderer's own stage functions on inputs from the
 * host, so unit tests check the device code itself (not a host copy of it). The scene probe binds
 * no texturing buffer, so no alpha test is compiled (alpha.cl). */
#define CLPT_HAS_ALPHA 0
#include "types.h"
#include "maths.cl"
#include "rng.cl"
#include "sampler.cl"
#include "camera.cl"
#include "intersect.cl"
#include "bvh.cl"
#include "bsdf.cl"
#include "bsdf_pbr.cl"

CLPT_INLINE Vec3 v3_from4(float4 v) { return v3(v.x, v.y, v.z); }
CLPT_INLINE float4 v3_to4(Vec3 v) { return (float4)(v.x, v.y, v.z, 0.0f); }

/* Philox4x32-10 of (counter[i], key): 4 words per counter. */
__kernel void probe_philox(__global const uint4* counters, uint k0, uint k1, __global uint4* out) {
  const size_t i = get_global_id(0);
  const uint4 c = counters[i];
  const Philox4 r = philox4x32_10(philox4(c.x, c.y, c.z, c.w), k0, k1);
  out[i] = (uint4)(r.x, r.y, r.z, r.w);
}

/* The sampler's draw for samples sample_begin + i of (pixel, dimension): out[i] = (u0, u1, u2, u3). */
__kernel void probe_sampler(uint k0, uint k1, uint sampler, uint pixel, uint dimension, uint sample_begin,
                            __global float4* out) {
  const uint i = (uint)get_global_id(0);
  RngKey key;
  key.k0 = k0;
  key.k1 = k1;
  const Uniform4 u = sampler_uniform4(key, sampler, pixel, sample_begin + i, dimension);
  out[i] = (float4)(u.u0, u.u1, u.u2, u.u3);
}

/* The camera's position inside the pixel for samples sample_begin + i of `pixel` (camera.cl). */
__kernel void probe_subpixel(uint k0, uint k1, uint sampler, uint pixel, uint sample_begin, __global float2* out) {
  const uint i = (uint)get_global_id(0);
  RngKey key;
  key.k0 = k0;
  key.k1 = k1;
  const Float2 s = camera_subpixel(key, sampler, pixel, sample_begin + i);
  out[i] = (float2)((float)s.x, (float)s.y);
}

/* Closest hit of ray i (origin with the sphere to skip in .w, unit direction) against spheres. */
__kernel void probe_intersect(__global const GpuSphere* spheres, uint count,
                              __global const float4* rays, float t_min, __global float2* out) {
  const size_t i = get_global_id(0);
  const Vec3 o = v3_from4(rays[2 * i]);
  const Vec3 d = v3_from4(rays[2 * i + 1]);
  const Hit hit = scene_intersect(spheres, count, o, d, t_min, (int)rays[2 * i].w);
  out[i] = (float2)(hit.t, (float)hit.sphere);
}

/* Scene queries of ray i (camera-relative origin, unit direction; no sphere skipped), answered by
 * the hierarchy (brute_force 0: bvh.cl's scene_closest_hit and scene_hierarchy_occluded, as the
 * renderer calls them) or by testing every primitive with the same intersection functions
 * (brute_force 1: sphere_count spheres, triangle_count triangles). out[2i] = (t, sphere, triangle,
 * 0); out[2i + 1] = (occluded before shadow_near[i], occluded before shadow_far[i], 0, 0). */
__kernel void probe_scene_hit(__global const GpuSphere* spheres, __global const GpuBvhNode* nodes,
                              __global const GpuTriangle* triangles, const GpuRenderParams params,
                              uint brute_force, uint sphere_count, uint triangle_count,
                              __global const float4* rays, __global const float2* shadow_t, __global float4* out) {
  const size_t i = get_global_id(0);
  const Vec3 o = v3_from4(rays[2 * i]);
  const Vec3 d = v3_from4(rays[2 * i + 1]);
  const SceneBuffers scene = scene_buffers(spheres, 0, nodes, triangles, 0, 0, 0);
  Hit hit = no_hit();
  bool near_blocked = false, far_blocked = false;
  if (brute_force) {
    const ShearedRay ray = sheared_ray(o, d);
    for (uint k = 0; k < sphere_count; ++k) {
      const real t = sphere_intersect(&spheres[k], o, d, params.ray_epsilon);
      if (t < hit.t) {
        hit.t = t;
        hit.sphere = (int)k;
      }
    }
    for (uint k = 0; k < triangle_count; ++k) {
      const real t = triangle_intersect(&ray, &triangles[k], hit.t);
      if (t < hit.t) {
        hit.t = t;
        hit.sphere = -1;
        hit.triangle = (int)k;
      }
    }
  } else {
    hit = scene_closest_hit(&scene, &params, o, d, -1, 0u);
    near_blocked = scene_hierarchy_occluded(&scene, &params, o, d, shadow_t[i].x, -1, -1, 0u);
    far_blocked = scene_hierarchy_occluded(&scene, &params, o, d, shadow_t[i].y, -1, -1, 0u);
  }
  out[2 * i] = (float4)(hit.t, (float)hit.sphere, (float)hit.triangle, 0.0f);
  out[2 * i + 1] = (float4)(near_blocked ? 1.0f : 0.0f, far_blocked ? 1.0f : 0.0f, 0.0f, 0.0f);
}

/* Camera direction for pixel (col,row) with a given sub-pixel offset. */
__kernel void probe_camera(const GpuRenderParams params, __global const float4* requests,
                           __global float4* out) {
  const size_t i = get_global_id(0);
  const float4 r = requests[i]; /* col, row, subpixel x, subpixel y */
  const Vec3 d = camera_ray_direction(&params.camera, params.width, params.height, (uint)r.x,
                                      (uint)r.y, f2(r.z, r.w));
  out[i] = v3_to4(d);
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
  const float4 u4 = in[3 * i + 2];
  Uniform4 u;
  u.u0 = u4.x;
  u.u1 = u4.y;
  u.u2 = u4.z;
  u.u3 = u4.w;
  Vec3 weight;
  const Vec3 dir = bsdf_glass_sample(v3_from4(in[3 * i]), v3_from4(in[3 * i + 1]), v3_splat(1.0f), ior,
                                     u, &weight);
  out[2 * i] = v3_to4(dir);
  out[2 * i + 1] = v3_to4(weight);
}

/* n directions: mode 0 cosine hemisphere around +z, mode 1 Phong lobe (exponent) around +z,
 * using the renderer's RNG stream (key, sample i, dimension 1). */
__kernel void probe_sample_directions(uint mode, float exponent, uint k0, uint k1,
                                      __global float4* out) {
  const uint i = (uint)get_global_id(0);
  RngKey key;
  key.k0 = k0;
  key.k1 = k1;
  const Uniform4 u = rng_uniform4(key, 0u, i, 1u);
  const Vec3 axis = v3(0.0f, 0.0f, 1.0f);
  const Vec3 d = mode == 0u ? sample_cosine_hemisphere(axis, u.u0, u.u1)
                            : sample_phong_lobe(axis, exponent, u.u0, u.u1);
  out[i] = v3_to4(d);
}

/* unit_circle(u) for each u. */
__kernel void probe_unit_circle(__global const float* u, __global float2* out) {
  const size_t i = get_global_id(0);
  const Float2 c = unit_circle(u[i]);
  out[i] = (float2)(c.x, c.y);
}

/* pow_unit(u, a) for each (u, a). */
__kernel void probe_pow_unit(__global const float2* in, __global float* out) {
  const size_t i = get_global_id(0);
  out[i] = pow_unit(in[i].x, in[i].y);
}

/* clpt_udiv(a, b) for each (a, b). */
__kernel void probe_udiv(__global const uint2* in, __global uint* out) {
  const size_t i = get_global_id(0);
  out[i] = clpt_udiv(in[i].x, in[i].y);
}

/* The Pbr material (bsdf_pbr.cl). params: base colour xyz and metallic w; shape: roughness x,
 * ior y, transmission z, w: 0 thin-walled, 1 a volume entered (wo outside), 2 a volume left (wo
 * inside: the outward normal is -z). Each work-item i reads wo (local frame, +z the normal) and uniforms u
 * from in[2 i], in[2 i + 1], and writes the sampled direction (w: its pdf), the weight (w: 0),
 * then f cos and the pdf evaluated at in[2 i + 1].xyz read as a direction (eval mode). */
__kernel void probe_pbr(float4 params, float4 shape, __global const float4* in, __global float4* out) {
  const size_t i = get_global_id(0);
  const PbrParams p =
      pbr_params(v3(params.x, params.y, params.z), params.w, shape.x, shape.y, shape.z, shape.w > 0.5f ? 1 : 0);
  const float4 wo4 = in[2 * i], u4 = in[2 * i + 1];
  const Vec3 n = v3(0.0f, 0.0f, shape.w > 1.5f ? -1.0f : 1.0f);
  const Vec3 d = v3(-wo4.x, -wo4.y, -wo4.z);
  Uniform4 u;
  u.u0 = u4.x;
  u.u1 = u4.y;
  u.u2 = u4.z;
  u.u3 = u4.w;
  Vec3 weight;
  real pdf;
  const Vec3 wi = bsdf_pbr_sample(d, n, &p, u, &weight, &pdf);
  real eval_pdf;
  const Vec3 f_cos = bsdf_pbr_eval(d, n, &p, v3(u4.x, u4.y, u4.z), &eval_pdf);
  out[3 * i] = (float4)(wi.x, wi.y, wi.z, pdf);
  out[3 * i + 1] = (float4)(weight.x, weight.y, weight.z, 0.0f);
  out[3 * i + 2] = (float4)(f_cos.x, f_cos.y, f_cos.z, eval_pdf);
}

/* The Pbr material's albedo table through its lookup (bsdf_pbr.cl, pbr_albedo): in[i] = (cos_o,
 * roughness) -> (S, B, G, 0). */
__kernel void probe_pbr_albedo(__global const float2* in, __global float4* out) {
  const size_t i = get_global_id(0);
  const PbrAlbedo e = pbr_albedo(in[i].x, sqrt(in[i].y));
  out[i] = (float4)(e.s, e.b, e.g, 0.0f);
}
