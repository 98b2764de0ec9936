/* aov.cl: what a path records for the first-hit layers a denoiser takes (CLPT_AOVS, decided in
 * kernel_options.cpp; docs/aovs.md): albedo, shading normal and the camera ray's hit distance.
 * Included by path.cl, whose path_begin starts the layers (albedo 1: the product of no delta
 * colours; normal and depth 0) and whose path_shade_surface_drawn calls aov_record once per
 * shading event;
 * without CLPT_AOVS this file compiles to nothing and path_state.h's AOV fields do not exist.
 *
 * Open Image Denoise's conventions (its API documentation, "RT" filter): the albedo is the
 * surface's colour independent of light and view, in [0, 1]; the normal is the shading normal in
 * world or view space, in [-1, 1]; both are taken at the first hit, or, better for reflections and
 * refractions, at the first non-delta hit after following perfect specular bounces, the albedo
 * then scaled by the specular surfaces' colours. clpt follows the delta bounces:
 *  - glass and the mirror are delta surfaces: a path that continues through one multiplies its
 *    colour (material_albedo) into the albedo and records nothing there; Glass's sampled choice
 *    of reflection or refraction makes the pixel's mean the Fresnel blend OIDN describes;
 *  - the first other surface (Lambertian, Phong, Pbr, an emitter) is recorded: the product times
 *    its material_albedo, and its shading normal;
 *  - a path that ends at a delta surface (the bounce limit, Russian roulette, a direction that
 *    would leave below a mesh's geometric surface) records that surface;
 *  - a path that leaves the scene records albedo 0 and normal 0 (clpt's background is black).
 * The depth is the first hit's alone: t along the camera ray (a unit direction), world units,
 * 0 for a miss. A path's normal is non-zero exactly when it has recorded a surface (a shading
 * normal is a unit vector), so no separate flag is kept. */
#ifndef CLPT_AOV_CL
#define CLPT_AOV_CL

#if defined(CLPT_AOVS) && CLPT_AOVS

CLPT_INLINE real aov_unit(real x) { return x < (real)0 ? (real)0 : x > (real)1 ? (real)1 : x; }

/* The albedo a denoiser takes for a surface of material m: its colour clamped to [0, 1] (the
 * reflectance; a Pbr material's base colour, which is its diffuse colour and, metallic, its
 * reflectance at normal incidence, as OIDN asks of metals), an emitter's emission clamped to
 * [0, 1]. The one place the layers read a material's colour: a texture lookup plugs in here. */
CLPT_INLINE Vec3 material_albedo(const SurfaceMaterial* m) {
  const Vec3 colour = v3_select(m->kind == CLPT_MATERIAL_EMITTER, m->emission, m->reflectance);
  return v3(aov_unit(colour.x), aov_unit(colour.y), aov_unit(colour.z));
}

/* Whether the layers look through a surface of material m: glass and the mirror. */
CLPT_INLINE bool material_is_delta(const SurfaceMaterial* m) {
#if CLPT_HAS_GLASS || CLPT_HAS_MIRROR
  /* A bit test, as in material_eval: two comparisons of one integer become a switch. */
  const uint delta_kinds = (1u << CLPT_MATERIAL_GLASS) | (1u << CLPT_MATERIAL_MIRROR);
  return ((1u << m->kind) & delta_kinds) != 0u;
#else
  (void)m;
  return false;
#endif
}

/* One shading event at the end of the path's current segment: `missed` (nothing hit), else the
 * hit at distance t with material m and shading normal `normal`; `continues`: the path scatters
 * on from here. Selects, not branches (PoCL vectorises the shading). */
CLPT_INLINE void aov_record(PathState* path, bool missed, real t, const SurfaceMaterial* m, Vec3 normal,
                            bool continues) {
  const bool open = v3_is_zero(path->aov_normal); /* nothing recorded yet (or a miss, which ended it) */
  const bool through = !missed && material_is_delta(m) && continues;
  const bool record = open && !through;
  const Vec3 colour = v3_select(missed, v3_splat((real)0), material_albedo(m));
  path->aov_albedo = v3_select(open, v3_mul(path->aov_albedo, colour), path->aov_albedo);
  path->aov_normal = v3_select(record && !missed, normal, path->aov_normal);
  path->aov_depth = path->bounce == 0u && !missed ? t : path->aov_depth;
}

#endif
#endif
