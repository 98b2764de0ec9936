/* bvh.cl: the ray/scene queries: closest hit (path segments) and any hit (shadow rays).
 *
 * A scene's primitives are spheres in today's loop (intersect.cl) and, when the host built one,
 * a bounding volume hierarchy (GpuBvhNode, types.h) over the triangles and, for scenes of more
 * than a few spheres, the spheres too (host: kernel_options.cpp decides, scene/bvh_build.cpp
 * builds). Both queries are written once here and called by the stage functions of path.cl, so
 * the megakernel and the wavefront traverse alike.
 *
 * Traversal: the hierarchy is 4-wide (GpuBvhNode, types.h); a node's four child boxes are tested in
 * one vector slab test (float4, double4 in the double preset), the hit children visited nearest
 * first, through a fixed stack of CLPT_BVH_STACK entries (the host refuses a tree that could need
 * more). The slab test's far distance is widened by 1 + 2 gamma(3) (Ize, "Robust BVH Ray
 * Traversal", JCGT 2013), with boxes rounded outwards on the host, so no rounding makes a ray miss
 * a box that holds its hit. A triangle leaf's triangles are read from its leaf blocks
 * (GpuTriangleBlock, types.h: four side by side, after the nodes in the same buffer), four in one
 * vector test on PoCL's CPU device (CLPT_WIDE_LEAF_TEST). Compiled only with CLPT_HAS_BVH
 * (kernel_options.cpp); without, the queries are the sphere loop alone and no traversal code
 * exists in the kernel.
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
/* The node the traversal starts at: 1 in a kernel whose triangle loop (CLPT_TRIANGLE_COUNT) tests
 * the meshes of large triangles beside the hierarchy: node 1 roots the hierarchy of the others,
 * the root's other subtree holds the loop's (kernel_options.cpp; DeviceScene::loop_triangles).
 * Else the root. */
#ifndef CLPT_BVH_ROOT
#define CLPT_BVH_ROOT 0
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
/* Four reals, one per child slot of a node: double4 in the double preset, as `real` is double. */
#if CLPT_PRECISION == CLPT_PRECISION_DOUBLE
typedef double4 real4;
typedef long4 real4_mask;
#define bvh_load4(p) convert_double4(vload4(0, (p)))
#else
typedef float4 real4;
typedef int4 real4_mask;
#define bvh_load4(p) vload4(0, (p))
#endif

/* The ray as the slab tests use it: origin and 1/d splatted over the four slots, and per axis
 * whether the direction's component is negative, which makes the upper corner the near plane.
 * Picking the planes by the ray's signs instead of min/max makes an inverted box (an empty slot,
 * types.h) a miss for every ray. */
typedef struct BoxRay {
  real4 ox, oy, oz, ix, iy, iz;
  bool neg_x, neg_y, neg_z;
  real ox1, oy1, oz1, ix1, iy1, iz1; /* the same, scalar, for one slot's box (bvh_slot_entry) */
} BoxRay;

/* 1/d per component; a zero component becomes 1/(+-1e-30), so that 0 * inf never makes a NaN. */
CLPT_INLINE Vec3 inverse_direction(Vec3 d) {
  const real tiny = (real)1e-30f;
  return v3((real)1 / (fabs(d.x) > tiny ? d.x : copysign(tiny, d.x)),
            (real)1 / (fabs(d.y) > tiny ? d.y : copysign(tiny, d.y)),
            (real)1 / (fabs(d.z) > tiny ? d.z : copysign(tiny, d.z)));
}

CLPT_INLINE BoxRay box_ray(Vec3 o, Vec3 inv) {
  BoxRay r;
  r.ox = (real4)(o.x);
  r.oy = (real4)(o.y);
  r.oz = (real4)(o.z);
  r.ix = (real4)(inv.x);
  r.iy = (real4)(inv.y);
  r.iz = (real4)(inv.z);
  r.neg_x = inv.x < (real)0;
  r.neg_y = inv.y < (real)0;
  r.neg_z = inv.z < (real)0;
  r.ox1 = o.x;
  r.oy1 = o.y;
  r.oz1 = o.z;
  r.ix1 = inv.x;
  r.iy1 = inv.y;
  r.iz1 = inv.z;
  return r;
}

