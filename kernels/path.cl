/* path.cl: the stages of one path, written once and called by every execution form.
 *
 *   path_begin      camera sample -> PathState with the camera ray          (ray generation)
 *   path_intersect  PathState ray -> Hit                                    (intersection)
 *   path_shade      PathState + Hit -> emission added, next ray or ended    (shading)
 *
 * Estimators (CLPT_ESTIMATOR_*, types.h):
 *  - book: no next-event estimation; a path gains light only when it hits an emitter, which
 *    ends it; a miss ends it (black background).
 *  - nee: at every Lambertian, Phong or Pbr vertex that may still scatter, one shadow ray towards a
 *    point sampled on a light (light.cl); its contribution and that of a BSDF-sampled ray hitting
 *    the light are weighted by the power heuristic (Veach's MIS, beta = 2), so the two strategies
 *    together count every light path once. Glass and the mirror are specular: no shadow ray
 *    there, and a light hit after them (or by the camera ray) has weight 1; so are a Pbr surface's
 *    delta lobes (roughness below 0.0316, bsdf_pbr.cl). Punctual lights are reached by the
 *    shadow ray alone (weight 1, no BSDF-sampled counterpart). Emitting triangles
 *    are lights like the spheres' caps (CLPT_HAS_TRIANGLE_LIGHTS, light.cl); without that
 *    feature the scene has none.
 *  - either: a ray that escapes sees the environment (CLPT_HAS_ENVIRONMENT, environment.cl), else
 *    black; under nee an environment image is a light like the others (sampled, and an escaping
 *    BSDF-sampled ray weighted against its density).
 * Segment `bounce` = 0 is the camera ray; at most max_bounces scattering events follow, and
 * emission found at the end of the last segment still counts. A shadow ray from a vertex that may
 * scatter is the same segment as the BSDF ray it competes with, so both estimators sum the same
 * path lengths and converge to the same image. Russian roulette (rr_from) ends a path at a
 * scattering event from bounce rr_from on with probability 1 - q, q = min(1, max throughput),
 * and divides the survivors by q: the expectation is unchanged.
 *
 * Specialisation (decided on the host in kernel_options.cpp, one place): CLPT_HAS_PHONG,
 * CLPT_HAS_GLASS, CLPT_HAS_MIRROR, CLPT_HAS_PBR (bsdf_pbr.cl), CLPT_HAS_PBR_TRANSMISSION and
 * CLPT_HAS_PBR_VOLUME (a thickness > 0: refraction into the volume, Beer's law inside it),
 * CLPT_HAS_RR, CLPT_HAS_TRIANGLES (triangle shading),
 * CLPT_HAS_BVH (traversal, bvh.cl), CLPT_HAS_TRIANGLE_LIGHTS (light.cl), CLPT_HAS_ENVIRONMENT
 * (environment.cl), CLPT_HAS_TEXTURES (texture.cl, apply_textures below; CLPT_HAS_VERTEX_COLORS,
 * vertex_colors.cl, in it) and CLPT_HAS_ALPHA
 * (alpha.cl: MASK and BLEND surfaces cut out inside the ray queries) compile those in;
 * CLPT_ESTIMATOR fixes the estimator (the generic kernel reads params->estimator at run time). */
#ifndef CLPT_PATH_CL
#define CLPT_PATH_CL

#include "types.h"
#include "maths.cl"
#include "path_state.h"
#include "rng.cl"
#include "sampler.cl"
#include "camera.cl"
#include "intersect.cl"
#include "bvh.cl"
#include "bsdf.cl"
#include "bsdf_pbr.cl"
#include "texture.cl"
#include "vertex_colors.cl"
#include "light.cl"
#include "environment.cl"

#ifndef CLPT_HAS_PHONG
#define CLPT_HAS_PHONG 1
#endif
#ifndef CLPT_HAS_GLASS
#define CLPT_HAS_GLASS 1
#endif
#ifndef CLPT_HAS_RR
#define CLPT_HAS_RR 1
#endif
#ifndef CLPT_HAS_MIRROR
#define CLPT_HAS_MIRROR 1
#endif
#ifndef CLPT_HAS_TRIANGLES
#define CLPT_HAS_TRIANGLES 1
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
  const uint row = clpt_udiv(pixel, params->width);
  const uint col = pixel - row * params->width;
  const Float2 subpixel = camera_subpixel(rng_key_of(params), params->sampler, pixel, sample);
  PathState path;
  path.direction = camera_ray(&params->camera, params->width, params->height, col, row, subpixel, &path.origin);
  path.throughput = v3_splat(1.0f);
  path.radiance = v3_splat(0.0f);
  path.pixel = pixel;
  path.sample = sample;
  path.bsdf_pdf = (real)0;
  path.bounce = 0u;
  path.segments = 0u;
  path.skip_sphere = -1;
  path.alive = 1;
#if defined(CLPT_AOVS) && CLPT_AOVS /* the first-hit layers (aov.cl): nothing recorded yet */
  path.aov_albedo = v3_splat((real)1);
  path.aov_normal = v3_splat((real)0);
  path.aov_depth = (real)0;
#endif
  return path;
}

/* The seed of the coverage decisions (alpha.cl) of the path's ray at its bounce (stream: the
 * segment's ray or its shadow ray); 0 where no alpha is compiled. */
CLPT_INLINE uint path_alpha_seed(const GpuRenderParams* params, const PathState* path, uint stream) {
#if CLPT_HAS_ALPHA
  return alpha_ray_seed(params->seed_lo, params->seed_hi, path->pixel, path->sample, path->bounce, stream);
#else
  (void)params;
  (void)path;
  (void)stream;
  return 0u;
#endif
}

