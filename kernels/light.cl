/* light.cl: next-event estimation's light sampling (the `nee` estimator).
 *
 * The light list (GpuLight, types.h) holds the emitter spheres' caps, then the emitting
 * triangles. Kernels without triangle lights (CLPT_HAS_TRIANGLE_LIGHTS 0: the scene has no
 * emitting mesh) pick a light uniformly, as before triangles could be lights; kernels with them
 * pick by power from the host's alias table (host/scene/light_pick.h), one draw, constant time.
 * Then a point uniformly by area on the light: on a sphere, its cap, the part of the emitter that
 * the host found not to be hidden inside another sphere (for the book's light the radius-1.41
 * disc-like patch below the ceiling, so nearly every shadow ray can reach it; sampling the whole
 * radius-100 sphere, or the cone it subtends, would send most shadow rays into the ceiling, README
 * "Estimators"); on a triangle, uniformly over it. Emitting triangles shine on both sides, as a
 * BSDF hit on either side counts their emission (path.cl). Densities are per unit solid angle at
 * the shading point, the light pick included (pick probability x distance^2 / (area |cos|)), so
 * that path.cl can weight light samples and BSDF hits against each other (power heuristic); a
 * BSDF hit on an emitting triangle finds its pick probability / area in its shading record
 * (GpuTriangleShading.light_area_density). */
#ifndef CLPT_LIGHT_CL
#define CLPT_LIGHT_CL

#include "types.h"
#include "maths.cl"
#include "rng.cl"
#include "intersect.cl"
#include "triangle.cl"
#include "bvh.cl"
#include "texture.cl"

#ifndef CLPT_HAS_TRIANGLE_LIGHTS
#define CLPT_HAS_TRIANGLE_LIGHTS 1
#endif
/* Punctual lights by kind: named in a specialised kernel's options only when its scene has them
 * (kernel_options.cpp), so absent they are 0 there and 1 in the generic kernel. */
#ifdef CLPT_ESTIMATOR
#define CLPT_PUNCTUAL_DEFAULT 0
#else
#define CLPT_PUNCTUAL_DEFAULT 1
#endif
#ifndef CLPT_HAS_POINT_LIGHTS
#define CLPT_HAS_POINT_LIGHTS CLPT_PUNCTUAL_DEFAULT
#endif
#ifndef CLPT_HAS_SPOT_LIGHTS
#define CLPT_HAS_SPOT_LIGHTS CLPT_PUNCTUAL_DEFAULT
#endif
#ifndef CLPT_HAS_DIRECTIONAL_LIGHTS
#define CLPT_HAS_DIRECTIONAL_LIGHTS CLPT_PUNCTUAL_DEFAULT
#endif
#define CLPT_HAS_PUNCTUAL_LIGHTS (CLPT_HAS_POINT_LIGHTS || CLPT_HAS_SPOT_LIGHTS || CLPT_HAS_DIRECTIONAL_LIGHTS)
/* The environment light (environment.cl): 1 an image (sampled by nee), 2 a constant colour (seen
 * by escaping rays only); named likewise only when the scene has one. */
#ifndef CLPT_HAS_ENVIRONMENT
#define CLPT_HAS_ENVIRONMENT CLPT_PUNCTUAL_DEFAULT
#endif
/* Lights picked by power from the alias table (else uniformly over the sphere caps). A sampled
 * environment needs the alias pick's LightSample (emission, target); the host fills the table
 * uniformly when there are only sphere lights, so their pick is the same. */
/* An emission texture on a sphere (texture.cl) scales a sampled cap point's radiance, which the
 * alias pick's LightSample carries (emission): such a kernel takes that pick. */
#define CLPT_SPHERE_EMISSION_TEXTURES (CLPT_HAS_SPHERE_TEXTURES && CLPT_HAS_EMISSION_TEXTURES)
#define CLPT_LIGHT_PICK_BY_POWER \
  (CLPT_HAS_TRIANGLE_LIGHTS || CLPT_HAS_PUNCTUAL_LIGHTS || CLPT_HAS_ENVIRONMENT == 1 || CLPT_SPHERE_EMISSION_TEXTURES)
/* How far a directional light's shadow ray looks, world units: below CLPT_NO_HIT (maths.cl), and
 * small enough that its square stays a finite float (next_event forms the ray's length). */