/* max and min by compare and select: one instruction each where fmax and fmin add their NaN rule
 * (a compare and a blend); no NaN reaches them (1/d is finite and at least 1 in magnitude). */
CLPT_INLINE real4 bvh_max4(real4 a, real4 b) { return a > b ? a : b; }
CLPT_INLINE real4 bvh_min4(real4 a, real4 b) { return a < b ? a : b; }
CLPT_INLINE real bvh_max(real a, real b) { return a > b ? a : b; }
CLPT_INLINE real bvh_min(real a, real b) { return a < b ? a : b; }

/* Entry distances of the ray into the four child boxes of `node`, CLPT_NO_HIT for a box it misses
 * in [0, t_max): the slab test on all four slots at once. The far distance is widened by
 * 1 + 2 gamma(3) (Ize). */
CLPT_INLINE real4 bvh_node_entries(__global const GpuBvhNode* node, const BoxRay* r, real t_max) {
  const real4 lx = bvh_load4(node->lower_x), ux = bvh_load4(node->upper_x);
  const real4 ly = bvh_load4(node->lower_y), uy = bvh_load4(node->upper_y);
  const real4 lz = bvh_load4(node->lower_z), uz = bvh_load4(node->upper_z);
  const real4 tnx = ((r->neg_x ? ux : lx) - r->ox) * r->ix, tfx = ((r->neg_x ? lx : ux) - r->ox) * r->ix;
  const real4 tny = ((r->neg_y ? uy : ly) - r->oy) * r->iy, tfy = ((r->neg_y ? ly : uy) - r->oy) * r->iy;
  const real4 tnz = ((r->neg_z ? uz : lz) - r->oz) * r->iz, tfz = ((r->neg_z ? lz : uz) - r->oz) * r->iz;
  const real4 entry = bvh_max4(bvh_max4(tnx, tny), bvh_max4(tnz, (real4)((real)0)));
  const real4 far = bvh_min4(bvh_min4(tfx, tfy), tfz) * (real)1.0000004f; /* 1 + 2 gamma(3) */
  const real4_mask in = (entry <= far) & (entry < (real4)(t_max));
  return in ? entry : (real4)(CLPT_NO_HIT);
}

/* The entry distance into child `slot`'s box alone (a popped entry's test), as bvh_node_entries. */
CLPT_INLINE real bvh_slot_entry(__global const GpuBvhNode* node, uint slot, const BoxRay* r, real t_max) {
  const real lx = node->lower_x[slot], ux = node->upper_x[slot];
  const real ly = node->lower_y[slot], uy = node->upper_y[slot];
  const real lz = node->lower_z[slot], uz = node->upper_z[slot];
  const real tnx = ((r->neg_x ? ux : lx) - r->ox1) * r->ix1, tfx = ((r->neg_x ? lx : ux) - r->ox1) * r->ix1;
  const real tny = ((r->neg_y ? uy : ly) - r->oy1) * r->iy1, tfy = ((r->neg_y ? ly : uy) - r->oy1) * r->iy1;
  const real tnz = ((r->neg_z ? uz : lz) - r->oz1) * r->iz1, tfz = ((r->neg_z ? lz : uz) - r->oz1) * r->iz1;
  const real entry = bvh_max(bvh_max(tnx, tny), bvh_max(tnz, (real)0));
  const real far = bvh_min(bvh_min(tfx, tfy), tfz) * (real)1.0000004f;
  return entry <= far && entry < t_max ? entry : CLPT_NO_HIT;
}

/* Orders two (distance, slot) pairs, the nearer first: one comparator of the sorting network. */
CLPT_INLINE void bvh_order(real* ta, uint* sa, real* tb, uint* sb) {
  const bool swap = *tb < *ta;
  const real t = *ta;
  const uint s = *sa;
  *ta = swap ? *tb : *ta;
  *sa = swap ? *sb : *sa;
  *tb = swap ? t : *tb;
  *sb = swap ? s : *sb;
}

