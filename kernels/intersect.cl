/* intersect.cl: ray/sphere and ray/scene closest hit.
 *
 * Float32 that stays accurate on the book's radius-1e5 walls and its unit balls alike
 * (docs/numerics.md, measured on this scene):
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
 * The fast preset drops the Haines discriminant for b'^2 - c' (exact enough on the book's
 * scenes, wrong for a small sphere far away). The textbook form with the centre c = s0 - r n0,
 * b = (c - o).d and disc = b^2 - (|c - o|^2 - r^2) is kept for measurement only: on the
 * radius-1e5 walls its terms are about 1e10, of which float keeps about 1e3 absolute, so the
 * ceiling moves by millimetres and covers much of the 0.01-high light cap: the book's image comes
 * out 11% too dark (README "Precision presets").
 * Contract: d is unit length; returns the smallest root > t_min, or CLPT_NO_HIT. */
#ifndef CLPT_INTERSECT_CL
#define CLPT_INTERSECT_CL

#include "types.h"
#include "maths.cl"

/* The sphere's geometry in `real`: the double preset adds the float remainders (types.h); y is
 * read with CLPT_Y_OF (maths.cl: SLP would pair it with x). */
#if CLPT_PRECISION == CLPT_PRECISION_DOUBLE
CLPT_INLINE Vec3 sphere_surface_point(__global const GpuSphere* s) {
  return v3((real)s->surface_point[0] + (real)s->surface_point_lo[0],
            (real)CLPT_Y_OF(s->surface_point) + (real)CLPT_Y_OF(s->surface_point_lo),
            (real)s->surface_point[2] + (real)s->surface_point_lo[2]);
}
CLPT_INLINE Vec3 sphere_surface_normal(__global const GpuSphere* s) {
  return v3((real)s->surface_normal[0] + (real)s->surface_normal_lo[0],
            (real)CLPT_Y_OF(s->surface_normal) + (real)CLPT_Y_OF(s->surface_normal_lo),
            (real)s->surface_normal[2] + (real)s->surface_normal_lo[2]);
}
CLPT_INLINE real sphere_radius(__global const GpuSphere* s) { return (real)s->radius + (real)s->radius_lo; }
#else
CLPT_INLINE Vec3 sphere_surface_point(__global const GpuSphere* s) { return v3_load_sphere_field(s->surface_point); }
CLPT_INLINE Vec3 sphere_surface_normal(__global const GpuSphere* s) { return v3_load_sphere_field(s->surface_normal); }
CLPT_INLINE real sphere_radius(__global const GpuSphere* s) { return s->radius; }
#endif

/* CLPT_HIT_CENTRE (the host's choice, kernel_options.cpp: the CPU's lockstep megakernel with every
 * sphere in the unrolled loop): the loop carries the closest sphere's c - o, which the robust test computes
 * anyway, by three selects per sphere, and the shading takes the normal from it instead of
 * gathering the hit sphere's surface point, normal and radius (seven gathers per path and
 * segment, slow on CPUs; measured 1.19x the paths/s of the book's image on an AMD EPYC Zen 4).
 * normalize(t d - (c - o)) is sphere_normal_at's normal to float rounding: the book's image comes
 * out bit for bit the same, and nee or specular renders differ in a few pixels (160x120, 16 spp:
 * raw RMSE 3e-10 to 3e-5). */
#ifndef CLPT_HIT_CENTRE
#define CLPT_HIT_CENTRE 0
#endif
typedef struct Hit {
  real t;       /* distance along the unit ray, CLPT_NO_HIT when nothing was hit */
  int sphere;   /* index into the sphere buffer, -1 when no sphere was hit */
  int triangle; /* index into the triangle buffer, -1 when no triangle was hit (bvh.cl) */
  CLPT_ABI_PAD(int, 2)
#if CLPT_HIT_CENTRE
  Vec3 centre_offset; /* c - o of the hit sphere, the ray's origin to the centre (world units) */
#endif
} Hit;

