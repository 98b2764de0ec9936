/* triangle.cl: watertight ray/triangle intersection and what shading needs at a triangle hit.
 *
 * The test follows the description in Woop, Benthin and Wald, "Watertight Ray/Triangle
 * Intersection" (JCGT 2(1), 2013): the ray is made the +z axis of a sheared frame (its largest
 * direction component becomes z, the other two are sheared to 0), the vertices are moved into
 * that frame relative to the origin, and the hit is decided by the signs of the three 2D edge
 * functions U, V, W of the projected triangle. Every ray forms the edge function of an edge from
 * the same two projected vertices in the same order, whichever triangle it belongs to, so two
 * triangles sharing an edge (or a vertex) get the same value there with opposite orientation:
 * no ray passes between them. An edge function of exactly 0 counts as inside for both, so a ray
 * through a shared edge hits both (the closer-or-equal one wins), never neither. The paper
 * recomputes exact-zero edge functions in double; that fallback only decides which of the two
 * triangles reports the hit, so it is left out (fp64 is optional in OpenCL).
 *
 * Coordinates are camera-relative floats (types.h), as the spheres': a triangle far from the
 * world origin costs no precision, only one far from the camera does (docs/numerics.md).
 * Self-intersection: the hit point is recomputed from the barycentrics, with pbrt's bound on its
 * rounding error (gamma(7) sum |b_i v_i|, Pharr, Jakob, Humphreys, "Physically Based Rendering",
 * 3rd ed., 3.9), and a new ray starts from it offset along the geometric normal by that bound
 * towards the side it leaves on; triangles are then intersected for t > 0 with no epsilon at all.
 * Written with selects so that a leaf's loop body is straight-line code. */
#ifndef CLPT_TRIANGLE_CL
#define CLPT_TRIANGLE_CL

#include "types.h"
#include "maths.cl"
#include "texture.cl"

/* A ray in the sheared frame of the watertight test, set up once per ray. */
typedef struct ShearedRay {
  int kx, ky, kz;    /* the permutation: kz is the largest |d| component */
  real sx, sy, sz;   /* shear -d_kx/d_kz, -d_ky/d_kz and the scale 1/d_kz */
  Vec3 origin;
  CLPT_ABI_PAD(int, 1)
} ShearedRay;

CLPT_INLINE real v3_component(Vec3 v, int k) { return k == 0 ? v.x : (k == 1 ? v.y : v.z); }

CLPT_INLINE ShearedRay sheared_ray(Vec3 o, Vec3 d) {
  ShearedRay r;
#if defined(CLPT_TRIANGLE_COUNT) && CLPT_TRIANGLE_COUNT > 0
  /* z's magnitude by a select, not fabs: LLVM's SLP vectoriser pairs two like fabs into a
   * <2 x float>, which stops PoCL's work-item vectoriser where this runs vectorised (the triangle
   * loop, triangle_loop.cl). The same values. */
  const real ax = fabs(d.x), ay = fabs(d.y), az = d.z < (real)0 ? -d.z : d.z;
#else
  const real ax = fabs(d.x), ay = fabs(d.y), az = fabs(d.z);
#endif
  const int kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
  int kx = kz == 2 ? 0 : kz + 1;
  int ky = kx == 2 ? 0 : kx + 1;
  /* Keep the winding: swap x and y when the ray points along -z of the frame. */
  const bool swap = v3_component(d, kz) < (real)0;
  const int tmp = kx;
  kx = swap ? ky : kx;
  ky = swap ? tmp : ky;
  r.kx = kx;
  r.ky = ky;
  r.kz = kz;
  const real dz = v3_component(d, kz);
  r.sx = v3_component(d, kx) / dz;
  r.sy = v3_component(d, ky) / dz;
  r.sz = (real)1 / dz;
  r.origin = o;
  return r;
}

