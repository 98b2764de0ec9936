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
  Vec3 origin;       /* camera-relative world units */
  Vec3 direction;    /* unit */
  Vec3 throughput;   /* product of BSDF weights so far */
  Vec3 radiance;     /* light gathered so far */
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
  const Float2 subpixel = camera_subpixel(rng_key_of(params), params->sampler, pixel, sample);
  PathState path;
  path.origin = v3_splat(0.0f);
  path.direction = camera_ray_direction(&params->camera, params->width, params->height, col, row, subpixel);
  path.throughput = v3_splat(1.0f);
  path.radiance = v3_splat(0.0f);
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

/* Next direction and throughput weight at a non-emitting surface. Materials left out of the
 * build (CLPT_HAS_*) fall back to Lambertian, which the host never lets happen. */
CLPT_INLINE Vec3 material_sample(__global const GpuSphere* sphere, Vec3 d, Vec3 normal, Uniform4 u,
                                 Vec3* weight) {
  const Vec3 rho = v3_load_global(sphere->reflectance);
  const uint material = sphere->material;
  Vec3 next = bsdf_lambertian_sample(d, normal, rho, u, weight);
#if CLPT_HAS_PHONG
  Vec3 phong_weight;
  const Vec3 phong = bsdf_phong_sample(d, normal, rho, sphere->phong_exponent, u, &phong_weight);
  next = v3_select(material == CLPT_MATERIAL_PHONG, phong, next);
  *weight = v3_select(material == CLPT_MATERIAL_PHONG, phong_weight, *weight);
#endif
#if CLPT_HAS_GLASS
  Vec3 glass_weight;
  const Vec3 glass = bsdf_glass_sample(d, normal, rho, sphere->ior, u, &glass_weight);
  next = v3_select(material == CLPT_MATERIAL_GLASS, glass, next);
  *weight = v3_select(material == CLPT_MATERIAL_GLASS, glass_weight, *weight);
#endif
  return next;
}

/* One shading event: a miss ends the path (black background); an emitter adds its emission and
 * ends it (emitters do not reflect); past max_bounces the path ends; otherwise the material
 * scatters it. Written as selects over the cases, not branches, so that PoCL vectorises it. */
CLPT_INLINE void path_shade(PathState* path, Hit hit, __global const GpuSphere* spheres,
                            const GpuRenderParams* params) {
  path->segments += 1u;
  const bool missed = hit.sphere < 0;
  const int index = missed ? 0 : hit.sphere;
  __global const GpuSphere* sphere = &spheres[index];
  const bool emitter = !missed && sphere->material == CLPT_MATERIAL_EMITTER;
  const bool scatters = !missed && !emitter && path->bounce < params->max_bounces;

  const Vec3 emitted = v3_mul(path->throughput, v3_load_global(sphere->emission));
  path->radiance = v3_select(emitter, v3_add(path->radiance, emitted), path->radiance);

  const float t = missed ? 0.0f : hit.t;
  const Vec3 hit_point = v3_add_scaled(path->origin, path->direction, t);
  const Vec3 normal = sphere_normal_at(sphere, path->origin, path->direction, t);
  const Uniform4 u = rng_uniform4(rng_key_of(params), path->pixel, path->sample, 1u + path->bounce);
  Vec3 weight;
  const Vec3 next = material_sample(sphere, path->direction, normal, u, &weight);

  path->throughput = v3_select(scatters, v3_mul(path->throughput, weight), path->throughput);
  path->origin = v3_select(scatters, hit_point, path->origin);
  path->direction = v3_select(scatters, next, path->direction);
  path->skip_sphere = scatters && v3_dot(next, normal) > 0.0f ? index : -1;
  path->bounce += scatters ? 1u : 0u;
  path->alive = scatters && !v3_is_zero(weight) ? 1 : 0;
}

#endif