CLPT_INLINE Hit path_intersect(const PathState* path, const SceneBuffers* scene, const GpuRenderParams* params) {
  return scene_closest_hit(scene, params, path->origin, path->direction, path->skip_sphere,
                           path_alpha_seed(params, path, CLPT_ALPHA_STREAM_HIT));
}

/* path_intersect in two halves, for a caller that puts a barrier between them (the lockstep
 * megakernel): the loop's spheres, then the hierarchy narrowing that hit. Together they are
 * path_intersect exactly. */
CLPT_INLINE Hit path_intersect_loop(const PathState* path, const SceneBuffers* scene, const GpuRenderParams* params) {
  return scene_loop_hit(scene, params, path->origin, path->direction, path->skip_sphere,
                        path_alpha_seed(params, path, CLPT_ALPHA_STREAM_HIT));
}
CLPT_INLINE void path_intersect_hierarchy(const PathState* path, const SceneBuffers* scene,
                                          const GpuRenderParams* params, Hit* hit) {
  scene_hierarchy_hit(scene, params, path->origin, path->direction, path->skip_sphere,
                      path_alpha_seed(params, path, CLPT_ALPHA_STREAM_HIT), hit);
}

/* A surface's material in private memory, read field by field (a struct copy would be lowered to
 * vector loads, which stop PoCL's vectoriser). Unused fields cost nothing: their reads are dead. */
typedef struct SurfaceMaterial {
  uint kind;        /* CLPT_MATERIAL_* */
  Vec3 reflectance; /* rho */
  Vec3 emission;
  real phong_exponent;
  real ior;
#if CLPT_HAS_PBR
  real metallic;
  real roughness;
  real transmission;
#endif
#if CLPT_HAS_PBR_VOLUME
  real thickness;    /* > 0: the transmission refracts into a closed volume */
  Vec3 attenuation;  /* Beer's law coefficients inside it, world units^-1 */
#endif
  CLPT_ABI_PAD(uint, 1)
} SurfaceMaterial;

CLPT_INLINE SurfaceMaterial material_of(__global const GpuMaterial* m) {
  SurfaceMaterial s;
  s.kind = m->kind;
  s.reflectance = v3_load_sphere_field(m->reflectance);
  s.emission = v3_load_sphere_field(m->emission);
  s.phong_exponent = m->phong_exponent;
  s.ior = m->ior;
#if CLPT_HAS_PBR
  s.metallic = m->metallic;
  s.roughness = m->roughness;
#if CLPT_HAS_PBR_TRANSMISSION
  s.transmission = m->transmission;
#else
  s.transmission = (real)0;
#endif
#endif
#if CLPT_HAS_PBR_VOLUME
  s.thickness = m->thickness;
  s.attenuation = v3_load_sphere_field(m->attenuation);
#endif
  return s;
}

#if CLPT_HAS_PBR
CLPT_INLINE PbrParams pbr_params_of(const SurfaceMaterial* m) {
#if CLPT_HAS_PBR_VOLUME
  const int volume = m->thickness > (real)0 ? 1 : 0;
#else
  const int volume = 0;
#endif
  return pbr_params(m->reflectance, m->metallic, m->roughness, m->ior, m->transmission, volume);
}
#endif

/* Sphere `index`'s material: by selects over the loop's spheres where CLPT_MATERIAL_BY_SELECT
 * (maths.cl) says so, else by one indexed read of each field. The same values either way. */
CLPT_INLINE SurfaceMaterial sphere_material(__global const GpuSphere* spheres, int index) {
#if CLPT_MATERIAL_BY_SELECT && defined(CLPT_SPHERE_COUNT)
  SurfaceMaterial m = material_of(&spheres[0].material);
#pragma unroll
  for (uint i = 1u; i < CLPT_SPHERE_COUNT; ++i) {
    const SurfaceMaterial c = material_of(&spheres[i].material);
    const bool pick = index == (int)i;
    m.kind = pick ? c.kind : m.kind;
    m.reflectance = v3_select(pick, c.reflectance, m.reflectance);
    m.emission = v3_select(pick, c.emission, m.emission);
    m.phong_exponent = pick ? c.phong_exponent : m.phong_exponent;
    m.ior = pick ? c.ior : m.ior;
#if CLPT_HAS_PBR
    m.metallic = pick ? c.metallic : m.metallic;
    m.roughness = pick ? c.roughness : m.roughness;
    m.transmission = pick ? c.transmission : m.transmission;
#endif
#if CLPT_HAS_PBR_VOLUME
    m.thickness = pick ? c.thickness : m.thickness;
    m.attenuation = v3_select(pick, c.attenuation, m.attenuation);
#endif
  }
  return m;
#else
  return material_of(&spheres[index].material);
#endif
}

/* Next direction and throughput weight at a non-emitting surface. Materials left out of the
 * build (CLPT_HAS_*) fall back to Lambertian, which the host never lets happen. *pbr_pdf: the
 * Pbr sampler's density of the direction (0 for its delta lobes), for the next hit's MIS weight;
 * left alone for the other kinds, whose density material_eval gives. */
