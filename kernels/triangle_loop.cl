/* triangle_loop.cl: a small mesh's triangles tested in an unrolled loop, with no hierarchy.
 *
 * CLPT_TRIANGLE_COUNT (the host's choice, kernel_options.cpp: a specialised kernel with unrolled
 * scene loops, i.e. on CPUs, whose scene has at most kMaxLoopTriangles triangles and all its
 * spheres in the sphere loop, scene/loop_spheres.h) fixes how many triangles every ray tests,
 * one after the other, in index order, as the sphere loop tests its spheres (intersect.cl). Each
 * test is triangle.cl's watertight one, written with selects: unrolled, the loop is straight-line
 * code, whose triangle reads are the same for every work-item, so PoCL vectorises it across
 * paths like the sphere loop (the lockstep megakernel then has no scalar region at all). A
 * kernel with this loop compiles no traversal (CLPT_HAS_BVH=0); the triangles keep the order
 * the host's hierarchy build gave them, which only decides which of two hits at exactly the
 * same distance is reported.
 *
 * Closest hit: triangle_loop_hit narrows the sphere loop's hit. Shadow rays: triangle_loop_blocked
 * (next-event estimation, path.cl), with the tests independent of each other (no closest hit
 * carried from one to the next). */
#ifndef CLPT_TRIANGLE_LOOP_CL
#define CLPT_TRIANGLE_LOOP_CL

#include "types.h"
#include "maths.cl"
#include "intersect.cl"
#include "triangle.cl"
#include "alpha.cl"

#if defined(CLPT_TRIANGLE_COUNT) && CLPT_TRIANGLE_COUNT > 0
/* A vertex with y read apart (maths.cl, CLPT_Y_APART): the loop's reads are the same for every
 * work-item, and LLVM's SLP vectoriser pairs adjacent ones into <2 x float>, which stops PoCL's
 * work-item vectoriser ("instruction return type cannot be vectorized"). */
#define CLPT_TRIANGLE_LOOP_VERTEX(v) v3((real)(v)[0], (real)CLPT_Y_APART(v), (real)(v)[2])
/* Triangle tri's distance along the ray (triangle_intersect). */
CLPT_INLINE real triangle_loop_test(const ShearedRay* ray, __global const GpuTriangle* tri, real t_max) {
  return triangle_test_distance(triangle_test_of(ray, CLPT_TRIANGLE_LOOP_VERTEX(tri->v0),
                                                 CLPT_TRIANGLE_LOOP_VERTEX(tri->v1), CLPT_TRIANGLE_LOOP_VERTEX(tri->v2)),
                                t_max);
}

/* The watertight test of triangle tri (triangle_test_of) with its vertices read the loop's way. */
CLPT_INLINE TriangleTest triangle_loop_edges(const ShearedRay* ray, __global const GpuTriangle* tri) {
  return triangle_test_of(ray, CLPT_TRIANGLE_LOOP_VERTEX(tri->v0), CLPT_TRIANGLE_LOOP_VERTEX(tri->v1),
                          CLPT_TRIANGLE_LOOP_VERTEX(tri->v2));
}

/* Narrows *hit to the closest triangle before hit->t (t > 0, triangle.cl's contract); with
 * CLPT_HAS_ALPHA not where the triangle's alpha cuts it away (alpha.cl, seed alpha_seed). */
CLPT_INLINE void triangle_loop_hit(__global const GpuTriangle* triangles, __global const uchar* texturing, Vec3 o,
                                   Vec3 d, uint alpha_seed, Hit* hit) {
  const ShearedRay ray = sheared_ray(o, d);
#if !CLPT_HAS_ALPHA
  (void)texturing;
  (void)alpha_seed;
#endif
#pragma unroll
  for (uint i = 0u; i < CLPT_TRIANGLE_COUNT; ++i) {
#if CLPT_HAS_ALPHA
    const TriangleTest test = triangle_loop_edges(&ray, &triangles[i]);
    const real t = triangle_test_distance(test, hit->t);
    bool closer = t < hit->t;
    if (closer) closer = !alpha_cut(texturing, i, test, alpha_seed);
#else
    const real t = triangle_loop_test(&ray, &triangles[i], hit->t);
    const bool closer = t < hit->t;
#endif
    hit->t = closer ? t : hit->t;
    hit->sphere = closer ? -1 : hit->sphere;
    hit->triangle = closer ? (int)i : hit->triangle;
  }
}

/* Whether a triangle but skip_triangle (-1: none) lies along the ray in (0, t_max) (with
 * CLPT_HAS_ALPHA: and is there, alpha.cl). */
CLPT_INLINE bool triangle_loop_blocked(__global const GpuTriangle* triangles, __global const uchar* texturing, Vec3 o,
                                       Vec3 d, real t_max, int skip_triangle, uint alpha_seed) {
  const ShearedRay ray = sheared_ray(o, d);
  int blocked = 0;
#if !CLPT_HAS_ALPHA
  (void)texturing;
  (void)alpha_seed;
#endif
#pragma unroll
  for (uint i = 0u; i < CLPT_TRIANGLE_COUNT; ++i) {
#if CLPT_HAS_ALPHA
    const TriangleTest test = triangle_loop_edges(&ray, &triangles[i]);
    const real t = triangle_test_distance(test, t_max);
    bool in_way = t < t_max && (int)i != skip_triangle;
    if (in_way) in_way = !alpha_cut(texturing, i, test, alpha_seed);
    blocked |= (int)in_way;
#else
    const real t = triangle_loop_test(&ray, &triangles[i], t_max);
    blocked |= (int)(t < t_max) & (int)((int)i != skip_triangle); /* no short-circuit: straight-line code */
#endif
  }
  return blocked != 0;
}
#endif

#endif
