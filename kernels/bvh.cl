/* bvh.cl: the ray/scene queries: closest hit (path segments) and any hit (shadow rays).
 *
 * A scene's primitives are spheres in today's loop (intersect.cl) and, when the host built one,
 * a bounding volume hierarchy (GpuBvhNode, types.h) over the triangles and, for scenes of more
 * than a few spheres, the spheres too (host: kernel_options.cpp decides, scene/bvh_build.cpp
 * builds). Both queries are written once here and called by the stage functions of path.cl, so
 * the megakernel and the wavefront traverse alike.
 *
 * Traversal: a fixed stack of CLPT_BVH_STACK node indices (the host refuses deeper hierarchies);
 * at an interior node both children's boxes are tested and the nearer is visited first, the
 * farther pushed. The slab test's far distance is widened by 1 + 2 gamma(3) (Ize, "Robust BVH Ray
 * Traversal", JCGT 2013), with boxes rounded outwards on the host, so no rounding makes a ray miss
 * a box that holds its hit. Compiled only with CLPT_HAS_BVH (kernel_options.cpp); without, the
 * queries are the sphere loop alone and no traversal code exists in the kernel.
 *
 * Hit ids: Hit.sphere is a sphere index or -1, Hit.triangle a triangle index or -1. */
#ifndef CLPT_BVH_CL
#define CLPT_BVH_CL

#include "types.h"
#include "maths.cl"
#include "intersect.cl"
#include "triangle.cl"
#include "triangle_loop.cl"
#include "alpha.cl"

#ifndef CLPT_HAS_BVH
#define CLPT_HAS_BVH 1
#endif
#ifndef CLPT_HAS_TRIANGLES
#define CLPT_HAS_TRIANGLES 1
#endif
#ifndef CLPT_HAS_TRIANGLE_LIGHTS
#define CLPT_HAS_TRIANGLE_LIGHTS 1
#endif

/* Every buffer that holds geometry (and the lights, and the environment), as the kernels receive them. */
typedef struct SceneBuffers {
  __global const GpuSphere* spheres;
  __global const GpuLight* lights;
  __global const GpuBvhNode* nodes;
  __global const GpuTriangle* triangles;
  __global const GpuTriangleShading* triangle_shading;
  __global const GpuEnvironment* environment; /* header and data (types.h), environment.cl */
  __global const uchar* texturing; /* GpuTexturing and its sections (texture.cl); read with CLPT_HAS_TEXTURES only */
} SceneBuffers;

CLPT_INLINE SceneBuffers scene_buffers(__global const GpuSphere* spheres, __global const GpuLight* lights,
                                       __global const GpuBvhNode* nodes, __global const GpuTriangle* triangles,
                                       __global const GpuTriangleShading* triangle_shading,
                                       __global const GpuEnvironment* environment,
                                       __global const uchar* texturing) {
  SceneBuffers s;
  s.spheres = spheres;
  s.lights = lights;
  s.nodes = nodes;
  s.triangles = triangles;
  s.triangle_shading = triangle_shading;
  s.environment = environment;
  s.texturing = texturing;
  return s;
}

#if CLPT_HAS_BVH
/* Entry distance of the ray into the box, or CLPT_NO_HIT when it misses it in [0, t_max]. */
CLPT_INLINE real box_entry(__global const GpuBvhNode* node, Vec3 o, Vec3 inv_d, real t_max) {
  const real x0 = ((real)node->lower[0] - o.x) * inv_d.x, x1 = ((real)node->upper[0] - o.x) * inv_d.x;
  const real y0 = ((real)node->lower[1] - o.y) * inv_d.y, y1 = ((real)node->upper[1] - o.y) * inv_d.y;
  const real z0 = ((real)node->lower[2] - o.z) * inv_d.z, z1 = ((real)node->upper[2] - o.z) * inv_d.z;
  const real tx_near = x0 < x1 ? x0 : x1, tx_far = x0 < x1 ? x1 : x0;
  const real ty_near = y0 < y1 ? y0 : y1, ty_far = y0 < y1 ? y1 : y0;
  const real tz_near = z0 < z1 ? z0 : z1, tz_far = z0 < z1 ? z1 : z0;
  const real t_near_xy = tx_near > ty_near ? tx_near : ty_near;
  const real t_near = t_near_xy > tz_near ? t_near_xy : tz_near;
  const real t_far_xy = tx_far < ty_far ? tx_far : ty_far;
  const real t_far = (t_far_xy < tz_far ? t_far_xy : tz_far) * (real)1.0000004f; /* 1 + 2 gamma(3) */
  const real entry = t_near > (real)0 ? t_near : (real)0;
  return entry <= t_far && entry < t_max ? entry : CLPT_NO_HIT;
}