CLPT_INLINE Vec3 material_sample(const SurfaceMaterial* m, Vec3 d, Vec3 normal, Uniform4 u, Vec3* weight,
                                 real* pbr_pdf) {
  const Vec3 rho = m->reflectance;
#if CLPT_HAS_PHONG || CLPT_HAS_GLASS || CLPT_HAS_MIRROR || CLPT_HAS_PBR /* read only where there is a choice */
  const uint kind = m->kind;
#endif
  Vec3 next = bsdf_lambertian_sample(d, normal, rho, u, weight);
#if CLPT_HAS_PHONG
  Vec3 phong_weight;
  const Vec3 phong = bsdf_phong_sample(d, normal, rho, m->phong_exponent, u, &phong_weight);
  next = v3_select(kind == CLPT_MATERIAL_PHONG, phong, next);
  *weight = v3_select(kind == CLPT_MATERIAL_PHONG, phong_weight, *weight);
#endif
#if CLPT_HAS_GLASS
  Vec3 glass_weight;
  const Vec3 glass = bsdf_glass_sample(d, normal, rho, m->ior, u, &glass_weight);
  next = v3_select(kind == CLPT_MATERIAL_GLASS, glass, next);
  *weight = v3_select(kind == CLPT_MATERIAL_GLASS, glass_weight, *weight);
#endif
#if CLPT_HAS_MIRROR
  Vec3 mirror_weight;
  const Vec3 mirror = bsdf_mirror_sample(d, normal, rho, &mirror_weight);
  next = v3_select(kind == CLPT_MATERIAL_MIRROR, mirror, next);
  *weight = v3_select(kind == CLPT_MATERIAL_MIRROR, mirror_weight, *weight);
#endif
#if CLPT_HAS_PBR
  Vec3 pbr_weight;
  const PbrParams pbr = pbr_params_of(m);
  const Vec3 pbr_next = bsdf_pbr_sample(d, normal, &pbr, u, &pbr_weight, pbr_pdf);
  next = v3_select(kind == CLPT_MATERIAL_PBR, pbr_next, next);
  *weight = v3_select(kind == CLPT_MATERIAL_PBR, pbr_weight, *weight);
#else
  (void)pbr_pdf;
#endif
  return next;
}

/* f cos towards wi and the BSDF sampler's density of wi, at a non-emitting surface (next-event
 * estimation). Glass and the mirror are specular: 0 and 0. */
CLPT_INLINE Vec3 material_eval(const SurfaceMaterial* m, Vec3 d, Vec3 normal, Vec3 wi, real* pdf) {
  const Vec3 rho = m->reflectance;
#if CLPT_HAS_PHONG || CLPT_HAS_GLASS || CLPT_HAS_MIRROR || CLPT_HAS_PBR /* read only where there is a choice */
  const uint kind = m->kind;
#endif
  Vec3 f_cos = bsdf_lambertian_eval(d, normal, rho, wi, pdf);
#if CLPT_HAS_PHONG
  real phong_pdf;
  const Vec3 phong = bsdf_phong_eval(d, normal, rho, m->phong_exponent, wi, &phong_pdf);
  f_cos = v3_select(kind == CLPT_MATERIAL_PHONG, phong, f_cos);
  *pdf = kind == CLPT_MATERIAL_PHONG ? phong_pdf : *pdf;
#endif
#if CLPT_HAS_GLASS || CLPT_HAS_MIRROR
  /* A bit test, not `kind == GLASS || kind == MIRROR`: LLVM turns two comparisons of one integer
   * into a switch, which stops PoCL's vectoriser ("loop contains a switch statement"; the glass
   * scene's nee kernels ran unvectorised, docs/performance.md "Presets"). OpenCL shifts count
   * modulo 32, and kinds are below 32. */
  const uint specular_kinds = (1u << CLPT_MATERIAL_GLASS) | (1u << CLPT_MATERIAL_MIRROR);
  const bool specular = ((1u << kind) & specular_kinds) != 0u;
  f_cos = v3_select(specular, v3_splat((real)0), f_cos);
  *pdf = specular ? (real)0 : *pdf;
#endif
#if CLPT_HAS_PBR
  real pbr_pdf;
  const PbrParams pbr = pbr_params_of(m);
  const Vec3 pbr_f_cos = bsdf_pbr_eval(d, normal, &pbr, wi, &pbr_pdf);
  f_cos = v3_select(kind == CLPT_MATERIAL_PBR, pbr_f_cos, f_cos);
  *pdf = kind == CLPT_MATERIAL_PBR ? pbr_pdf : *pdf;
#endif
  return f_cos;
}

/* Power heuristic weight of a strategy with density a against one with density b. */
CLPT_INLINE real mis_power(real a, real b) {
  const real a2 = a * a, b2 = b * b;
  return a2 + b2 > (real)0 ? a2 / (a2 + b2) : (real)0;
}

/* Where a path stands on the surface it hit. Spheres: the point o + t d, the outward normal, no
 * offset (a new ray skips the sphere it leaves, intersect.cl). Triangles (triangle.cl): the point
 * from the barycentrics with its error bound, new rays offset off the plane; `normal` is the
 * shading normal, kept only when the incoming ray sees it from the same side as the geometric
 * normal (else the geometric one shades), and a direction leaving on one side of the shading
 * normal but the other side of the geometric one carries nothing: no light through a surface at
 * grazing angles, where interpolated normals tilt past the true plane. */
typedef struct SurfacePoint {
  Vec3 point;     /* camera-relative */
  Vec3 normal;    /* unit normal the BSDF uses */
#if CLPT_HAS_TRIANGLES
  TriangleSurface triangle; /* valid when on_triangle */
#endif
  int on_triangle;
  CLPT_ABI_PAD(int, 3)
} SurfacePoint;