#define CLPT_DIRECTIONAL_DISTANCE ((real)1e15f)
#if CLPT_HAS_TRIANGLE_LIGHTS && defined(CLPT_HAS_TRIANGLES) && !CLPT_HAS_TRIANGLES
#error "triangle lights need triangles (kernel_options.cpp)"
#endif

/* Sampler dimension of the light sample taken at bounce b: CLPT_DIM_LIGHT + b (sampler.cl and
 * rng.cl number the camera 0 and scattering 1 + b). */
#define CLPT_DIM_LIGHT 0x40000000u

typedef struct LightSample {
  Vec3 direction; /* unit, from the shading point to the sampled point */
  real distance;  /* to the sampled point, world units */
  real pdf;       /* solid-angle density of this direction, light pick included; 0: unusable (the
                     point faces away from the shading point, or the density overflowed) */
  int sphere;     /* the emitter's index in the sphere buffer; -1 for a triangle or punctual light */
#if CLPT_LIGHT_PICK_BY_POWER
  int triangle;   /* the emitting triangle's index in the triangle buffer; -1 for the others */
  /* Punctual lights (delta = 1): pdf is the pick probability alone, and emission the radiance
   * the light brings along direction: intensity x falloff / distance^2, or the irradiance. */
  int delta;
  Vec3 emission;  /* the light's emitted radiance per channel */
  /* Where a shadow ray to a triangle light ends: the sampled point moved off the triangle's plane
   * towards the shading point by its rounding bound (triangle_offset_origin), so that no rounding
   * puts the end behind the plane (the light itself is also skipped by index, bvh.cl). */
  Vec3 target;
#endif
} LightSample;

/* Solid-angle density of a cap point seen at `distance` under `cos_light` (its normal against
 * the ray), when each of light_count lights is picked with probability 1 / light_count. */
CLPT_INLINE real light_solid_angle_pdf(real distance, real cos_light, real cap_area, uint light_count) {
  const real denominator = cap_area * fabs(cos_light) * (real)light_count;
  return denominator > (real)0 ? distance * distance / denominator : (real)0;
}

/* The same density when the light was picked with probability `pick_probability`. */
CLPT_INLINE real light_pick_pdf(real distance, real cos_light, real area, real pick_probability) {
  const real denominator = area * fabs(cos_light);
  return denominator > (real)0 ? distance * distance * pick_probability / denominator : (real)0;
}

/* A point uniformly by area on the cap of sphere light `light` for draws u0, u1, seen from x:
 * direction and distance filled, pdf left to the caller; *cos_light is the point's normal
 * against the direction, *facing whether that side can be seen from x, *point_normal the point's
 * outward normal. */
CLPT_INLINE LightSample sphere_cap_sample(__global const GpuLight* light, __global const GpuSphere* spheres, Vec3 x,
                                          Uniform4 u, real* cos_light, bool* facing, Vec3* point_normal) {
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
  *cos_light = v3_dot(normal, s.direction);
  *point_normal = normal;
  /* Only the side facing x can be seen from x: from outside the sphere the point must face back
   * along the ray, from inside it must face along it. Outside means |c - x|^2 - r^2 > 0, formed as
   * intersect.cl forms c' (no r^2 term). The shadow ray's distance cannot tell the sides apart:
   * the chord between them is as short as 2r, or shorter near the silhouette. */
  const Vec3 e = v3_sub(sphere_surface_point(sphere), x);
  const real r = sphere_radius(sphere);
  const bool outside = v3_dot(e, e) - (real)2 * r * v3_dot(sphere_surface_normal(sphere), e) > (real)0;
  *facing = outside ? *cos_light < (real)0 : *cos_light > (real)0;
  s.pdf = (real)0;
  s.sphere = (int)light->sphere;
  return s;
}

#if CLPT_HAS_PUNCTUAL_LIGHTS
/* Punctual light `light` seen from x (KHR_lights_punctual): direction to it, distance (a
 * directional light's CLPT_DIRECTIONAL_DISTANCE), and in *emission what it brings: point and
 * spot I x spot ramp x range window / d^2, directional E. */