/* 1/d per component; a zero component becomes 1/(+-1e-30), so that 0 * inf never makes a NaN. */
CLPT_INLINE Vec3 inverse_direction(Vec3 d) {
  const real tiny = (real)1e-30f;
  return v3((real)1 / (fabs(d.x) > tiny ? d.x : copysign(tiny, d.x)),
            (real)1 / (fabs(d.y) > tiny ? d.y : copysign(tiny, d.y)),
            (real)1 / (fabs(d.z) > tiny ? d.z : copysign(tiny, d.z)));
}

/* Walks the hierarchy for the closest hit before hit->t (any_hit: stops at the first hit, for a
 * shadow ray whose hit->t is the distance to the light). Spheres keep intersect.cl's contract:
 * t > t_min, and sphere `skip` (the one the ray leaves on its outer side) is never hit; triangle
 * `skip_triangle` (a shadow ray's sampled light triangle, which cannot hide its own point; -1:
 * none) neither, in kernels with triangle lights. With CLPT_HAS_ALPHA, a triangle hit where its
 * material's alpha cuts the surface away (alpha.cl, seed `alpha_seed`) is no hit. */
CLPT_INLINE void bvh_traverse(const SceneBuffers* scene, uint node_count, Vec3 o, Vec3 d, real t_min,
                              int skip, int skip_triangle, bool any_hit, uint alpha_seed, Hit* hit) {
#if !CLPT_HAS_ALPHA
  (void)alpha_seed;
#endif
#if !CLPT_HAS_TRIANGLE_LIGHTS
  (void)skip_triangle; /* only a kernel with triangle lights skips a light's own triangle */
#endif
  if (node_count == 0u) return;
  /* The slab test's copies of the ray, which SLP may pair without harm (maths.cl, v3_unpaired). */
  const Vec3 o_box = v3_unpaired(o);
  const Vec3 inv_box = v3_unpaired(inverse_direction(d));
  const ShearedRay ray = sheared_ray(o, d);
  uint stack[CLPT_BVH_STACK];
  uint depth = 0u;
  uint node = 0u;
  bool done = box_entry(&scene->nodes[0], o_box, inv_box, hit->t) >= CLPT_NO_HIT;
  bool popped = false; /* the current node came off the stack */
  while (!done) {
    __global const GpuBvhNode* n = &scene->nodes[node];
    bool pop = true;
    if (popped && box_entry(n, o_box, inv_box, hit->t) >= CLPT_NO_HIT) {
      /* Pushed before a nearer hit was found, and now wholly behind it: not opened. Its box is
       * tested again rather than its entry distance kept on the stack, which would double the
       * stack (a GPU's scratch memory) for one box test per pop. */
    } else if (n->count == 0u) {
      const uint a = node + 1u, b = n->first;
      const real ta = box_entry(&scene->nodes[a], o_box, inv_box, hit->t);
      const real tb = box_entry(&scene->nodes[b], o_box, inv_box, hit->t);
      const bool hit_a = ta < CLPT_NO_HIT, hit_b = tb < CLPT_NO_HIT;
      if (hit_a || hit_b) {
        pop = false;
        const bool a_first = hit_a && (!hit_b || ta <= tb);
        node = a_first ? a : b;
        if (hit_a && hit_b) stack[depth++] = a_first ? b : a;
      }
    } else {
      const uint first = n->first;
      const uint count = n->count & CLPT_BVH_COUNT_MASK;
      if (n->count & CLPT_BVH_SPHERE_LEAF) {
        for (uint i = first; i < first + count; ++i) {
          const real t = sphere_intersect(&scene->spheres[i], o, d, t_min);
          const bool closer = t < hit->t && (int)i != skip;
          hit->t = closer ? t : hit->t;
          hit->sphere = closer ? (int)i : hit->sphere;
          hit->triangle = closer ? -1 : hit->triangle;
        }
      } else {
#if CLPT_HAS_TRIANGLES
        for (uint i = first; i < first + count; ++i) {
#if CLPT_HAS_ALPHA
          const TriangleTest test = triangle_test(&ray, &scene->triangles[i]);
          const real t = triangle_test_distance(test, hit->t);
#else
          const real t = triangle_intersect(&ray, &scene->triangles[i], hit->t);
#endif
#if CLPT_HAS_TRIANGLE_LIGHTS
          bool closer = t < hit->t && (int)i != skip_triangle;
#else
          bool closer = t < hit->t;
#endif
#if CLPT_HAS_ALPHA
          if (closer) closer = !alpha_cut(scene->texturing, i, test, alpha_seed);
#endif
          hit->t = closer ? t : hit->t;
          hit->sphere = closer ? -1 : hit->sphere;
          hit->triangle = closer ? (int)i : hit->triangle;
        }
#endif
      }
      done = any_hit && (hit->sphere >= 0 || hit->triangle >= 0);
    }
    popped = pop && !done;
    if (popped) {
      done = depth == 0u;
      node = done ? 0u : stack[--depth];
    }
  }
}
#endif