CLPT_INLINE SurfacePoint surface_point_of(const SceneBuffers* scene, Hit hit, Vec3 o, Vec3 d, real t) {
  SurfacePoint s;
  s.point = v3_add_scaled(o, d, t);
#if CLPT_HIT_CENTRE /* the loop carried c - o (intersect.cl): the normal is (p - c) / r, normalised */
  s.normal = v3_normalize(v3_sub(v3_scale(d, t), hit.centre_offset));
  (void)scene; /* read by the triangle half below only, which CLPT_HIT_CENTRE never has */
#else
  const SphereGeometry sphere = sphere_geometry(scene->spheres, hit.sphere < 0 ? 0 : hit.sphere);
  s.normal = sphere_normal_at(&sphere, o, d, t);
#endif
  s.on_triangle = 0;
#if CLPT_HAS_TRIANGLES
  const int tri = hit.triangle < 0 ? 0 : hit.triangle;
  s.triangle = triangle_surface(o, d, &scene->triangles[tri], &scene->triangle_shading[tri]);
  const bool on_triangle = hit.triangle >= 0;
  const bool consistent = (v3_dot(d, s.triangle.shading) < (real)0) == (v3_dot(d, s.triangle.geometric) < (real)0);
  s.point = v3_select(on_triangle, s.triangle.point, s.point);
  s.normal = v3_select(on_triangle, consistent ? s.triangle.shading : s.triangle.geometric, s.normal);
  s.on_triangle = on_triangle ? 1 : 0;
#endif
  return s;
}

#if CLPT_HAS_TEXTURES
/* The hit's textured-material index (CLPT_TEXTURE_NONE: none) and its texture coordinates *u, *v:
 * a triangle's interpolated ones, or on a sphere the spherical mapping at its outward normal
 * (texture.cl, sphere_uv; CLPT_HAS_SPHERE_TEXTURES). */
CLPT_INLINE uint hit_texture_material(__global const uchar* texturing, int triangle, int sphere, const SurfacePoint* s,
                                      float* u, float* v) {
  uint material = CLPT_TEXTURE_NONE;
  *u = 0.0f;
  *v = 0.0f;
#if CLPT_HAS_TRIANGLES
  material = triangle_texture_material(texturing, triangle);
  if (material != CLPT_TEXTURE_NONE) {
    const real b1 = s->triangle.b1, b2 = s->triangle.b2;
    triangle_uv(triangle_texturing(texturing, (uint)triangle), (float)((real)1 - b1 - b2), (float)b1, (float)b2, u, v);
    return material;
  }
#endif
#if CLPT_HAS_SPHERE_TEXTURES
  material = sphere_texture_material(texturing, triangle < 0 ? sphere : -1);
  if (material != CLPT_TEXTURE_NONE) sphere_uv(s->normal, u, v);
#else
  (void)sphere;
  (void)s;
#endif
  return material;
}

/* The hit's textures (texture.cl) applied to its material and shading normal: each
 * textured parameter is its factor times the lookup (colours and metallic/roughness clamped to
 * [0, 1], emission to >= 0). A normal map's normal is used only when the arriving ray sees it from
 * the same side as the geometric normal (else the unmapped shading normal stays), and
 * leaves_consistently then drops any direction on opposite sides of it and of the geometric
 * normal: no light leaks through the surface (docs/textures.md). */
CLPT_INLINE void apply_textures(const SceneBuffers* scene, int triangle, int sphere, Vec3 d, SurfacePoint* s,
                                SurfaceMaterial* m) {
  __global const uchar* texturing = scene->texturing;
  float u, v;
  const uint material = hit_texture_material(texturing, triangle, sphere, s, &u, &v);
  if (material == CLPT_TEXTURE_NONE) return;
  __global const GpuMaterialTextures* mt = material_textures(texturing, material);
  if (mt->base_color != CLPT_TEXTURE_NONE) {
    const TexelRgba c = texture_lookup(texturing, mt->base_color, u, v, CLPT_BASE_STORAGES);
    m->reflectance = v3_mul(m->reflectance, v3(clamp(c.r, 0.0f, 1.0f), clamp(c.g, 0.0f, 1.0f), clamp(c.b, 0.0f, 1.0f)));
  }
#if CLPT_HAS_VERTEX_COLORS
#if CLPT_HAS_SPHERE_TEXTURES
  if (triangle >= 0) /* a triangle's (a sphere's record has none) */
#endif
  {
    const real b1 = s->triangle.b1, b2 = s->triangle.b2;
    const TexelRgba k = triangle_vertex_color(texturing, (uint)triangle, (float)((real)1 - b1 - b2), (float)b1, (float)b2);
    m->reflectance = v3_mul(m->reflectance, v3(k.r, k.g, k.b)); /* glTF COLOR_0 (vertex_colors.cl) */
  }
#endif
#if CLPT_HAS_PBR
  if (mt->metallic != CLPT_TEXTURE_NONE) {
    const uint index = mt->metallic;
    m->metallic *= clamp(texture_lookup_channel(texturing, index, texture_at(texturing, index)->channel, u, v, CLPT_MR_STORAGES), 0.0f, 1.0f);
  }
  if (mt->roughness != CLPT_TEXTURE_NONE) {
    const uint index = mt->roughness;
    m->roughness *= clamp(texture_lookup_channel(texturing, index, texture_at(texturing, index)->channel, u, v, CLPT_MR_STORAGES), 0.0f, 1.0f);
  }
#endif
#if CLPT_HAS_EMISSION_TEXTURES
  if (mt->emission != CLPT_TEXTURE_NONE) {
    const TexelRgba c = texture_lookup(texturing, mt->emission, u, v, CLPT_EMISSION_STORAGES);
    m->emission = v3_mul(m->emission, v3(fmax(c.r, 0.0f), fmax(c.g, 0.0f), fmax(c.b, 0.0f)));
  }
#endif
#if CLPT_HAS_NORMAL_MAPS && CLPT_HAS_TRIANGLES /* triangles only: a sphere's record has no normal map */
  if (mt->normal != CLPT_TEXTURE_NONE) {
    const real b1 = s->triangle.b1, b2 = s->triangle.b2;
    const Vec3 mapped = normal_mapped(texturing, (uint)triangle, mt->normal, mt->normal_scale, u, v, b1, b2, s->normal);
    const bool consistent = (v3_dot(d, mapped) < (real)0) == (v3_dot(d, s->triangle.geometric) < (real)0);
    s->normal = v3_select(consistent, mapped, s->normal);
  }
#else
  (void)d;
#endif
}
#endif