/* Which formula (kernel_options.cpp decides, from the precision preset):
 *   CLPT_INTERSECT_CENTRE     textbook, centre-based (measured only: README "Precision presets")
 *   CLPT_INTERSECT_SURFACE    s0/n0 form, disc = b'^2 - c'
 *   CLPT_INTERSECT_ROBUST     s0/n0 form, disc = r^2 - |l|^2 (Haines) */
#define CLPT_INTERSECT_CENTRE 0
#define CLPT_INTERSECT_SURFACE 1
#define CLPT_INTERSECT_ROBUST 2
#ifndef CLPT_INTERSECT
#define CLPT_INTERSECT CLPT_INTERSECT_ROBUST
#endif

#if CLPT_INTERSECT == CLPT_INTERSECT_CENTRE
CLPT_INLINE real sphere_intersect(__global const GpuSphere* sphere, Vec3 o, Vec3 d, real t_min) {
  const real r = sphere_radius(sphere);
  const Vec3 centre = v3_add_scaled(sphere_surface_point(sphere), sphere_surface_normal(sphere), -r);
  const Vec3 oc = v3_sub(centre, o);
  const real b = v3_dot(oc, d);
  const real disc = b * b - v3_dot(oc, oc) + r * r;
  const real root = clpt_sqrt(fmax(disc, (real)0));
  const real t_near = b - root;
  const real t_far = b + root;
  const real t_pick = t_near > t_min ? t_near : t_far;
  return disc < (real)0 || t_pick <= t_min ? CLPT_NO_HIT : t_pick;
}
#else
/* sphere_intersect, also storing c - o, the ray's origin to the sphere's centre, in *centre_offset. */
CLPT_INLINE real sphere_intersect_centred(__global const GpuSphere* sphere, Vec3 o, Vec3 d, real t_min,
                                          Vec3* centre_offset) {
  const Vec3 n0 = sphere_surface_normal(sphere);
  const real r = sphere_radius(sphere);
  const Vec3 e = v3_sub(sphere_surface_point(sphere), o);
  const real c_prime = v3_dot(e, e) - (real)2 * r * v3_dot(n0, e);
  const real b_prime = v3_dot(e, d) - r * v3_dot(n0, d);
  *centre_offset = v3_add_scaled(e, n0, -r);
#if CLPT_INTERSECT == CLPT_INTERSECT_SURFACE
  const real disc = b_prime * b_prime - c_prime;
#else
  const Vec3 l = v3_add_scaled(*centre_offset, d, -b_prime);
  const real disc = r * r - v3_dot(l, l);
#endif
  const real q = b_prime + copysign(clpt_sqrt(fmax(disc, (real)0)), b_prime);
  const real root_a = q;
  const real root_b = c_prime / q;
  /* Selects, not fmin/fmax: the compiler pairs fmin/fmax of the same operands into a 2-wide
   * vector operation, which stops PoCL's vectoriser across work-items (measured: 3.3x slower). */
  const bool a_first = b_prime < (real)0;
  const real t_near = a_first ? root_a : root_b;
  const real t_far = a_first ? root_b : root_a;
  const real t_pick = t_near > t_min ? t_near : t_far;
  const real t = t_pick > t_min ? t_pick : CLPT_NO_HIT;
  /* A miss: no real root, or outside the sphere and moving away (both roots negative). */
  const bool miss = disc < (real)0 || (c_prime > (real)0 && b_prime < (real)0);
  return miss ? CLPT_NO_HIT : t;
}
CLPT_INLINE real sphere_intersect(__global const GpuSphere* sphere, Vec3 o, Vec3 d, real t_min) {
  Vec3 unused;
  return sphere_intersect_centred(sphere, o, d, t_min, &unused);
}
#endif

/* Closest hit over the loop's spheres but `skip` (-1: none); a linear scan, the book's scenes
 * have 8. A scene of more than a few spheres puts them in the hierarchy instead (bvh.cl), and its
 * specialised kernel fixes CLPT_SPHERE_COUNT at 0.
 * A scene-specialised build fixes CLPT_SPHERE_COUNT. With CLPT_UNROLL_SCENE_LOOPS (the host's
 * choice for CPUs, kernel_options.cpp) the loop unrolls into straight-line code, which PoCL can
 * vectorise across work-items; without (GPUs) it stays a loop, whose one sphere at a time needs
 * fewer live registers than eight intersections scheduled side by side. The generic build reads
 * the count at run time. Either way the spheres are visited in index order: the same hit. */