CLPT_INLINE Hit no_hit(void) {
  Hit hit;
  hit.t = CLPT_NO_HIT;
  hit.sphere = -1;
  hit.triangle = -1;
  return hit;
}

/* Closest hit over the loop's spheres, and a small mesh's triangles where they are in a loop too
 * (triangle_loop.cl), alone (loop-free once unrolled: the first half of scene_closest_hit, which
 * the lockstep megakernel runs in its own vectorised region). */
CLPT_INLINE Hit scene_loop_hit(const SceneBuffers* scene, const GpuRenderParams* params, Vec3 o, Vec3 d, int skip,
                               uint alpha_seed) {
#if defined(CLPT_TRIANGLE_COUNT) && CLPT_TRIANGLE_COUNT > 0
  Hit hit = scene_intersect(scene->spheres, params->sphere_count, o, d, params->ray_epsilon, skip);
  triangle_loop_hit(scene->triangles, scene->texturing, o, d, alpha_seed, &hit);
  return hit;
#else
  (void)alpha_seed;
  return scene_intersect(scene->spheres, params->sphere_count, o, d, params->ray_epsilon, skip);
#endif
}

/* Narrows `hit` (the loop's closest hit, or no_hit()) to the hierarchy's closest hit before hit->t:
 * the second half of scene_closest_hit. Without a hierarchy: nothing. */
CLPT_INLINE void scene_hierarchy_hit(const SceneBuffers* scene, const GpuRenderParams* params, Vec3 o, Vec3 d,
                                     int skip, uint alpha_seed, Hit* hit) {
#if CLPT_HAS_BVH
  bvh_traverse(scene, params->bvh_node_count, o, d, params->ray_epsilon, skip, -1, false, alpha_seed, hit);
#else
  (void)alpha_seed;
  (void)scene;
  (void)params;
  (void)o;
  (void)d;
  (void)skip;
  (void)hit;
#endif
}

/* Closest hit over the loop's spheres and the hierarchy (alpha_seed: alpha.cl, alpha_ray_seed). */
CLPT_INLINE Hit scene_closest_hit(const SceneBuffers* scene, const GpuRenderParams* params, Vec3 o, Vec3 d,
                                  int skip, uint alpha_seed) {
  Hit hit = scene_loop_hit(scene, params, o, d, skip, alpha_seed);
  scene_hierarchy_hit(scene, params, o, d, skip, alpha_seed, &hit);
  return hit;
}

/* Whether anything of the hierarchy lies along the ray before t_max (a shadow ray's test; the
 * loop's spheres are tested by the caller's closest hit, path.cl), not counting sphere `skip` and
 * triangle `skip_triangle` (bvh_traverse). Without a hierarchy: false. */
CLPT_INLINE bool scene_hierarchy_occluded(const SceneBuffers* scene, const GpuRenderParams* params, Vec3 o,
                                          Vec3 d, real t_max, int skip, int skip_triangle, uint alpha_seed) {
#if CLPT_HAS_BVH
  Hit hit = no_hit();
  hit.t = t_max;
  bvh_traverse(scene, params->bvh_node_count, o, d, params->ray_epsilon, skip, skip_triangle, true, alpha_seed, &hit);
  return hit.sphere >= 0 || hit.triangle >= 0;
#else
  (void)scene;
  (void)params;
  (void)o;
  (void)d;
  (void)t_max;
  (void)skip;
  (void)skip_triangle;
  (void)alpha_seed;
  return false;
#endif
}

#endif