/* Whether direction `dir` leaving the surface is on the same side of the geometric normal as of
 * the shading normal (always, on a sphere). */
CLPT_INLINE bool leaves_consistently(const SurfacePoint* s, Vec3 dir) {
#if CLPT_HAS_TRIANGLES
  return !s->on_triangle || v3_dot(dir, s->triangle.geometric) * v3_dot(dir, s->normal) > (real)0;
#else
  (void)s;
  (void)dir;
  return true;
#endif
}

/* Origin of a ray leaving the surface along dir. */
CLPT_INLINE Vec3 leaving_origin(const SurfacePoint* s, Vec3 dir) {
#if CLPT_HAS_TRIANGLES
  return v3_select(s->on_triangle != 0, triangle_offset_origin(&s->triangle, dir), s->point);
#else
  (void)dir;
  return s->point;
#endif
}

/* A shadow ray whose answer waits on the hierarchy, and the light it brings if nothing of the
 * hierarchy blocks it (throughput applied; zero when there is nothing to bring, and then the ray
 * need not be traced). Filled by path_shade_surface, answered by shadow_query_blocked, used by
 * path_shade_light: the three halves of path_shade, which the lockstep megakernel separates by
 * barriers so that the any-hit traversal loop runs in a region of its own. */
typedef struct ShadowQuery {
  Vec3 origin;
  Vec3 direction;
  Vec3 light;
  real t_max;
  int skip;
  int skip_triangle;
#if CLPT_HAS_ALPHA
  uint alpha_seed; /* alpha.cl: the shadow ray's coverage decisions */
#endif
  CLPT_ABI_PAD(int, 1)
} ShadowQuery;

/* The shadow ray's coverage seed (alpha.cl), 0 where no alpha is compiled (the field is absent). */
#if CLPT_HAS_ALPHA
#define shadow_alpha_seed(q) ((q)->alpha_seed)
#else
#define shadow_alpha_seed(q) 0u
#endif

CLPT_INLINE ShadowQuery no_shadow_query(void) {
  ShadowQuery q;
  q.origin = v3_splat((real)0);
  q.direction = v3_splat((real)0);
  q.light = v3_splat((real)0);
  q.t_max = (real)0;
  q.skip = -1;
  q.skip_triangle = -1;
#if CLPT_HAS_ALPHA
  q.alpha_seed = 0u;
#endif
  return q;
}

/* Next-event estimation at surface point `surface` of sphere `index` (-1: a triangle), material m,
 * for a path arriving along d: one shadow ray to a light sample, tested here against the loop's
 * spheres; returns the MIS-weighted radiance it brings when the hierarchy does not block it
 * (throughput not yet applied), fills the ray into *q for that test, and counts the shadow ray
 * in *segments. */