/* CLPT_WIDE_LEAF_TEST (kernel_options.h, wide_leaf_test): 1, a leaf block's four triangles tested
 * in one vector test (PoCL's CPU device: triangle_block_distances); 0, one at a time from the same
 * block (elsewhere: a GPU's lanes are rays already, and the vector test cost it a third more
 * registers in the traversing kernels, docs/performance.md). */
#ifndef CLPT_WIDE_LEAF_TEST
#define CLPT_WIDE_LEAF_TEST 1
#endif

#if CLPT_HAS_TRIANGLES && CLPT_WIDE_LEAF_TEST
/* The watertight test (triangle.cl: triangle_test_of, then triangle_test_distance) on the four
 * triangles of a leaf block (GpuTriangleBlock, types.h) at once: for each lane the same operations
 * in the same order, so the same distances bit for bit as the triangles tested one by one. The
 * ray's permutation (kx, ky, kz) picks the stored axis each coordinate of the sheared frame reads:
 * an address, where one triangle's test takes a select per coordinate. CLPT_NO_HIT in a lane
 * missed, or hit outside (0, t_max). */
CLPT_INLINE real4 triangle_block_distances(const ShearedRay* ray, __global const GpuTriangleBlock* blk, real t_max) {
#pragma OPENCL FP_CONTRACT OFF
  const real4 okx = (real4)(v3_component(ray->origin, ray->kx));
  const real4 oky = (real4)(v3_component(ray->origin, ray->ky));
  const real4 okz = (real4)(v3_component(ray->origin, ray->kz));
  const real4 az = bvh_load4(blk->v[0][ray->kz]) - okz;
  const real4 bz = bvh_load4(blk->v[1][ray->kz]) - okz;
  const real4 cz = bvh_load4(blk->v[2][ray->kz]) - okz;
  const real4 ax = (bvh_load4(blk->v[0][ray->kx]) - okx) - ray->sx * az;
  const real4 ay = (bvh_load4(blk->v[0][ray->ky]) - oky) - ray->sy * az;
  const real4 bx = (bvh_load4(blk->v[1][ray->kx]) - okx) - ray->sx * bz;
  const real4 by = (bvh_load4(blk->v[1][ray->ky]) - oky) - ray->sy * bz;
  const real4 cx = (bvh_load4(blk->v[2][ray->kx]) - okx) - ray->sx * cz;
  const real4 cy = (bvh_load4(blk->v[2][ray->ky]) - oky) - ray->sy * cz;
  const real4 u = cx * by - cy * bx;
  const real4 v = ax * cy - ay * cx;
  const real4 w = bx * ay - by * ax;
  const real4 det = u + v + w;
  const real4 t_scaled = (u * az + v * bz + w * cz) * ray->sz;
  const real4 zero = (real4)((real)0);
  const real4_mask mixed = ((u < zero) | (v < zero) | (w < zero)) & ((u > zero) | (v > zero) | (w > zero));
  const real4 t = t_scaled / det;
  const real4_mask hit = (mixed == (real4_mask)(0)) & (det != zero) & (t > zero) & (t < (real4)(t_max));
  return hit ? t : (real4)(CLPT_NO_HIT);
}
#endif

#if CLPT_HAS_TRIANGLES

/* Triangle i (the triangle buffer's index) at distance t (CLPT_NO_HIT: missed) made the closest hit
 * when it is nearer than hit->t and not triangle `skip_triangle` (a kernel with triangle lights),
 * nor cut away by its material's alpha (CLPT_HAS_ALPHA): one lane of a leaf block. */
