/* intersect.cl: ray/sphere and ray/scene closest hit.
 *
 * Float32 that stays accurate on the book's radius-1e5 walls and its unit balls alike
 * (numerics.md, measured on this scene):
 *  - Each sphere is given by a surface point s0 near the scene, the outward normal n0 there and
 *    the radius r (centre c = s0 - r n0, computed on the host in double). With e = s0 - o:
 *      c'  = |c - o|^2 - r^2 = |e|^2 - 2 r (n0 . e)          (no term of size r^2)
 *      b'  = (c - o) . d     = e . d - r (n0 . d)
 *  - The discriminant is r^2 - |l|^2 with l = (c - o) - b' d, the centre's offset from the
 *    closest point of the line (Haines et al., Ray Tracing Gems ch. 7): exact hit/miss for a
 *    small sphere far away, where b'^2 - c' cancels. On the walls r^2 - |l|^2 rounds to about
 *    r^2 2^-24, but the error of l itself is larger there (about 2 r |c - o| 2^-24).
 *  - Stable root pair q = b' + sign(b') sqrt(disc): roots q and c'/q (Numerical Recipes).
 *  - Hits closer than ray_epsilon are ignored; new rays start exactly at the hit point, with no
 *    offset along the normal (offsets leaked light at corners and darkened the unit balls).
 *  - A ray leaving a sphere's outer side cannot hit that (convex) sphere again, so the caller
 *    passes it as `skip`: no self-hit even at grazing angles, where the near-zero root's error
 *    (about 1e-6 / cos(theta) on the walls) would exceed ray_epsilon.
 * Written with selects rather than early returns, so that the scene loop is straight-line code.
 * Contract: d is unit length; returns the smallest root > t_min, or INFINITY. */
#ifndef CLPT_INTERSECT_CL
#define CLPT_INTERSECT_CL

#include "types.h"
#include "maths.cl"

typedef struct Hit {
  float t;    /* distance along the unit ray, INFINITY when nothing was hit */
  int sphere; /* index into the sphere buffer, -1 when nothing was hit */
} Hit;

CLPT_INLINE float sphere_intersect(__global const GpuSphere* sphere, Vec3 o, Vec3 d, float t_min) {
  const Vec3 n0 = v3_load_global(sphere->surface_normal);
  const float r = sphere->radius;
  const Vec3 e = v3_sub(v3_load_global(sphere->surface_point), o);
  const float c_prime = v3_dot(e, e) - 2.0f * r * v3_dot(n0, e);
  const float b_prime = v3_dot(e, d) - r * v3_dot(n0, d);
  const Vec3 l = v3_add_scaled(v3_add_scaled(e, n0, -r), d, -b_prime);
  const float disc = r * r - v3_dot(l, l);
  const float q = b_prime + copysign(sqrt(fmax(disc, 0.0f)), b_prime);
  const float root_a = q;
  const float root_b = c_prime / q;
  /* Selects, not fmin/fmax: the compiler pairs fmin/fmax of the same operands into a 2-wide
   * vector operation, which stops PoCL's vectoriser across work-items (measured: 3.3x slower). */
  const bool a_first = root_a < root_b;
  const float t_near = a_first ? root_a : root_b;
  const float t_far = a_first ? root_b : root_a;
  const float t_pick = t_near > t_min ? t_near : t_far;
  const float t = t_pick > t_min ? t_pick : INFINITY;
  /* A miss: no real root, or outside the sphere and moving away (both roots negative). */
  const bool miss = disc < 0.0f || (c_prime > 0.0f && b_prime < 0.0f);
  return miss ? INFINITY : t;
}

/* Closest hit over all spheres but `skip` (-1: none); a linear scan, the book's scenes have 8.
 * A scene-specialised build fixes CLPT_SPHERE_COUNT, so the loop unrolls into straight-line code
 * (which PoCL can vectorise across work-items); the generic build reads the count at run time. */
CLPT_INLINE Hit scene_intersect(__global const GpuSphere* spheres, uint sphere_count, Vec3 o, Vec3 d,
                                float t_min, int skip) {
  Hit hit;
  hit.t = INFINITY;
  hit.sphere = -1;
#ifdef CLPT_SPHERE_COUNT
  (void)sphere_count;
#pragma unroll
  for (uint i = 0; i < CLPT_SPHERE_COUNT; ++i) {
#else
  for (uint i = 0; i < sphere_count; ++i) {
#endif
    const float t = sphere_intersect(&spheres[i], o, d, t_min);
    const bool closer = t < hit.t && (int)i != skip;
    hit.t = closer ? t : hit.t;
    hit.sphere = closer ? (int)i : hit.sphere;
  }
  return hit;
}

/* Outward unit normal at the hit point o + t d: (p - c) / r = n0 + (t d - e) / r, which keeps
 * full precision for huge r (it tends to n0). */
CLPT_INLINE Vec3 sphere_normal_at(__global const GpuSphere* sphere, Vec3 o, Vec3 d, float t) {
  const Vec3 e = v3_sub(v3_load_global(sphere->surface_point), o);
  const Vec3 offset = v3_scale(v3_sub(v3_scale(d, t), e), 1.0f / sphere->radius);
  return v3_normalize(v3_add(v3_load_global(sphere->surface_normal), offset));
}

#endif