/* The three scaled barycentrics (edge functions) and the scaled distance of one triangle. */
typedef struct TriangleTest {
  real u, v, w; /* edge functions: the barycentrics of v0, v1, v2 times det */
  real det;     /* u + v + w */
  real t_scaled; /* distance times det */
  CLPT_ABI_PAD(int, 3)
} TriangleTest;

/* The test against the triangle of vertices v0, v1, v2 (triangle_test reads them from the buffer;
 * triangle_loop.cl reads them its own way). */
CLPT_INLINE TriangleTest triangle_test_of(const ShearedRay* ray, Vec3 v0, Vec3 v1, Vec3 v2) {
  /* No fused multiply-add here: the edge function of an edge is the exact negation of its
   * neighbour's only when both products are rounded alike (fma(a, b, -c d) is not -fma(c, d, -a b));
   * with contraction, 2% of the rays aimed at a box's edges escaped it (BvhTraversal tests). */
#pragma OPENCL FP_CONTRACT OFF
  const Vec3 a = v3_sub(v0, ray->origin);
  const Vec3 b = v3_sub(v1, ray->origin);
  const Vec3 c = v3_sub(v2, ray->origin);
  const real az = v3_component(a, ray->kz), bz = v3_component(b, ray->kz), cz = v3_component(c, ray->kz);
  const real ax = v3_component(a, ray->kx) - ray->sx * az, ay = v3_component(a, ray->ky) - ray->sy * az;
  const real bx = v3_component(b, ray->kx) - ray->sx * bz, by = v3_component(b, ray->ky) - ray->sy * bz;
  const real cx = v3_component(c, ray->kx) - ray->sx * cz, cy = v3_component(c, ray->ky) - ray->sy * cz;
  TriangleTest r;
  r.u = cx * by - cy * bx; /* opposite v0: weight of v0 */
  r.v = ax * cy - ay * cx; /* weight of v1 */
  r.w = bx * ay - by * ax; /* weight of v2 */
  r.det = r.u + r.v + r.w;
  r.t_scaled = (r.u * az + r.v * bz + r.w * cz) * ray->sz;
  return r;
}

CLPT_INLINE TriangleTest triangle_test(const ShearedRay* ray, __global const GpuTriangle* tri) {
  return triangle_test_of(ray, v3_load_global(tri->v0), v3_load_global(tri->v1), v3_load_global(tri->v2));
}

/* Distance along the ray when test r is a hit at t in (0, t_max), else CLPT_NO_HIT. */
CLPT_INLINE real triangle_test_distance(TriangleTest r, real t_max) {
  const bool mixed = (r.u < (real)0 || r.v < (real)0 || r.w < (real)0) && (r.u > (real)0 || r.v > (real)0 || r.w > (real)0);
  const real t = r.t_scaled / r.det;
  const bool hit = !mixed && r.det != (real)0 && t > (real)0 && t < t_max;
  return hit ? t : CLPT_NO_HIT;
}

/* Distance to the triangle along the ray when it is hit at t in (0, t_max), else CLPT_NO_HIT. */
CLPT_INLINE real triangle_intersect(const ShearedRay* ray, __global const GpuTriangle* tri, real t_max) {
  return triangle_test_distance(triangle_test(ray, tri), t_max);
}

/* A triangle hit as shading sees it. */
typedef struct TriangleSurface {
  Vec3 point;       /* from the barycentrics, camera-relative */
  Vec3 geometric;   /* unit geometric normal (v1 - v0) x (v2 - v0) */
  Vec3 shading;     /* unit shading normal: interpolated when the mesh has normals, else geometric */
  real error;       /* bound on |point - exact point| per coordinate, world units */
#if CLPT_HAS_TEXTURES
  real b1, b2;      /* barycentrics of v1 and v2 (texture coordinates, texture.cl) */
#endif
  CLPT_ABI_PAD(int, 3)
} TriangleSurface;

