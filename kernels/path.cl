/* path.cl: the stages of one path, written once and called by every execution form.
 *
 *   path_begin      camera sample -> PathState with the camera ray          (ray generation)
 *   path_intersect  PathState ray -> Hit                                    (intersection)
 *   path_shade      PathState + Hit -> emission added, next ray or ended    (shading)
 *
 * The estimator is the book's: no next-event estimation; a path gains light only when it hits
 * an emitter, which ends it; a miss ends it (black background). Segment `bounce` = 0 is the
 * camera ray; at most max_bounces scattering events follow, and emission found at the end of the
 * last segment still counts.
 *
 * Specialisation (decided on the host in kernel_options.cpp, one place): CLPT_HAS_PHONG and
 * CLPT_HAS_GLASS compile those materials in; a scene without them gets a shorter shader. */
#ifndef CLPT_PATH_CL
#define CLPT_PATH_CL

#include "types.h"
#include "maths.cl"
#include "rng.cl"
#include "camera.cl"
#include "intersect.cl"
#include "bsdf.cl"

#ifndef CLPT_HAS_PHONG
#define CLPT_HAS_PHONG 1
#endif
#ifndef CLPT_HAS_GLASS
#define CLPT_HAS_GLASS 1
#endif

typedef struct PathState {
  float3 origin;     /* camera-relative world units */
  float3 direction;  /* unit */
  float3 throughput; /* product of BSDF weights so far */
  float3 radiance;   /* light gathered so far */
  uint pixel;        /* global pixel index, row-major, row 0 at the top */
  uint sample;       /* global sample index within the pixel */
  uint bounce;       /* index of the current segment: 0 = camera ray */
  uint segments;     /* segments traced so far (for rays/s) */
  int skip_sphere;   /* sphere the ray is leaving on its outer side (cannot be hit), or -1 */
  int alive;         /* 0 once the path has ended */
} PathState;

CLPT_INLINE RngKey rng_key_of(const GpuRenderParams* params) {
  RngKey key;
  key.k0 = params->seed_lo;
  key.k1 = params->seed_hi;
  return key;
}

CLPT_INLINE PathState path_begin(const GpuRenderParams* params, uint pixel, uint sample) {
  const uint col = pixel % params->width;
  const uint row = pixel / params->width;
  const float2 subpixel = camera_subpixel(rng_key_of(params), params->sampler, pixel, sample);
  PathState path;
  path.origin = (float3)(0.0f);
  path.direction = camera_ray_direction(&params->camera, params->width, params->height, col, row, subpixel);
  path.throughput = (float3)(1.0f);
  path.radiance = (float3)(0.0f);
  path.pixel = pixel;
  path.sample = sample;
  path.bounce = 0u;
  path.segments = 0u;
  path.skip_sphere = -1;
  path.alive = 1;
  return path;
}

CLPT_INLINE Hit path_intersect(const PathState* path, __global const GpuSphere* spheres,
                          const GpuRenderParams* params) {
  return scene_intersect(spheres, params->sphere_count, path->origin, path->direction,
                         params->ray_epsilon, path->skip_sphere);
}

/* Scatter at a non-emitting surface: new direction and throughput. */
CLPT_INLINE void path_scatter(PathState* path, __global const GpuSphere* sphere, int sphere_index,
                         float3 hit_point, float3 normal, float4 u) {
  const float3 rho = load_global_float3(sphere->reflectance);
  float3 weight = (float3)(0.0f);
  float3 next = path->direction;
  const uint material = sphere->material;
  if (material == CLPT_MATERIAL_LAMBERTIAN) {
    next = bsdf_lambertian_sample(path->direction, normal, rho, u, &weight);
  }
#if CLPT_HAS_PHONG
  else if (material == CLPT_MATERIAL_PHONG) {
    next = bsdf_phong_sample(path->direction, normal, rho, sphere->phong_exponent, u, &weight);
  }
#endif
#if CLPT_HAS_GLASS
  else if (material == CLPT_MATERIAL_GLASS) {
    next = bsdf_glass_sample(path->direction, normal, rho, sphere->ior, u, &weight);
  }
#endif
  path->throughput *= weight;
  path->origin = hit_point;
  path->direction = next;
  path->skip_sphere = dot(next, normal) > 0.0f ? sphere_index : -1;
  path->bounce += 1u;
  if (weight.x == 0.0f && weight.y == 0.0f && weight.z == 0.0f) path->alive = 0;
}

CLPT_INLINE void path_shade(PathState* path, Hit hit, __global const GpuSphere* spheres,
                       const GpuRenderParams* params) {
  path->segments += 1u;
  if (hit.sphere < 0) { /* escaped: black background */
    path->alive = 0;
    return;
  }
  __global const GpuSphere* sphere = &spheres[hit.sphere];
  if (sphere->material == CLPT_MATERIAL_EMITTER) { /* emitters do not reflect */
    path->radiance += path->throughput * load_global_float3(sphere->emission);
    path->alive = 0;
    return;
  }
  if (path->bounce >= params->max_bounces) {
    path->alive = 0;
    return;
  }
  const float3 hit_point = path->origin + hit.t * path->direction;
  const float3 normal = sphere_normal_at(sphere, path->origin, path->direction, hit.t);
  const float4 u = rng_uniform4(rng_key_of(params), path->pixel, path->sample, 1u + path->bounce);
  path_scatter(path, sphere, hit.sphere, hit_point, normal, u);
}

#endif