#ifndef CLPT_UNROLL_SCENE_LOOPS
#define CLPT_UNROLL_SCENE_LOOPS 1
#endif
CLPT_INLINE Hit scene_intersect(__global const GpuSphere* spheres, uint sphere_count, Vec3 o, Vec3 d,
                                real t_min, int skip) {
  Hit hit;
  hit.t = CLPT_NO_HIT;
  hit.sphere = -1;
  hit.triangle = -1;
#if CLPT_HIT_CENTRE
  hit.centre_offset = v3_splat((real)1);
#endif
#ifdef CLPT_SPHERE_COUNT
  (void)sphere_count;
#if CLPT_UNROLL_SCENE_LOOPS
#pragma unroll
#else
#pragma unroll 1
#endif
  for (uint i = 0; i < CLPT_SPHERE_COUNT; ++i) {
#else
  for (uint i = 0; i < sphere_count; ++i) {
#endif
    const real t_min_chained = hit.t < (real)0 ? hit.t : t_min;
#if CLPT_HIT_CENTRE
    Vec3 centre_offset;
    const real t = sphere_intersect_centred(&spheres[i], o, d, t_min_chained, &centre_offset);
#else
    const real t = sphere_intersect(&spheres[i], o, d, t_min_chained);
#endif
    const bool closer = t < hit.t && (int)i != skip;
    hit.t = closer ? t : hit.t;
    hit.sphere = closer ? (int)i : hit.sphere;
#if CLPT_HIT_CENTRE
    hit.centre_offset = v3_select(closer, centre_offset, hit.centre_offset);
#endif
  }
  return hit;
}

/* A sphere's surface geometry in `real` (the accessors above). */
typedef struct SphereGeometry {
  Vec3 surface_point;  /* s0 */
  Vec3 surface_normal; /* n0 */
  real radius;
  CLPT_ABI_PAD(real, 3)
} SphereGeometry;

CLPT_INLINE SphereGeometry sphere_geometry_of(__global const GpuSphere* s) {
  SphereGeometry g;
  g.surface_point = sphere_surface_point(s);
  g.surface_normal = sphere_surface_normal(s);
  g.radius = sphere_radius(s);
  return g;
}

/* Sphere `index`'s geometry, index in [0, sphere count). Where gathers are slow (CLPT_NO_FAST_GATHER,
 * maths.cl) by selects over the loop's spheres, whose reads are the same for every work-item;
 * elsewhere one indexed read of each field. The same values either way. */
CLPT_INLINE SphereGeometry sphere_geometry(__global const GpuSphere* spheres, int index) {
#if CLPT_NO_FAST_GATHER && defined(CLPT_SPHERE_COUNT)
  SphereGeometry g = sphere_geometry_of(&spheres[0]);
#pragma unroll
  for (uint i = 1u; i < CLPT_SPHERE_COUNT; ++i) {
    const SphereGeometry c = sphere_geometry_of(&spheres[i]);
    const bool pick = index == (int)i;
    g.surface_point = v3_select(pick, c.surface_point, g.surface_point);
    g.surface_normal = v3_select(pick, c.surface_normal, g.surface_normal);
    g.radius = pick ? c.radius : g.radius;
  }
  return g;
#else
  return sphere_geometry_of(&spheres[index]);
#endif
}

/* Outward unit normal at the hit point o + t d: (p - c) / r = n0 + (t d - e) / r, which keeps
 * full precision for huge r (it tends to n0). */
CLPT_INLINE Vec3 sphere_normal_at(const SphereGeometry* sphere, Vec3 o, Vec3 d, real t) {
  const Vec3 e = v3_sub(sphere->surface_point, o);
  const Vec3 offset = v3_scale(v3_sub(v3_scale(d, t), e), (real)1 / sphere->radius);
  return v3_normalize(v3_add(sphere->surface_normal, offset));
}

#endif
