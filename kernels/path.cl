/* path.cl: the stages of one path, written once and called by every execution form.
 *
 *   path_begin      camera sample -> PathState with the camera ray          (ray generation)
 *   path_intersect  PathState ray -> Hit                                    (intersection)
 *   path_shade      PathState + Hit -> emission added, next ray or ended    (shading)
 *
 * Estimators (CLPT_ESTIMATOR_*, types.h):
 *  - book: no next-event estimation; a path gains light only when it hits an emitter, which
 *    ends it; a miss ends it (black background).
 *  - nee: at every Lambertian or Phong vertex that may still scatter, one shadow ray towards a
 *    point sampled on a light (light.cl); its contribution and that of a BSDF-sampled ray hitting
 *    the light are weighted by the power heuristic (Veach's MIS, beta = 2), so the two strategies
 *    together count every light path once. Glass is specular: no shadow ray there, and a light
 *    hit after glass (or by the camera ray) has weight 1.
 * Segment `bounce` = 0 is the camera ray; at most max_bounces scattering events follow, and
 * emission found at the end of the last segment still counts. A shadow ray from a vertex that may
 * scatter is the same segment as the BSDF ray it competes with, so both estimators sum the same
 * path lengths and converge to the same image. Russian roulette (rr_from) ends a path at a
 * scattering event from bounce rr_from on with probability 1 - q, q = min(1, max throughput),
 * and divides the survivors by q: the expectation is unchanged.
 *
 * Specialisation (decided on the host in kernel_options.cpp, one place): CLPT_HAS_PHONG,
 * CLPT_HAS_GLASS and CLPT_HAS_RR compile those in; CLPT_ESTIMATOR fixes the estimator (the
 * generic kernel reads params->estimator at run time). */
#ifndef CLPT_PATH_CL
#define CLPT_PATH_CL

#include "types.h"
#include "maths.cl"
#include "path_state.h"
#include "rng.cl"
#include "sampler.cl"
#include "camera.cl"
#include "intersect.cl"
#include "bsdf.cl"
#include "light.cl"

#ifndef CLPT_HAS_PHONG
#define CLPT_HAS_PHONG 1
#endif
#ifndef CLPT_HAS_GLASS
#define CLPT_HAS_GLASS 1
#endif
#ifndef CLPT_HAS_RR
#define CLPT_HAS_RR 1
#endif
#ifdef CLPT_ESTIMATOR
#define CLPT_NEE_COMPILED (CLPT_ESTIMATOR == CLPT_ESTIMATOR_NEE)
#define CLPT_NEE_ON(params) (CLPT_ESTIMATOR == CLPT_ESTIMATOR_NEE)
#else
#define CLPT_NEE_COMPILED 1
#define CLPT_NEE_ON(params) ((params)->estimator == CLPT_ESTIMATOR_NEE)
#endif

/* One path's state: the fields of CLPT_PATH_FIELDS (path_state.h), where each is documented. */
typedef struct PathState {
  CLPT_PATH_STATE_MEMBERS
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
  path.bsdf_pdf = (real)0;
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
#if CLPT_HAS_PHONG || CLPT_HAS_GLASS /* read only where there is a choice (else an unused variable) */
  const uint material = sphere->material;
#endif
  Vec3 next = bsdf_lambertian_sample(d, normal, rho, u, weight);
#if CLPT_HAS_PHONG
  Vec3 phong_weight;
  const Vec3 phong = bsdf_phong_sample(d, normal, rho, (real)sphere->phong_exponent, u, &phong_weight);
  next = v3_select(material == CLPT_MATERIAL_PHONG, phong, next);
  *weight = v3_select(material == CLPT_MATERIAL_PHONG, phong_weight, *weight);
#endif
#if CLPT_HAS_GLASS
  Vec3 glass_weight;
  const Vec3 glass = bsdf_glass_sample(d, normal, rho, (real)sphere->ior, u, &glass_weight);
  next = v3_select(material == CLPT_MATERIAL_GLASS, glass, next);
  *weight = v3_select(material == CLPT_MATERIAL_GLASS, glass_weight, *weight);
#endif
  return next;
}

