/* light.cl: next-event estimation's light sampling (the `nee` estimator).
 *
 * One emitter is picked uniformly from the light buffer, then a point uniformly by area on its
 * cap (GpuLight, types.h): the part of the emitter sphere that the host found not to be hidden
 * inside another sphere. For the book's light that cap is the radius-1.41 disc-like patch below
 * the ceiling, so nearly every shadow ray can reach it; sampling the whole radius-100 sphere, or
 * the cone it subtends, would send most shadow rays into the ceiling (README "Estimators").
 * Densities are per unit solid angle at the shading point, the light pick included, so that
 * path.cl can weight light samples and BSDF hits against each other (power heuristic). */
#ifndef CLPT_LIGHT_CL
#define CLPT_LIGHT_CL

#include "types.h"
#include "maths.cl"
#include "rng.cl"
#include "intersect.cl"

/* Sampler dimension of the light sample taken at bounce b: CLPT_DIM_LIGHT + b (sampler.cl and
 * rng.cl number the camera 0 and scattering 1 + b). */
#define CLPT_DIM_LIGHT 0x40000000u

typedef struct LightSample {
  Vec3 direction; /* unit, from the shading point to the sampled point */
  real distance;  /* to the sampled point, world units */
  real pdf;       /* solid-angle density of this direction, light pick included; 0: unusable (the
                     point faces away from the shading point, or the density overflowed) */
  int sphere;     /* the emitter's index in the sphere buffer */
} LightSample;

/* Solid-angle density of a cap point seen at `distance` under `cos_light` (its normal against
 * the ray), when each of light_count lights is picked with probability 1 / light_count. */
CLPT_INLINE real light_solid_angle_pdf(real distance, real cos_light, real cap_area, uint light_count) {
  const real denominator = cap_area * fabs(cos_light) * (real)light_count;
  return denominator > (real)0 ? distance * distance / denominator : (real)0;
}

CLPT_INLINE LightSample light_sample(__global const GpuLight* lights, uint light_count,
                                     __global const GpuSphere* spheres, Vec3 x, Uniform4 u) {
  const uint index = min((uint)(u.u2 * (float)light_count), light_count - 1u);
  __global const GpuLight* light = &lights[index];
  __global const GpuSphere* sphere = &spheres[light->sphere];
  /* A point at polar angle theta from the cap axis, 1 - cos(theta) uniform in [0, one_minus_cos_cap]
   * (uniform by area on a sphere); sin(theta) from v (2 - v) keeps precision for tiny caps. */
  const real v = (real)u.u1 * (real)light->one_minus_cos_cap;
  const real sin_theta = clpt_sqrt(fmax((real)0, v * ((real)2 - v)));
  const Float2 circle = unit_circle(u.u0);
  const Vec3 normal = to_world(v3(sin_theta * circle.x, sin_theta * circle.y, (real)1 - v),
                               v3_load_global(light->cap_axis));
  /* p = c + r normal = s0 + r (normal - n0): the small difference keeps the point's precision. */
  const Vec3 p = v3_add_scaled(sphere_surface_point(sphere), v3_sub(normal, sphere_surface_normal(sphere)),
                               sphere_radius(sphere));
  const Vec3 to_point = v3_sub(p, x);
  LightSample s;
  s.distance = clpt_sqrt(v3_dot(to_point, to_point));
  s.direction = v3_scale(to_point, (real)1 / s.distance);
  const real cos_light = v3_dot(normal, s.direction);
  /* Only the side facing x can be seen from x: from outside the sphere the point must face back
   * along the ray, from inside it must face along it. Outside means |c - x|^2 - r^2 > 0, formed as
   * intersect.cl forms c' (no r^2 term). The shadow ray's distance cannot tell the sides apart:
   * the chord between them is as short as 2r, or shorter near the silhouette. */
  const Vec3 e = v3_sub(sphere_surface_point(sphere), x);
  const real r = sphere_radius(sphere);
  const bool outside = v3_dot(e, e) - (real)2 * r * v3_dot(sphere_surface_normal(sphere), e) > (real)0;
  const bool facing = outside ? cos_light < (real)0 : cos_light > (real)0;
  s.pdf = light_solid_angle_pdf(s.distance, cos_light, light->cap_area, light_count);
  s.pdf = facing && is_finite_real(s.pdf) ? s.pdf : (real)0;
  s.sphere = (int)light->sphere;
  return s;
}

/* Density with which light_sample would have chosen the direction d that hit emitter `sphere` at
 * distance t with outward normal `normal` there: 0 when the sphere is no light or the point lies
 * outside its cap (a tolerance of 1e-3 of the cap's height absorbs float rounding at the rim). */
CLPT_INLINE real light_pdf_of_hit(__global const GpuLight* lights, uint light_count, int sphere,
                                  Vec3 normal, Vec3 d, real t) {
  real pdf = (real)0;
#ifdef CLPT_LIGHT_COUNT
  (void)light_count;
#if CLPT_UNROLL_SCENE_LOOPS /* intersect.cl */
#pragma unroll
#else
#pragma unroll 1
#endif
  for (uint i = 0; i < CLPT_LIGHT_COUNT; ++i) {
    const uint count = CLPT_LIGHT_COUNT;
#else
  for (uint i = 0; i < light_count; ++i) {
    const uint count = light_count;
#endif
    __global const GpuLight* light = &lights[i];
    const real height = (real)1 - v3_dot(normal, v3_load_global(light->cap_axis));
    const bool in_cap = (int)light->sphere == sphere && height <= (real)light->one_minus_cos_cap * (real)1.001f;
    pdf = in_cap ? light_solid_angle_pdf(t, v3_dot(normal, d), light->cap_area, count) : pdf;
  }
  return pdf;
}

#endif