CLPT_INLINE Vec3 punctual_light_at(__global const GpuLight* light, Vec3 x, real* distance, Vec3* emission) {
  const Vec3 axis = v3_load_global(light->cap_axis);
  const Vec3 to_light = v3_sub(v3_load_global(light->position), x);
  const real d2 = v3_dot(to_light, to_light);
  const real d = clpt_sqrt(d2);
  Vec3 direction = v3_scale(to_light, d > (real)0 ? (real)1 / d : (real)0);
  /* The range window clamp(1 - (d / range)^4, 0, 1), the extension's recommended one. */
  const real range = light->range;
  const real q = range > (real)0 ? d2 / (range * range) : (real)0;
  const real window0 = (real)1 - q * q;
  const real window = window0 > (real)0 ? window0 : (real)0;
  real falloff = d2 > (real)0 ? window / d2 : (real)0;
#if CLPT_HAS_SPOT_LIGHTS
  const real ramp0 = -v3_dot(axis, direction) * (real)light->spot_scale + (real)light->spot_offset;
  const real ramp = ramp0 < (real)0 ? (real)0 : (ramp0 > (real)1 ? (real)1 : ramp0);
  falloff *= ramp * ramp;
#endif
  *distance = d;
#if CLPT_HAS_DIRECTIONAL_LIGHTS
  const bool directional = light->punctual == CLPT_LIGHT_DIRECTIONAL;
  direction = v3_select(directional, v3_neg(axis), direction);
  *distance = directional ? CLPT_DIRECTIONAL_DISTANCE : d;
  falloff = directional ? (real)1 : falloff;
#else
  (void)axis;
#endif
  *emission = v3_scale(v3_load_global(light->intensity), is_finite_real(falloff) ? falloff : (real)0);
  return direction;
}
#endif

#if !CLPT_LIGHT_PICK_BY_POWER
/* Sphere lights only, picked uniformly. */
CLPT_INLINE LightSample light_sample(const SceneBuffers* scene, uint light_count, Vec3 x, Uniform4 u) {
#ifdef CLPT_LIGHT_COUNT
  light_count = CLPT_LIGHT_COUNT; /* fixed: with one light the pick folds to entry 0, read alike by every path */
#endif
  const uint index = min((uint)(u.u2 * (float)light_count), light_count - 1u);
  __global const GpuLight* light = &scene->lights[index];
  real cos_light;
  bool facing;
  Vec3 point_normal;
  LightSample s = sphere_cap_sample(light, scene->spheres, x, u, &cos_light, &facing, &point_normal);
  s.pdf = light_solid_angle_pdf(s.distance, cos_light, light->cap_area, light_count);
  s.pdf = facing && is_finite_real(s.pdf) ? s.pdf : (real)0;
  return s;
}
#else
/* Sphere, triangle and punctual lights, picked by power: entry i = floor(u2 n) is kept when the
 * fraction of u2 n is below its alias threshold, else its alias is taken (Walker's alias method).
 * Every compiled kind's point is formed and the light's kind selects one (selects, not branches,
 * for PoCL). */