/* f cos towards wi and the BSDF sampler's density of wi, at a non-emitting surface (next-event
 * estimation). Glass is specular: 0 and 0. */
CLPT_INLINE Vec3 material_eval(__global const GpuSphere* sphere, Vec3 d, Vec3 normal, Vec3 wi, real* pdf) {
  const Vec3 rho = v3_load_global(sphere->reflectance);
#if CLPT_HAS_PHONG || CLPT_HAS_GLASS /* read only where there is a choice (else an unused variable) */
  const uint material = sphere->material;
#endif
  Vec3 f_cos = bsdf_lambertian_eval(d, normal, rho, wi, pdf);
#if CLPT_HAS_PHONG
  real phong_pdf;
  const Vec3 phong = bsdf_phong_eval(d, normal, rho, (real)sphere->phong_exponent, wi, &phong_pdf);
  f_cos = v3_select(material == CLPT_MATERIAL_PHONG, phong, f_cos);
  *pdf = material == CLPT_MATERIAL_PHONG ? phong_pdf : *pdf;
#endif
#if CLPT_HAS_GLASS
  f_cos = v3_select(material == CLPT_MATERIAL_GLASS, v3_splat((real)0), f_cos);
  *pdf = material == CLPT_MATERIAL_GLASS ? (real)0 : *pdf;
#endif
  return f_cos;
}

/* Power heuristic weight of a strategy with density a against one with density b. */
CLPT_INLINE real mis_power(real a, real b) {
  const real a2 = a * a, b2 = b * b;
  return a2 + b2 > (real)0 ? a2 / (a2 + b2) : (real)0;
}

/* Next-event estimation at the vertex hit_point of `sphere` (index), for a path arriving along d:
 * one shadow ray to a light sample; returns the MIS-weighted radiance it brings (throughput
 * not yet applied) and counts the shadow ray in *segments. */
CLPT_INLINE Vec3 next_event(const PathState* path, __global const GpuSphere* spheres,
                            __global const GpuLight* lights, const GpuRenderParams* params,
                            int index, Vec3 hit_point, Vec3 normal, uint* segments) {
  /* With no light, light_sample reads the buffer's placeholder entry and returns pdf 0 (no early
   * return: a branch here would stop PoCL's vectoriser). */
  __global const GpuSphere* sphere = &spheres[index];
  const Uniform4 u = sampler_uniform4(rng_key_of(params), params->sampler, path->pixel, path->sample,
                                       CLPT_DIM_LIGHT + path->bounce);
  const LightSample ls = light_sample(lights, params->light_count, spheres, hit_point, u);
  real bsdf_pdf;
  const Vec3 f_cos = material_eval(sphere, path->direction, normal, ls.direction, &bsdf_pdf);
  const int skip = v3_dot(ls.direction, normal) > (real)0 ? index : -1;
  const Hit shadow = scene_intersect(spheres, params->sphere_count, hit_point, ls.direction,
                                     params->ray_epsilon, skip);
  *segments += 1u;
  /* Visible: the sampled point faces the vertex (light_sample) and the first thing along the ray
   * is the emitter, at the sampled point's distance (nothing in between). */
  const bool visible = ls.pdf > (real)0 && shadow.sphere == ls.sphere &&
                       shadow.t >= ls.distance * (real)0.999f && !v3_is_zero(f_cos);
  const real weight = visible ? mis_power(ls.pdf, bsdf_pdf) / ls.pdf : (real)0;
  return v3_scale(v3_mul(f_cos, v3_load_global(spheres[ls.sphere].emission)), weight);
}

/* Field-wise choice between two path states (a select of the whole struct would stop PoCL's
 * vectoriser, see v3_select). */