CLPT_INLINE Vec3 next_event(const PathState* path, const SceneBuffers* scene, const GpuRenderParams* params,
                            int index, const SurfaceMaterial* m, const SurfacePoint* surface, uint* segments,
                            ShadowQuery* q) {
  /* With no light, light_sample reads the buffer's placeholder entry and returns pdf 0 (no early
   * return: a branch here would stop PoCL's vectoriser). */
  const Uniform4 u = sampler_uniform4(rng_key_of(params), params->sampler, path->pixel, path->sample,
                                       CLPT_DIM_LIGHT + path->bounce);
  LightSample ls = light_sample(scene, params->light_count, surface->point, u);
#if CLPT_HAS_ENVIRONMENT == 1
  environment_light_choice(scene->environment, surface->point, u, &ls); /* or the environment's */
#endif
  real bsdf_pdf;
  const Vec3 f_cos = material_eval(m, path->direction, surface->normal, ls.direction, &bsdf_pdf);
  const int skip = index >= 0 && v3_dot(ls.direction, surface->normal) > (real)0 ? index : -1;
  const Vec3 origin = leaving_origin(surface, ls.direction);
#if CLPT_LIGHT_PICK_BY_POWER
  /* A triangle light's shadow ray runs from the offset origin to the sample's offset target and
   * skips the light's own triangle (bvh.cl): no epsilon of the scene's size at either end. A
   * punctual light's runs to the light (a directional one's CLPT_DIRECTIONAL_DISTANCE). A sphere
   * light's ends 0.1% short of its point, as below. */
  const bool to_target = ls.triangle >= 0 || ls.delta != 0;
  const Vec3 to_target_v = v3_sub(ls.target, origin);
  const real target_distance = clpt_sqrt(v3_dot(to_target_v, to_target_v));
  const Vec3 shadow_direction =
      v3_select(to_target, v3_scale(to_target_v, (real)1 / (target_distance > (real)0 ? target_distance : (real)1)),
                ls.direction);
  const real near_light = to_target ? target_distance : ls.distance * (real)0.999f;
  const int skip_triangle = ls.triangle;
#else
  const Vec3 shadow_direction = ls.direction;
  const real near_light = ls.distance * (real)0.999f;
  const int skip_triangle = -1;
#endif
  const Hit shadow = scene_intersect(scene->spheres, params->sphere_count, origin, shadow_direction,
                                     params->ray_epsilon, skip);
  q->origin = origin;
  q->direction = shadow_direction;
  q->t_max = near_light;
  q->skip = skip;
  q->skip_triangle = skip_triangle;
#if CLPT_HAS_ALPHA
  q->alpha_seed = path_alpha_seed(params, path, CLPT_ALPHA_STREAM_SHADOW);
#endif
  *segments += 1u;
  /* Visible: the sampled point faces the vertex (light_sample) and the first thing along the ray
   * is the emitter, at the sampled point's distance (nothing in between): the loop's spheres
   * find the emitter first (when the lights are in the loop), the hierarchy nothing before it;
   * for a triangle light, the loop's spheres nothing before its target. */
#if CLPT_LIGHT_PICK_BY_POWER
  bool loop_clear = params->sphere_count == 0u ||
                    ((to_target || shadow.sphere == ls.sphere) && shadow.t >= near_light);
  const Vec3 emission = ls.emission;
#else
  bool loop_clear = params->sphere_count == 0u || (shadow.sphere == ls.sphere && shadow.t >= near_light);
  const Vec3 emission = v3_load_global(scene->spheres[ls.sphere].material.emission);
#endif
#if defined(CLPT_TRIANGLE_COUNT) && CLPT_TRIANGLE_COUNT > 0
  /* A small mesh's triangles in their loop (triangle_loop.cl): none before the light either. */
  loop_clear = loop_clear & !triangle_loop_blocked(scene->triangles, scene->texturing, origin, shadow_direction, near_light,
                                                   skip_triangle, shadow_alpha_seed(q));
#endif
  /* int operands and `&`, not `&&`: f_cos's reads behind a short-circuit would be masked loads
   * (maths.cl, v3_is_zero). */
  const bool visible = ((ls.pdf > (real)0) & (int)loop_clear & !v3_is_zero(f_cos) &
                        (int)leaves_consistently(surface, ls.direction)) != 0;
#if CLPT_HAS_PUNCTUAL_LIGHTS
  /* A delta light has no BSDF-sampled counterpart: weight 1, divided by its pick probability. */
  const real mis = ls.delta != 0 ? (real)1 : mis_power(ls.pdf, bsdf_pdf);
#else
  const real mis = mis_power(ls.pdf, bsdf_pdf);
#endif
  const real weight = visible ? mis / ls.pdf : (real)0;
#if CLPT_HAS_ENVIRONMENT
  /* A scene lit by its environment alone has an empty light list, whose placeholder entry's
   * sample may be NaN where it is not visible: selected away, not multiplied by 0. */
  return v3_select(visible, v3_scale(v3_mul(f_cos, emission), weight), v3_splat((real)0));
#else
  return v3_scale(v3_mul(f_cos, emission), weight);
#endif
}

#include "aov.cl" /* the first-hit layers (CLPT_AOVS): material_albedo, aov_record */

/* Field-wise choice between two path states (a select of the whole struct would stop PoCL's
 * vectoriser, see v3_select). */
CLPT_INLINE PathState path_select(bool c, PathState a, PathState b) {
  PathState p;
  CLPT_PATH_SELECT_FIELDS
  return p;
}

/* CLPT_SCATTER_DRAW_PAIRS (the host's choice, kernel_options.cpp, scatter_draws_paired; the generic
 * kernel reads GpuRenderParams.scatter_draw_pairs): where scattering reads only u0 and u1 of its
 * draw (no glass, whose Fresnel choice reads u2, and no Russian roulette, which reads u3), one
 * draw serves two bounces: bounce b scatters with the draw of dimension 1 + b / 2, its (u0, u1)
 * for an even b and its (u2, u3) for an odd one. Otherwise bounce b has dimension 1 + b to
 * itself. Either way the numbers depend on (key, pixel, sample, bounce) alone, in every form;
 * the Philox words are independent, so the pairs are too. Why: Philox is about a fifth of the
 * CPU's lockstep megakernel, whose live paths are all at the same bounce, so that loop evaluates
 * each paired draw once for two segments (megakernel.cl; docs/performance.md, "What limits the
 * speed"). */
#ifdef CLPT_SCATTER_DRAW_PAIRS
#define CLPT_SCATTER_PAIRED(params) ((void)(params), CLPT_SCATTER_DRAW_PAIRS)
#else
#define CLPT_SCATTER_PAIRED(params) ((params)->scatter_draw_pairs != 0u)
#endif

/* The draw the path's scattering at its current bounce takes its uniforms from
 * (scatter_uniforms_of). */
CLPT_INLINE Uniform4 scatter_draw(const GpuRenderParams* params, const PathState* path) {
  const uint dimension = 1u + (CLPT_SCATTER_PAIRED(params) ? path->bounce >> 1 : path->bounce);
  return sampler_uniform4(rng_key_of(params), params->sampler, path->pixel, path->sample, dimension);
}

/* The scattering's uniforms at `bounce` from its draw: the draw itself, or for the odd bounce of
 * a paired draw its second pair in u0 and u1. */