CLPT_INLINE void bvh_triangle_lane(const SceneBuffers* scene, const ShearedRay* ray, real t, uint i,
                                   int skip_triangle, uint alpha_seed, Hit* hit) {
#if !CLPT_HAS_ALPHA
  (void)scene;
  (void)ray;
  (void)alpha_seed;
#endif
#if CLPT_HAS_TRIANGLE_LIGHTS
  bool closer = t < hit->t && (int)i != skip_triangle;
#else
  (void)skip_triangle;
  bool closer = t < hit->t;
#endif
#if CLPT_HAS_ALPHA
  /* The test again, for the barycentrics: a lane past the block's count never gets here (t is
   * CLPT_NO_HIT), so i is a triangle. */
  if (closer) closer = !alpha_cut(scene->texturing, i, triangle_test(ray, &scene->triangles[i]), alpha_seed);
#endif
  hit->t = closer ? t : hit->t;
  hit->sphere = closer ? -1 : hit->sphere;
  hit->triangle = closer ? (int)i : hit->triangle;
}
#endif

/* Walks the hierarchy for the closest hit before hit->t (any_hit: stops at the first hit, for a
 * shadow ray whose hit->t is the distance to the light). Spheres keep intersect.cl's contract:
 * t > t_min, and sphere `skip` (the one the ray leaves on its outer side) is never hit; triangle
 * `skip_triangle` (a shadow ray's sampled light triangle, which cannot hide its own point; -1:
 * none) neither, in kernels with triangle lights. With CLPT_HAS_ALPHA, a triangle hit where its
 * material's alpha cuts the surface away (alpha.cl, seed `alpha_seed`) is no hit.
 *
 * At a node, the four child boxes are tested at once (bvh_node_entries); a single hit child is
 * visited at once; of two, the nearer is visited and the other pushed (one comparison); three or
 * four are sorted by entry distance (a 5-comparator network), the nearest visited (an interior
 * child is opened next, a leaf's primitives tested), the others pushed farthest first, so that
 * they come off the stack nearest first. The two-child shortcut orders them as the network would,
 * ties included, so the walk is the same either way. A stack entry names a child slot (node << 2 | slot); popped, its
 * box is tested again against the hit->t found since it was pushed, and it is skipped when wholly
 * behind it. */
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
  const BoxRay box = box_ray(v3_unpaired(o), v3_unpaired(inverse_direction(d)));
  const ShearedRay ray = sheared_ray(o, d);
  uint stack[CLPT_BVH_STACK];
  uint depth = 0u;
  uint node = CLPT_BVH_ROOT; /* the node to open, when `open` */
  bool open = true; /* false: the entry `ref` just came off the stack */
  uint ref = 0u;
  bool done = false;
  while (!done) {
    bool leaf = false;
    uint first = 0u, count = 0u;
    if (open) {
      __global const GpuBvhNode* n = &scene->nodes[node];
      const real4 t = bvh_node_entries(n, &box, hit->t);
      /* The hit children counted, not as bits of a mask: LLVM turns a mask's one-bit test into
       * llvm.ctpop, which Oclgrind cannot run. */
      const bool h0 = t.s0 < CLPT_NO_HIT, h1 = t.s1 < CLPT_NO_HIT, h2 = t.s2 < CLPT_NO_HIT, h3 = t.s3 < CLPT_NO_HIT;
      const uint hits = (uint)h0 + (uint)h1 + (uint)h2 + (uint)h3;
      uint s0 = 0u;
      if (hits == 2u) {
        /* Two hit children, a the lower slot and b the higher: the nearer visited, the other
         * pushed; on a tie a first, as the sorting network below orders them. */
        const uint a = h0 ? 0u : (h1 ? 1u : 2u), b = h3 ? 3u : (h2 ? 2u : 1u);
        const real ta = h0 ? t.s0 : (h1 ? t.s1 : t.s2), tb = h3 ? t.s3 : (h2 ? t.s2 : t.s1);
        const bool a_first = ta <= tb;
        s0 = a_first ? a : b;
        stack[depth++] = (node << 2) | (a_first ? b : a);
      } else if (hits > 1u) {
        real t0 = t.s0, t1 = t.s1, t2 = t.s2, t3 = t.s3;
        uint s1 = 1u, s2 = 2u, s3 = 3u;
        bvh_order(&t0, &s0, &t1, &s1);
        bvh_order(&t2, &s2, &t3, &s3);
        bvh_order(&t0, &s0, &t2, &s2);
        bvh_order(&t1, &s1, &t3, &s3);
        bvh_order(&t1, &s1, &t2, &s2);
        const uint base = node << 2;
        if (t3 < CLPT_NO_HIT) stack[depth++] = base | s3;
        if (t2 < CLPT_NO_HIT) stack[depth++] = base | s2;
        stack[depth++] = base | s1;
      } else {
        s0 = h0 ? 0u : (h1 ? 1u : (h2 ? 2u : 3u));
      }
      if (hits != 0u) {
        count = n->count[s0];
        first = n->child[s0];
        leaf = count != 0u;
        node = first;
        open = !leaf;
      } else {
        open = false;
      }
    } else {
      __global const GpuBvhNode* n = &scene->nodes[ref >> 2];
      const uint slot = ref & 3u;
      /* Pushed before a nearer hit was found, and now wholly behind it: not visited. Its box is
       * tested again rather than its entry distance kept on the stack (the same answer, as the
       * entry distance does not depend on hit->t), which would double the stack, a GPU's scratch
       * memory, and measured no faster on the CPU (docs/performance.md, "Traversal"). */
      if (bvh_slot_entry(n, slot, &box, hit->t) < CLPT_NO_HIT) {
        count = n->count[slot];
        first = n->child[slot];
        leaf = count != 0u;
        node = first;
        open = !leaf;
      }
    }
    if (leaf) {
      const uint n_prims = count & CLPT_BVH_COUNT_MASK;
      if (count & CLPT_BVH_SPHERE_LEAF) {
        for (uint i = first; i < first + n_prims; ++i) {
          const real t = sphere_intersect(&scene->spheres[i], o, d, t_min);
          const bool closer = t < hit->t && (int)i != skip;
          hit->t = closer ? t : hit->t;
          hit->sphere = closer ? (int)i : hit->sphere;
          hit->triangle = closer ? -1 : hit->triangle;
        }
      } else {
#if CLPT_HAS_TRIANGLES
        /* The leaf's blocks follow the nodes (GpuTriangleBlock, types.h); `first` is the first's index. */
        __global const GpuTriangleBlock* blk = (__global const GpuTriangleBlock*)(scene->nodes + node_count) + first;
        for (uint b = 0u; b < (n_prims + 3u) >> 2; ++b, ++blk) {
          const uint i = blk->first;
#if CLPT_WIDE_LEAF_TEST
          const real4 t = triangle_block_distances(&ray, blk, hit->t);
          bvh_triangle_lane(scene, &ray, t.s0, i, skip_triangle, alpha_seed, hit);
          bvh_triangle_lane(scene, &ray, t.s1, i + 1u, skip_triangle, alpha_seed, hit);
          bvh_triangle_lane(scene, &ray, t.s2, i + 2u, skip_triangle, alpha_seed, hit);
          bvh_triangle_lane(scene, &ray, t.s3, i + 3u, skip_triangle, alpha_seed, hit);
#else
          for (uint j = 0u; j < blk->count; ++j) {
            const Vec3 v0 = v3((real)blk->v[0][0][j], (real)blk->v[0][1][j], (real)blk->v[0][2][j]);
            const Vec3 v1 = v3((real)blk->v[1][0][j], (real)blk->v[1][1][j], (real)blk->v[1][2][j]);
            const Vec3 v2 = v3((real)blk->v[2][0][j], (real)blk->v[2][1][j], (real)blk->v[2][2][j]);
            const real t = triangle_test_distance(triangle_test_of(&ray, v0, v1, v2), hit->t);
            bvh_triangle_lane(scene, &ray, t, i + j, skip_triangle, alpha_seed, hit);
          }
#endif
        }
#endif
      }
      done = any_hit && (hit->sphere >= 0 || hit->triangle >= 0);
    }
    if (!open && !done) {
      done = depth == 0u;
      ref = done ? 0u : stack[--depth];
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