/* The point of triangle tri at barycentrics (b0, b1, b2), with its error bound and the geometric
 * normal; the shading normal is left the geometric one. Hits (triangle_surface) and light
 * samples (light.cl) both take their points from here, so both offset rays alike. */
CLPT_INLINE TriangleSurface triangle_point(__global const GpuTriangle* tri, real b0, real b1, real b2) {
  /* v3_load_sphere_field (maths.cl): y read apart where this runs vectorised (the triangle loop). */
  const Vec3 p0 = v3_load_sphere_field(tri->v0), p1 = v3_load_sphere_field(tri->v1), p2 = v3_load_sphere_field(tri->v2);
  TriangleSurface s;
  s.point = v3_add(v3_add(v3_scale(p0, b0), v3_scale(p1, b1)), v3_scale(p2, b2));
  /* gamma(7) = 7 u / (1 - 7 u), u the unit roundoff of `real`; times the sum of |b_i p_i|. */
  const real gamma7 = sizeof(real) == 8 ? (real)7.8e-16 : (real)4.2e-7f;
  const Vec3 abs_sum = v3(fabs(b0 * p0.x) + fabs(b1 * p1.x) + fabs(b2 * p2.x),
                          fabs(b0 * p0.y) + fabs(b1 * p1.y) + fabs(b2 * p2.y),
                          fabs(b0 * p0.z) + fabs(b1 * p1.z) + fabs(b2 * p2.z));
  s.error = gamma7 * (abs_sum.x > abs_sum.y ? (abs_sum.x > abs_sum.z ? abs_sum.x : abs_sum.z)
                                            : (abs_sum.y > abs_sum.z ? abs_sum.y : abs_sum.z));
  const Vec3 e1 = v3_sub(p1, p0), e2 = v3_sub(p2, p0);
  s.geometric = v3_normalize(v3(e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x));
  s.shading = s.geometric;
#if CLPT_HAS_TEXTURES
  s.b1 = b1;
  s.b2 = b2;
#endif
  return s;
}

CLPT_INLINE TriangleSurface triangle_surface(Vec3 o, Vec3 d, __global const GpuTriangle* tri,
                                             __global const GpuTriangleShading* shading) {
  const ShearedRay ray = sheared_ray(o, d);
  const TriangleTest r = triangle_test(&ray, tri);
  const real inv = r.det != (real)0 ? (real)1 / r.det : (real)0;
  const real b0 = r.u * inv, b1 = r.v * inv, b2 = r.w * inv;
  TriangleSurface s = triangle_point(tri, b0, b1, b2);
  const Vec3 interpolated = v3_add(v3_add(v3_scale(v3_load_sphere_field(shading->normal0), b0),
                                          v3_scale(v3_load_sphere_field(shading->normal1), b1)),
                                   v3_scale(v3_load_sphere_field(shading->normal2), b2));
  const real length2 = v3_dot(interpolated, interpolated);
  const bool use_interpolated = shading->has_normals != 0u && length2 > (real)1e-12f;
  s.shading = v3_select(use_interpolated, v3_scale(interpolated, (real)1 / clpt_sqrt(use_interpolated ? length2 : (real)1)),
                        s.geometric);
  return s;
}

/* Origin for a ray leaving the triangle point p along `dir`: moved off the plane along the
 * geometric normal, to dir's side, by 2x the bound on p's error in the normal's direction (so the
 * ray's origin is strictly on its side of the exact plane, and a t > 0 test cannot find the
 * triangle it leaves; pbrt 3.9.5 adds a further rounding step that the factor 2 covers). */
CLPT_INLINE Vec3 triangle_offset_origin(const TriangleSurface* s, Vec3 dir) {
  const Vec3 n = s->geometric;
  const real along = (real)2 * s->error * (fabs(n.x) + fabs(n.y) + fabs(n.z));
  return v3_add_scaled(s->point, n, v3_dot(dir, n) > (real)0 ? along : -along);
}

#endif