CLPT_INLINE LightSample light_sample(const SceneBuffers* scene, uint light_count, Vec3 x, Uniform4 u) {
  const float scaled = u.u2 * (float)light_count;
  const uint slot = min((uint)scaled, light_count - 1u);
  const float fraction = scaled - (float)slot;
  const uint index = fraction < scene->lights[slot].alias_threshold ? slot : scene->lights[slot].alias;
  __global const GpuLight* light = &scene->lights[index];

  real cos_light;
  bool facing;
  Vec3 point_normal;
  LightSample s = sphere_cap_sample(light, scene->spheres, x, u, &cos_light, &facing, &point_normal);
  s.triangle = -1;
  s.delta = 0;
  s.emission = v3_load_global(scene->spheres[light->sphere].material.emission);
#if CLPT_SPHERE_EMISSION_TEXTURES
  /* The sampled point's emission texture, as a BSDF hit there reads it (path.cl, apply_textures). */
  s.emission = v3_mul(s.emission, sphere_emission_scale(scene->texturing, (int)light->sphere, point_normal));
#endif
  s.target = v3_add_scaled(x, s.direction, s.distance);

#if CLPT_HAS_TRIANGLE_LIGHTS
  const bool is_triangle = light->triangle != CLPT_LIGHT_SPHERE;
  /* Uniform by area: b0 = 1 - sqrt(u0), b1 = u1 sqrt(u0), b2 = the rest. Seen from either side. */
  const uint tri = is_triangle ? light->triangle : 0u;
  const real root = clpt_sqrt((real)u.u0);
  const real b1 = (real)u.u1 * root;
  const TriangleSurface point = triangle_point(&scene->triangles[tri], (real)1 - root, b1, root - b1);
  const Vec3 to_point = v3_sub(point.point, x);
  const real distance = clpt_sqrt(v3_dot(to_point, to_point));
  const Vec3 direction = v3_scale(to_point, (real)1 / distance);
  s.direction = v3_select(is_triangle, direction, s.direction);
  s.distance = is_triangle ? distance : s.distance;
  cos_light = is_triangle ? v3_dot(point.geometric, direction) : cos_light;
  facing = is_triangle || facing;
  s.sphere = is_triangle ? -1 : s.sphere;
  s.triangle = is_triangle ? (int)tri : -1;
  s.emission = v3_select(is_triangle, v3_load_global(scene->triangle_shading[tri].material.emission), s.emission);
#if CLPT_HAS_EMISSION_TEXTURES
  /* An emission texture scales the sampled point's radiance as it scales a BSDF hit's (path.cl). */
  s.emission = v3_select(is_triangle,
                         v3_mul(s.emission, triangle_emission_scale(scene->texturing, tri, (real)1 - root, b1, root - b1)),
                         s.emission);
#endif
  s.target = v3_select(is_triangle, triangle_offset_origin(&point, v3_scale(direction, (real)-1)), s.target);
#endif

  s.pdf = light_pick_pdf(s.distance, cos_light, light->cap_area, (real)light->pick_probability);
  s.pdf = facing && is_finite_real(s.pdf) ? s.pdf : (real)0;
#if CLPT_HAS_PUNCTUAL_LIGHTS
  const bool is_punctual = light->punctual != 0u;
  real punctual_distance;
  Vec3 punctual_emission;
  const Vec3 punctual_direction = punctual_light_at(light, x, &punctual_distance, &punctual_emission);
  s.direction = v3_select(is_punctual, punctual_direction, s.direction);
  s.distance = is_punctual ? punctual_distance : s.distance;
  s.sphere = is_punctual ? -1 : s.sphere;
  s.delta = is_punctual ? 1 : 0;
  s.emission = v3_select(is_punctual, punctual_emission, s.emission);
  s.target = v3_select(is_punctual, v3_add_scaled(x, punctual_direction, punctual_distance), s.target);
  s.pdf = is_punctual ? (real)light->pick_probability : s.pdf;
#endif
  return s;
}
#endif

#if CLPT_HAS_TRIANGLE_LIGHTS

/* Density with which light_sample would have chosen the direction d that hit emitting triangle
 * `shading` (geometric normal `geometric`) at distance t: its pick probability / area, converted
 * to solid angle. 0 for a triangle that is no light. */
CLPT_INLINE real triangle_light_pdf_of_hit(__global const GpuTriangleShading* shading, Vec3 geometric, Vec3 d, real t) {
  const real pdf = light_pick_pdf(t, v3_dot(geometric, d), (real)1, (real)shading->light_area_density);
  return is_finite_real(pdf) ? pdf : (real)0;
}
#endif

/* Density with which light_sample would have chosen the direction d that hit emitter `sphere` at
 * distance t with outward normal `normal` there: 0 when the sphere is no light or the point lies
 * outside its cap (a tolerance of 1e-3 of the cap's height absorbs float rounding at the rim).
 * The loop runs over the sphere lights (CLPT_LIGHT_COUNT; the generic kernel runs over the whole
 * list, whose triangle entries have an empty cap and never match). */
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
    /* `&`, not `&&`: the second test's reads behind a branch would be masked loads (maths.cl). */
    const bool in_cap = ((int)light->sphere == sphere) & (height <= (real)light->one_minus_cos_cap * (real)1.001f);
    /* The density is formed for every light and then chosen, not formed under the condition:
     * there its reads would be masked loads, which the vectoriser costs as gathers (maths.cl). */
#if CLPT_LIGHT_PICK_BY_POWER
    (void)count;
    const real candidate = light_pick_pdf(t, v3_dot(normal, d), light->cap_area, (real)light->pick_probability);
#else
    const real candidate = light_solid_angle_pdf(t, v3_dot(normal, d), light->cap_area, count);
#endif
    pdf = in_cap ? candidate : pdf;
  }
  return pdf;
}

#endif