CLPT_INLINE Uniform4 scatter_uniforms_of(const GpuRenderParams* params, Uniform4 draw, uint bounce) {
  const bool second = CLPT_SCATTER_PAIRED(params) && (bounce & 1u) != 0u;
  Uniform4 u = draw;
  u.u0 = second ? draw.u2 : draw.u0;
  u.u1 = second ? draw.u3 : draw.u1;
  return u;
}

/* One shading event: a miss ends the path (black, or the environment); an emitter adds its emission
 * (MIS-weighted under nee) and ends it (emitters do not reflect); past max_bounces the path ends;
 * otherwise, under nee, a shadow ray adds the light it finds, and the material scatters the path.
 * Written as selects over the cases, not branches, so that PoCL vectorises it.
 *
 * path_shade = path_shade_surface, shadow_query_blocked, path_shade_light, in that order; the
 * shadow ray's light is the last thing added to the radiance, so the split changes no sum.
 * path_shade_surface_drawn takes the scattering's draw from its caller: it must be
 * scatter_draw(params, path). */
CLPT_INLINE void path_shade_surface_drawn(PathState* path, Hit hit, const SceneBuffers* scene,
                                          const GpuRenderParams* params, Uniform4 draw, ShadowQuery* shadow) {
  *shadow = no_shadow_query();
  path->segments += 1u;
  const bool missed = hit.sphere < 0 && hit.triangle < 0;
  const int index = hit.sphere < 0 ? 0 : hit.sphere;
#if CLPT_HAS_TRIANGLES
  const bool on_triangle = hit.triangle >= 0;
  __global const GpuMaterial* stored =
      on_triangle ? &scene->triangle_shading[hit.triangle].material : &scene->spheres[index].material;
  SurfaceMaterial material = material_of(stored);
#else
  SurfaceMaterial material = sphere_material(scene->spheres, index);
#if !CLPT_MATERIAL_BY_SELECT
  __global const GpuMaterial* stored = &scene->spheres[index].material;
#endif
#endif
#if CLPT_MATERIAL_BY_SELECT
  /* Picked by selects: read for every path, as a masked load would be costed as a gather. */
  const bool emitter = !missed && material.kind == CLPT_MATERIAL_EMITTER;
#else
  /* Behind the `&&` where gathers are fast. Read for every path (as above), it let LLVM's SLP
   * vectoriser pack the loop-carried path state on an AVX-512 CPU, and the megakernel ran scalar
   * there (measured on an AMD EPYC Zen 4: 6x slower; docs/performance.md, "CPUs without fast
   * gathers"). */
  const bool emitter = !missed && stored->kind == CLPT_MATERIAL_EMITTER;
#endif
  bool scatters = !missed && !emitter && path->bounce < params->max_bounces;

  const real t = missed ? (real)0 : hit.t;
  SurfacePoint surface = surface_point_of(scene, hit, path->origin, path->direction, t);
#if CLPT_HAS_TEXTURES
  apply_textures(scene, missed ? -1 : hit.triangle, missed ? -1 : hit.sphere, path->direction, &surface, &material);
#endif
  const Vec3 normal = surface.normal;
  /* The sphere the path stands on, or -1 on a triangle (a sphere a new ray may skip). */
  const int sphere_index = surface.on_triangle ? -1 : index;

#if CLPT_HAS_PBR_VOLUME
  /* Beer's law: a segment that ends where it leaves a Pbr volume (it meets the surface from
   * inside, along the outward normal) ran inside it for t. Applied before the surface's emission
   * and everything after it. */
  const bool leaves_volume = !missed && material.kind == CLPT_MATERIAL_PBR && material.thickness > (real)0 &&
                             v3_dot(path->direction, normal) > (real)0;
  const Vec3 absorbed = v3_scale(material.attenuation, -t);
  const Vec3 transmittance = v3(exp(absorbed.x), exp(absorbed.y), exp(absorbed.z));
  path->throughput = v3_select(leaves_volume, v3_mul(path->throughput, transmittance), path->throughput);
#endif
  Vec3 emitted = v3_mul(path->throughput, material.emission);
#if CLPT_NEE_COMPILED
  if (CLPT_NEE_ON(params)) {
    /* A BSDF-sampled ray that found a light competes with the light sample taken before it. An
     * emitting triangle's density comes from its shading record; without triangle lights it is
     * no sampled light (density 0: the hit keeps its full weight). */
    /* Evaluated for every path, then chosen: formed under the condition, its reads would be
     * masked loads (maths.cl, v3_is_zero). */
    const real hit_pdf = light_pdf_of_hit(scene->lights, params->light_count, sphere_index, normal, path->direction, t);
    real light_pdf = path->bsdf_pdf > (real)0 ? hit_pdf : (real)0;
#if CLPT_HAS_TRIANGLE_LIGHTS
    const real triangle_pdf = triangle_light_pdf_of_hit(&scene->triangle_shading[surface.on_triangle ? hit.triangle : 0],
                                                        surface.triangle.geometric, path->direction, t);
    light_pdf = surface.on_triangle ? triangle_pdf : light_pdf;
#endif
#if CLPT_HAS_ENVIRONMENT == 1
    light_pdf *= (real)1 - (real)scene->environment->pick_probability; /* the list was chosen */
#endif
    const real hit_weight = mis_power(path->bsdf_pdf, light_pdf); /* likewise formed for every path */
    emitted = v3_scale(emitted, path->bsdf_pdf > (real)0 ? hit_weight : (real)1);
  }
#endif
#if CLPT_HAS_PBR
  /* A Pbr surface emits (its emission may be 0) and scatters. */
  const bool emits = emitter || (!missed && material.kind == CLPT_MATERIAL_PBR);
#else
  const bool emits = emitter;
#endif
  path->radiance = v3_select(emits, v3_add(path->radiance, emitted), path->radiance);
#if CLPT_HAS_ENVIRONMENT
  /* An escaping ray sees the environment; under nee an image's is weighted against its light
   * sample's density, as an emitter hit is above (constant: no light sample, weight 1). */
  Vec3 background = v3_mul(path->throughput, environment_radiance(scene->environment, path->direction));
#if CLPT_HAS_ENVIRONMENT == 1 && CLPT_NEE_COMPILED
  if (CLPT_NEE_ON(params)) {
    const real environment_light_pdf =
        (real)scene->environment->pick_probability * environment_pdf(scene->environment, path->direction);
    const real environment_weight = mis_power(path->bsdf_pdf, environment_light_pdf);
    background = v3_scale(background, path->bsdf_pdf > (real)0 ? environment_weight : (real)1);
  }
#endif
  path->radiance = v3_select(missed, v3_add(path->radiance, background), path->radiance);
#endif

  const Uniform4 u = scatter_uniforms_of(params, draw, path->bounce);
  Vec3 weight;
  real pbr_pdf = (real)0;
  const Vec3 next = material_sample(&material, path->direction, normal, u, &weight, &pbr_pdf);
  weight = v3_select(leaves_consistently(&surface, next), weight, v3_splat((real)0));

#if CLPT_NEE_COMPILED
  if (CLPT_NEE_ON(params)) {
    uint shadow_segments = 0u;
    const Vec3 light = next_event(path, scene, params, sphere_index, &material, &surface, &shadow_segments, shadow);
    shadow->light = v3_select(scatters, v3_mul(path->throughput, light), v3_splat((real)0));
    path->segments += scatters ? shadow_segments : 0u;
    real next_pdf;
    (void)material_eval(&material, path->direction, normal, next, &next_pdf);
#if CLPT_HAS_PBR
    /* The sampler's own density: 0 after a delta lobe, whose direction material_eval cannot tell
     * from one its diffuse lobe might have drawn. */
    next_pdf = material.kind == CLPT_MATERIAL_PBR ? pbr_pdf : next_pdf;
#endif
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

#if defined(CLPT_AOVS) && CLPT_AOVS
  aov_record(path, missed, t, &material, normal, scatters && !v3_is_zero(weight));
#endif
  path->throughput = v3_select(scatters, throughput, path->throughput);
  path->origin = v3_select(scatters, leaving_origin(&surface, next), path->origin);
  path->direction = v3_select(scatters, next, path->direction);
  path->skip_sphere = scatters && sphere_index >= 0 && v3_dot(next, normal) > (real)0 ? sphere_index : -1;
  path->bounce += scatters ? 1u : 0u;
#if defined(CLPT_LOCKSTEP_GROUP) && CLPT_LOCKSTEP_GROUP
  /* `&`, not `&&`, in the lockstep megakernel: the short-circuit became a branch on `scatters`
   * into which LLVM sank the reads only scattering paths use (the light's emission, under nee),
   * and a read under a branch is a gather per work-item where it was one read for the whole
   * work-item loop before it (16 gathers in the diffuse scene's nee kernel against 4;
   * docs/performance.md, "The book's scenes against the tree before the glTF material"). Not
   * elsewhere: in the wavefront's shade kernel the branch-free form let SLP pair the sphere
   * normal's x and y, which keeps three of its work-item loops scalar. */
  path->alive = (scatters & !v3_is_zero(weight)) ? 1 : 0;
#else
  path->alive = scatters && !v3_is_zero(weight) ? 1 : 0;
#endif
}

CLPT_INLINE void path_shade_surface(PathState* path, Hit hit, const SceneBuffers* scene, const GpuRenderParams* params,
                                    ShadowQuery* shadow) {
  path_shade_surface_drawn(path, hit, scene, params, scatter_draw(params, path), shadow);
}

/* Whether the hierarchy blocks the shadow ray of *q (false when it brings nothing, or with no
 * hierarchy). */
CLPT_INLINE bool shadow_query_blocked(const ShadowQuery* q, const SceneBuffers* scene, const GpuRenderParams* params) {
  return !v3_is_zero(q->light) &&
         scene_hierarchy_occluded(scene, params, q->origin, q->direction, q->t_max, q->skip, q->skip_triangle,
                                  shadow_alpha_seed(q));
}

/* Adds the shadow ray's light unless the hierarchy blocks it. */
CLPT_INLINE void path_shade_light(PathState* path, const ShadowQuery* q, bool blocked) {
#if CLPT_NEE_COMPILED
  path->radiance = v3_select(blocked, path->radiance, v3_add(path->radiance, q->light));
#else
  (void)path; /* no shadow rays compiled: q is no_shadow_query() */
  (void)q;
  (void)blocked;
#endif
}

/* path_shade with the scattering's draw from the caller (path_shade_surface_drawn's contract). */
CLPT_INLINE void path_shade_drawn(PathState* path, Hit hit, const SceneBuffers* scene, const GpuRenderParams* params,
                                  Uniform4 draw) {
  ShadowQuery q;
  path_shade_surface_drawn(path, hit, scene, params, draw, &q);
  path_shade_light(path, &q, shadow_query_blocked(&q, scene, params));
}

CLPT_INLINE void path_shade(PathState* path, Hit hit, const SceneBuffers* scene, const GpuRenderParams* params) {
  path_shade_drawn(path, hit, scene, params, scatter_draw(params, path));
}

#endif