CLPT_INLINE PathState path_select(bool c, PathState a, PathState b) {
  PathState p;
  CLPT_PATH_SELECT_FIELDS
  return p;
}

/* One shading event: a miss ends the path (black background); an emitter adds its emission
 * (MIS-weighted under nee) and ends it (emitters do not reflect); past max_bounces the path ends;
 * otherwise, under nee, a shadow ray adds the light it finds, and the material scatters the path.
 * Written as selects over the cases, not branches, so that PoCL vectorises it. */
CLPT_INLINE void path_shade(PathState* path, Hit hit, __global const GpuSphere* spheres,
                            __global const GpuLight* lights, const GpuRenderParams* params) {
  path->segments += 1u;
  const bool missed = hit.sphere < 0;
  const int index = missed ? 0 : hit.sphere;
  __global const GpuSphere* sphere = &spheres[index];
  const bool emitter = !missed && sphere->material == CLPT_MATERIAL_EMITTER;
  bool scatters = !missed && !emitter && path->bounce < params->max_bounces;

  const real t = missed ? (real)0 : hit.t;
  const Vec3 hit_point = v3_add_scaled(path->origin, path->direction, t);
  const Vec3 normal = sphere_normal_at(sphere, path->origin, path->direction, t);

  Vec3 emitted = v3_mul(path->throughput, v3_load_global(sphere->emission));
#if CLPT_NEE_COMPILED
  if (CLPT_NEE_ON(params)) {
    /* A BSDF-sampled ray that found a light competes with the light sample taken before it. */
    const real light_pdf = path->bsdf_pdf > (real)0
        ? light_pdf_of_hit(lights, params->light_count, index, normal, path->direction, t) : (real)0;
    emitted = v3_scale(emitted, path->bsdf_pdf > (real)0 ? mis_power(path->bsdf_pdf, light_pdf) : (real)1);
  }
#else
  (void)lights;
#endif
  path->radiance = v3_select(emitter, v3_add(path->radiance, emitted), path->radiance);

  const Uniform4 u = sampler_uniform4(rng_key_of(params), params->sampler, path->pixel, path->sample, 1u + path->bounce);
  Vec3 weight;
  const Vec3 next = material_sample(sphere, path->direction, normal, u, &weight);

#if CLPT_NEE_COMPILED
  if (CLPT_NEE_ON(params)) {
    uint shadow_segments = 0u;
    const Vec3 light = next_event(path, spheres, lights, params, index, hit_point, normal, &shadow_segments);
    path->radiance = v3_select(scatters, v3_add(path->radiance, v3_mul(path->throughput, light)), path->radiance);
    path->segments += scatters ? shadow_segments : 0u;
    real next_pdf;
    (void)material_eval(sphere, path->direction, normal, next, &next_pdf);
    path->bsdf_pdf = next_pdf;
  }
#endif

  Vec3 throughput = v3_mul(path->throughput, weight);
#if CLPT_HAS_RR
  /* Russian roulette: survive with q = min(1, max throughput); u3 is free at every bounce. */
  const real max_rg = throughput.x > throughput.y ? throughput.x : throughput.y;
  const real max_rgb = max_rg > throughput.z ? max_rg : throughput.z;
  const real q = max_rgb < (real)1 ? max_rgb : (real)1; /* selects: fmin/fmax pairs stop PoCL's vectoriser */
  const bool roulette = path->bounce >= params->rr_from;
  scatters = scatters && (!roulette || u.u3 < q);
  throughput = v3_scale(throughput, roulette && q > (real)0 ? (real)1 / q : (real)1);
#endif

  path->throughput = v3_select(scatters, throughput, path->throughput);
  path->origin = v3_select(scatters, hit_point, path->origin);
  path->direction = v3_select(scatters, next, path->direction);
  path->skip_sphere = scatters && v3_dot(next, normal) > (real)0 ? index : -1;
  path->bounce += scatters ? 1u : 0u;
  path->alive = scatters && !v3_is_zero(weight) ? 1 : 0;
}

#endif
