/* bsdf_pbr.cl: the glTF 2.0 metallic-roughness material (CLPT_MATERIAL_PBR), evaluated and sampled.
 *
 * The specification's Appendix B (docs/materials.md says it in full, with where clpt departs):
 *   specular  = D(h) V(wo, wi): Trowbridge-Reitz (GGX) D with alpha = roughness^2 and the
 *               height-correlated Smith visibility V = G2 / (4 |n.wo| |n.wi|)
 *   metal     = specular x Schlick(F0 = base colour, wo.h)
 *   dielectric= specular x Schlick(f0, wo.h) + base layer, f0 = ((ior - 1) / (ior + 1))^2
 *   base layer= Appendix B's fresnel_mix, renormalised by the specular layer's albedo:
 *               (1 - Schlick(f0, wo.h)) (1 - E(n.wo)) / (1 - G(n.wo)) base / pi  (diffuse), and
 *               (1 - E(n.wo)) x specular(wo, mirror(wi)) x base  (thin transmission), mixed by
 *               transmission; E = f0 S + B the Fresnel-weighted specular lobe's directional
 *               albedo, G the mean of (1 - wo.h)^5 over cosine-distributed wi
 *   f         = mix(dielectric, metal, metallic)
 * Appendix B's own fresnel_mix reflects up to 1.8 times the light it receives at grazing angles
 * (docs/materials.md); scaled so, the base layer's albedo is exactly (1 - E(n.wo)) x base: a white
 * dielectric returns all it receives at every angle and roughness, the diffuse keeps the angular
 * shape of fresnel_mix, and rough surfaces keep what the specular layer does not reflect (the
 * earlier weight, the transmittance of a smooth coat at n.wo and n.wi, removed up to 40% of it at
 * grazing views). S, B and G come from pbr_albedo_table.h, integrated in double when clpt is
 * built (cmake/make_pbr_albedo_table.cpp). The thin-walled transmission (KHR_materials_transmission)
 * continues through the surface: its lobe is the specular lobe of wi mirrored through the tangent
 * plane.
 *
 * Sampling: one of three lobes by a probability from the specular layer's albedo at n.wo
 * (specular: (1 - metallic) E + metallic E_metal, E_metal = mean(base) S + B; diffuse and
 * transmission share the rest by transmission), the diffuse lobe cosine-weighted, the specular
 * one by GGX's visible normals (Heitz 2018, "Sampling the GGX Distribution of Visible Normals"),
 * the transmission as the specular mirrored. The weight is f cos / pdf with the pdf of the whole
 * mixture (one-sample MIS over the lobes), which next-event estimation also sees (path.cl).
 * A reflection sampled below the surface (or a transmission above it) carries nothing, so the
 * mixture's density is exactly what the sampler produces.
 *
 * alpha below CLPT_PBR_DELTA_ALPHA (roughness < 0.0316) makes the specular and transmission
 * lobes deltas: they are sampled with their mixture probability and a density of 0, as the mirror
 * is (no light sample through them, light hits after them have MIS weight 1); evaluation sees
 * only the diffuse lobe. Uniforms: u0, u1 the direction, u2 the lobe (three, so scattering draws
 * are not paired: kernel_options.cpp). */
#ifndef CLPT_BSDF_PBR_CL
#define CLPT_BSDF_PBR_CL

#include "maths.cl"
#include "rng.cl"

/* The features of the glTF material (kernel_options.cpp): CLPT_HAS_PBR, CLPT_HAS_PBR_TRANSMISSION
 * and CLPT_HAS_PBR_VOLUME are named in a specialised kernel's options only when its scene has a
 * Pbr material, so that the kernels of scenes without one build from exactly the options they
 * had before: absent, they are 0 in a specialised kernel (CLPT_ESTIMATOR fixed) and 1 in the
 * generic one. */
#ifndef CLPT_HAS_PBR
#ifdef CLPT_ESTIMATOR
#define CLPT_HAS_PBR 0
#else
#define CLPT_HAS_PBR 1
#endif
#endif
#ifndef CLPT_HAS_PBR_TRANSMISSION
#define CLPT_HAS_PBR_TRANSMISSION CLPT_HAS_PBR
#endif
#ifndef CLPT_HAS_PBR_VOLUME
#define CLPT_HAS_PBR_VOLUME CLPT_HAS_PBR_TRANSMISSION
#endif

#if CLPT_HAS_PBR
#include "pbr_albedo_table.h"

/* pbrt-v4's "effectively smooth" bound: a lobe narrower than about 1e-3 radians, whose D
 * (1 / (pi alpha^2) at its peak) would also lose float precision as alpha shrinks further. */
#define CLPT_PBR_DELTA_ALPHA ((real)1e-3f)

/* The material's parameters as the lobes use them. */
typedef struct PbrParams {
  Vec3 base;         /* base colour, [0, 1] per channel */
  real metallic;     /* [0, 1] */
  real alpha;        /* roughness^2 */
  real f0;           /* dielectric reflectance at normal incidence, ((ior - 1) / (ior + 1))^2 */
  real transmission; /* [0, 1] */
  int delta;         /* alpha < CLPT_PBR_DELTA_ALPHA: specular and transmission are delta lobes */
  int volume;        /* the transmission refracts into a volume (KHR_materials_volume, thickness > 0) */
  real ior;          /* index of refraction inside */
  real eta;          /* volume: index on the far side of the surface / on wo's side (the frame's) */
  real table_s;      /* sqrt(roughness): the albedo table's roughness coordinate */
  CLPT_ABI_PAD(int, 1)
} PbrParams;

CLPT_INLINE PbrParams pbr_params(Vec3 base, real metallic, real roughness, real ior, real transmission, int volume) {
  PbrParams p;
  p.base = base;
  p.metallic = metallic;
  p.alpha = roughness * roughness;
  const real r = (ior - (real)1) / (ior + (real)1);
  p.f0 = r * r;
  p.transmission = transmission;
  p.delta = p.alpha < CLPT_PBR_DELTA_ALPHA ? 1 : 0;
  p.volume = volume;
  p.ior = ior;
  p.eta = ior;
  p.table_s = clpt_sqrt(roughness);
  return p;
}

/* (1 - c)^5 for c in [0, 1] (clamped), Schlick's weight. */
CLPT_INLINE real schlick_weight(real c) {
  const real m0 = (real)1 - c;
  const real m = m0 < (real)0 ? (real)0 : (m0 > (real)1 ? (real)1 : m0);
  const real m2 = m * m;
  return m2 * m2 * m;
}

/* GGX normal distribution D(h) for cos(theta_h) = cos_h, alpha^2 = alpha2. */
CLPT_INLINE real ggx_d(real alpha2, real cos_h) {
  const real k = cos_h * cos_h * (alpha2 - (real)1) + (real)1;
  return cos_h > (real)0 ? alpha2 / (CLPT_PI * k * k) : (real)0;
}

/* Height-correlated Smith visibility V = G2 / (4 cos_o cos_i) (cosines >= 0). */
CLPT_INLINE real ggx_visibility(real alpha2, real cos_o, real cos_i) {
  const real a = cos_i * clpt_sqrt(alpha2 + ((real)1 - alpha2) * cos_o * cos_o);
  const real b = cos_o * clpt_sqrt(alpha2 + ((real)1 - alpha2) * cos_i * cos_i);
  const real den = a + b;
  return den > (real)0 ? (real)0.5f / den : (real)0;
}

/* Smith's masking G1 of the direction with cosine cos_o. */
CLPT_INLINE real ggx_g1(real alpha2, real cos_o) {
  return (real)2 * cos_o / (cos_o + clpt_sqrt(alpha2 + ((real)1 - alpha2) * cos_o * cos_o));
}

/* Solid-angle density of the reflected direction whose half vector has cosine cos_h, when the
 * half vector is drawn from the visible normals of wo: D_wo(h) / (4 wo.h) = G1(wo) D(h) / (4 cos_o). */
CLPT_INLINE real ggx_reflection_pdf(real alpha2, real cos_o, real cos_h) {
  return ggx_g1(alpha2, cos_o) * ggx_d(alpha2, cos_h) / ((real)4 * cos_o);
}

/* A GGX visible normal for wo (local frame, wo.z > 0), Heitz 2018's construction. */
CLPT_INLINE Vec3 ggx_sample_visible_normal(Vec3 wo, real alpha, real u0, real u1) {
  const Vec3 vh = v3_normalize(v3(alpha * wo.x, alpha * wo.y, wo.z));
  const real len2 = vh.x * vh.x + vh.y * vh.y;
  const real inv_len = len2 > (real)0 ? (real)1 / clpt_sqrt(len2) : (real)0;
  const Vec3 t1 = v3_select(len2 > (real)0, v3(-vh.y * inv_len, vh.x * inv_len, (real)0), v3((real)1, (real)0, (real)0));
  const Vec3 t2 = v3(vh.y * t1.z - vh.z * t1.y, vh.z * t1.x - vh.x * t1.z, vh.x * t1.y - vh.y * t1.x);
  const real r = clpt_sqrt(u0);
  const Float2 circle = unit_circle(u1);
  const real p1 = r * circle.x;
  const real s = (real)0.5f * ((real)1 + vh.z);
  const real p2 = ((real)1 - s) * clpt_sqrt(fmax((real)0, (real)1 - p1 * p1)) + s * r * circle.y;
  const real up = clpt_sqrt(fmax((real)0, (real)1 - p1 * p1 - p2 * p2));
  const Vec3 nh = v3_add(v3_add(v3_scale(t1, p1), v3_scale(t2, p2)), v3_scale(vh, up));
  return v3_normalize(v3(alpha * nh.x, alpha * nh.y, fmax((real)1e-7f, nh.z)));
}

/* The specular layer's albedo at cos_o (pbr_albedo_table.h): S and B, E = F0 S + F90 B, and G,
 * bilinear in (sqrt(cos_o), sqrt(roughness)) = (t, s), the table's grid. */
typedef struct PbrAlbedo {
  real s, b, g;
  CLPT_ABI_PAD(real, 2)
} PbrAlbedo;

CLPT_INLINE PbrAlbedo pbr_albedo(real cos_o, real table_s) {
  const real ft = clpt_sqrt(fmin(fmax(cos_o, (real)0), (real)1)) * (real)(CLPT_PBR_ALBEDO_NMU - 1);
  const real fs = fmin(fmax(table_s, (real)0), (real)1) * (real)(CLPT_PBR_ALBEDO_NR - 1);
  const int i = min((int)ft, CLPT_PBR_ALBEDO_NMU - 2), j = min((int)fs, CLPT_PBR_ALBEDO_NR - 2);
  const real a = ft - (real)i, c = fs - (real)j;
  const int k00 = 2 * (j * CLPT_PBR_ALBEDO_NMU + i), k10 = k00 + 2 * CLPT_PBR_ALBEDO_NMU;
  const real w00 = ((real)1 - a) * ((real)1 - c), w01 = a * ((real)1 - c), w10 = ((real)1 - a) * c, w11 = a * c;
  PbrAlbedo e;
  e.s = w00 * (real)clpt_pbr_albedo[k00] + w01 * (real)clpt_pbr_albedo[k00 + 2] + w10 * (real)clpt_pbr_albedo[k10] +
        w11 * (real)clpt_pbr_albedo[k10 + 2];
  e.b = w00 * (real)clpt_pbr_albedo[k00 + 1] + w01 * (real)clpt_pbr_albedo[k00 + 3] +
        w10 * (real)clpt_pbr_albedo[k10 + 1] + w11 * (real)clpt_pbr_albedo[k10 + 3];
  e.g = ((real)1 - a) * (real)clpt_pbr_fresnel_mean[i] + a * (real)clpt_pbr_fresnel_mean[i + 1];
  return e;
}

/* The lobes' sampling probabilities at wo (they sum to 1), and the base layer's weights there. */
typedef struct PbrLobes {
  real diffuse;
  real specular;
  real transmission;
  real base_keep;    /* (1 - metallic) (1 - E(n.wo)): the base layer's albedo per unit base colour */
  real base_scale;   /* (1 - metallic) (1 - E(n.wo)) / (1 - G(n.wo)): fresnel_mix's diffuse scaled to it */
  CLPT_ABI_PAD(real, 2)
} PbrLobes;

CLPT_INLINE PbrLobes pbr_lobes(const PbrParams* p, real cos_o) {
  PbrAlbedo e = pbr_albedo(cos_o, p->table_s);
  /* A delta lobe's albedo is its Fresnel term at n.wo, exactly. */
  const real sw = schlick_weight(cos_o);
  e.s = p->delta ? (real)1 - sw : e.s;
  e.b = p->delta ? sw : e.b;
  const real e_dielectric = p->f0 * e.s + e.b;
  const real fresnel_mean = p->f0 + ((real)1 - p->f0) * e.g;
  const real base_mean = (p->base.x + p->base.y + p->base.z) * (real)(1.0f / 3.0f);
  const real e_metal = base_mean * e.s + e.b;
  /* The specular lobe keeps a floor: where its albedo is 0 (a black metal seen head on), f may
   * still be above 0 for other half vectors. */
  const real specular = ((real)1 - p->metallic) * e_dielectric + p->metallic * e_metal + (real)1e-3f;
  const real keep = ((real)1 - p->metallic) * fmax((real)0, (real)1 - e_dielectric);
  const real under = keep * base_mean;
  const real total = specular + under;
  PbrLobes l;
  l.specular = specular / total;
  l.transmission = under * p->transmission / total;
  l.diffuse = (real)1 - l.specular - l.transmission;
  l.base_keep = keep;
  l.base_scale = keep / ((real)1 - fresnel_mean);
  return l;
}

#if CLPT_HAS_PBR_VOLUME
/* The rough refraction into (or out of) a volume, Walter et al. 2007's microfacet BTDF with the
 * GGX D and the height-correlated G2, as pbrt-v4's dielectric forms it: f cos towards wi (below
 * the surface, wo above) and in *pdf the density of wi when the half vector is a visible normal
 * of wo refracted with p->eta. Weighted by the base layer's (1 - metallic) transmission base and
 * Schlick's transmittance at wo.h; radiance is scaled by 1 / eta^2. 0 for a delta lobe. */
CLPT_INLINE Vec3 pbr_refraction_eval(const PbrParams* p, Vec3 wo, Vec3 wi, real* pdf) {
  const real eta = p->eta;
  Vec3 wm = v3_add(v3_scale(wi, eta), wo);
  const real len2 = v3_dot(wm, wm);
  wm = v3_scale(wm, len2 > (real)0 ? (real)1 / clpt_sqrt(len2) : (real)0);
  wm = v3_select(wm.z < (real)0, v3_neg(wm), wm);
  const real i_m = v3_dot(wi, wm), o_m = v3_dot(wo, wm);
  const real cos_o = wo.z, cos_i = fabs(wi.z);
  const real root = i_m + o_m / eta;
  const real denom = root * root;
  const real alpha2 = p->alpha * p->alpha;
  /* Microfacets facing away from either direction carry nothing. */
  const bool ok = p->delta == 0 && len2 > (real)0 && i_m < (real)0 && o_m > (real)0 && denom > (real)0 && cos_i > (real)0;
  const real d = ggx_d(alpha2, wm.z);
  const real g2 = (real)4 * ggx_visibility(alpha2, cos_o, cos_i) * cos_o * cos_i;
  const real transmittance = (real)1 - (p->f0 + ((real)1 - p->f0) * schlick_weight(o_m));
  const real f = d * g2 * fabs(i_m * o_m) / (denom * cos_i * cos_o) / (eta * eta);
  *pdf = ok ? ggx_g1(alpha2, cos_o) * d * o_m / cos_o * fabs(i_m) / denom : (real)0;
  const real weight = ok ? ((real)1 - p->metallic) * p->transmission * transmittance * f * cos_i : (real)0;
  return v3_scale(p->base, weight);
}

/* wo (above) refracted through the microfacet normal m into the far side with p->eta; *tir when
 * there is no refracted direction (then the reflection about m is returned). */
CLPT_INLINE Vec3 pbr_refract(const PbrParams* p, Vec3 wo, Vec3 m, bool* tir) {
  const real c = v3_dot(wo, m);
  const real sin2_t = ((real)1 - c * c) / (p->eta * p->eta);
  *tir = sin2_t >= (real)1;
  const real cos_t = clpt_sqrt(fmax((real)0, (real)1 - sin2_t));
  const Vec3 refracted = v3_add_scaled(v3_scale(wo, (real)-1 / p->eta), m, c / p->eta - cos_t);
  return v3_select(*tir, v3_add_scaled(v3_neg(wo), m, (real)2 * c), refracted);
}
#endif

/* f cos(theta_i) towards wi and, in *pdf, the density with which pbr_sample_local draws wi; both
 * in the local frame (z the normal on wo's side, wo.z > 0), delta lobes left out. */
CLPT_INLINE Vec3 pbr_eval_local(const PbrParams* p, const PbrLobes* lobes, Vec3 wo, Vec3 wi, real* pdf) {
  const real cos_o = wo.z;
  const bool above = wi.z > (real)0;
  const real cos_i = fabs(wi.z);
  /* The thin-walled transmission's lobe is the specular one of wi mirrored above the surface. */
  const Vec3 h = v3_normalize(v3_add(wo, v3(wi.x, wi.y, cos_i)));
  const real o_dot_h = v3_dot(wo, h);
  const real alpha2 = p->alpha * p->alpha;
  const real specular = p->delta ? (real)0 : ggx_d(alpha2, h.z) * ggx_visibility(alpha2, cos_o, cos_i);
  const real w = schlick_weight(o_dot_h);
  const real fresnel = p->f0 + ((real)1 - p->f0) * w;
  const Vec3 fresnel_metal = v3_add(p->base, v3_scale(v3_sub(v3_splat((real)1), p->base), w));
  /* The base layer: fresnel_mix's diffuse at the half vector, scaled to the albedo 1 - E. */
  const real diffuse = ((real)1 - fresnel) * lobes->base_scale * ((real)1 - p->transmission) / CLPT_PI;
  const Vec3 reflected = v3_add(v3_add(v3_scale(p->base, diffuse), v3_splat(((real)1 - p->metallic) * fresnel * specular)),
                                v3_scale(fresnel_metal, p->metallic * specular));
  Vec3 transmitted = v3_scale(p->base, lobes->base_keep * p->transmission * specular);
  const real specular_pdf = p->delta ? (real)0 : ggx_reflection_pdf(alpha2, cos_o, h.z);
  const real p_above = lobes->diffuse * cos_i / CLPT_PI + lobes->specular * specular_pdf;
  real p_below = lobes->transmission * specular_pdf;
#if CLPT_HAS_PBR_VOLUME
  real volume_pdf;
  const Vec3 refracted = pbr_refraction_eval(p, wo, wi, &volume_pdf);
  transmitted = v3_select(p->volume != 0, v3_scale(refracted, (real)1 / cos_i), transmitted);
  p_below = p->volume != 0 ? lobes->transmission * volume_pdf : p_below;
#endif
  *pdf = above ? p_above : p_below;
  return v3_scale(v3_select(above, reflected, transmitted), cos_i);
}

/* A direction from the lobe mixture (local frame), its weight f cos / pdf in *weight and its
 * density in *pdf (0 for a delta lobe). */
CLPT_INLINE Vec3 pbr_sample_local(const PbrParams* p, const PbrLobes* lobes, Vec3 wo, Uniform4 u, Vec3* weight,
                                  real* pdf) {
  const bool pick_diffuse = u.u2 < lobes->diffuse;
  const bool pick_transmission = !pick_diffuse && u.u2 >= lobes->diffuse + lobes->specular;
  const Float2 circle = unit_circle(u.u0);
  const real radius = clpt_sqrt(u.u1);
  const Vec3 diffuse = v3(radius * circle.x, radius * circle.y, clpt_sqrt(fmax((real)0, (real)1 - radius * radius)));
  const Vec3 h = v3_select(p->delta != 0, v3((real)0, (real)0, (real)1), ggx_sample_visible_normal(wo, p->alpha, u.u0, u.u1));
  const Vec3 reflected = v3_add_scaled(v3_neg(wo), h, (real)2 * v3_dot(wo, h));
  Vec3 transmitted = v3(reflected.x, reflected.y, -reflected.z);
#if CLPT_HAS_PBR_VOLUME
  bool tir;
  const Vec3 refracted = pbr_refract(p, wo, h, &tir);
  transmitted = v3_select(p->volume != 0, refracted, transmitted);
#endif
  const Vec3 wi = v3_select(pick_diffuse, diffuse, v3_select(pick_transmission, transmitted, reflected));
  Vec3 f_cos = pbr_eval_local(p, lobes, wo, wi, pdf);
  Vec3 w = v3_scale(f_cos, *pdf > (real)0 ? (real)1 / *pdf : (real)0);
  /* Delta lobes: the specular's Fresnel at n.wo, the transmission straight on. */
  const real sw = schlick_weight(wo.z);
  const Vec3 delta_specular = v3_scale(
      v3_add(v3_splat(((real)1 - p->metallic) * (p->f0 + ((real)1 - p->f0) * sw)),
             v3_scale(v3_add(p->base, v3_scale(v3_sub(v3_splat((real)1), p->base), sw)), p->metallic)),
      (real)1 / lobes->specular);
  real delta_transmitted = lobes->base_keep * p->transmission;
  bool valid = pick_diffuse || reflected.z > (real)0;
#if CLPT_HAS_PBR_VOLUME
  /* Smooth refraction: Schlick's transmittance, radiance scaled by 1 / eta^2; under total internal
   * reflection everything reflects. A rough one is valid when it went below the surface. */
  const real volume_delta = tir ? (real)1 : ((real)1 - p->f0 - ((real)1 - p->f0) * sw) / (p->eta * p->eta);
  delta_transmitted = p->volume != 0 ? ((real)1 - p->metallic) * p->transmission * volume_delta : delta_transmitted;
  const bool refraction_valid = p->delta != 0 || (!tir && refracted.z < (real)0);
  valid = p->volume != 0 && pick_transmission ? refraction_valid : valid;
#endif
  const Vec3 delta_transmission =
      v3_scale(p->base, lobes->transmission > (real)0 ? delta_transmitted / lobes->transmission : (real)0);
  const bool delta_pick = p->delta != 0 && !pick_diffuse;
  w = v3_select(delta_pick, v3_select(pick_transmission, delta_transmission, delta_specular), w);
  *pdf = delta_pick ? (real)0 : *pdf;
  /* A reflection below the surface (its mirror, the transmission, above it) carries nothing. */
  *weight = v3_select(valid && v3_all_finite(w), w, v3_splat((real)0));
  *pdf = valid && is_finite_real(*pdf) ? *pdf : (real)0;
  return wi;
}

/* The world-frame wrappers, for a ray arriving along d (unit) at a surface of outward normal n:
 * the frame's z is the normal on the side the ray came from (both sides shade alike). */
typedef struct PbrFrame {
  Vec3 t, b, n;
  Vec3 wo; /* local */
} PbrFrame;

CLPT_INLINE PbrFrame pbr_frame(Vec3 d, Vec3 n) {
  PbrFrame f;
  f.n = v3_select(v3_dot(n, d) < (real)0, n, v3_neg(n));
  orthonormal_basis(f.n, &f.t, &f.b);
  const Vec3 wo = v3_neg(d);
  f.wo = v3(v3_dot(wo, f.t), v3_dot(wo, f.b), fmax((real)1e-7f, v3_dot(wo, f.n)));
  return f;
}

/* The parameters as seen from the side d arrives on: a volume's eta is ior entering (d against
 * the outward normal n), 1 / ior leaving. */
CLPT_INLINE PbrParams pbr_params_facing(const PbrParams* p, Vec3 d, Vec3 n) {
  PbrParams q = *p;
  q.eta = v3_dot(n, d) < (real)0 ? p->ior : (real)1 / p->ior;
  return q;
}

CLPT_INLINE Vec3 bsdf_pbr_sample(Vec3 d, Vec3 n, const PbrParams* params, Uniform4 u, Vec3* weight, real* pdf) {
  const PbrParams q = pbr_params_facing(params, d, n);
  const PbrParams* p = &q;
  const PbrFrame f = pbr_frame(d, n);
  const PbrLobes lobes = pbr_lobes(p, f.wo.z);
  const Vec3 wi = pbr_sample_local(p, &lobes, f.wo, u, weight, pdf);
  return v3_add(v3_add(v3_scale(f.t, wi.x), v3_scale(f.b, wi.y)), v3_scale(f.n, wi.z));
}

CLPT_INLINE Vec3 bsdf_pbr_eval(Vec3 d, Vec3 n, const PbrParams* params, Vec3 wi, real* pdf) {
  const PbrParams q = pbr_params_facing(params, d, n);
  const PbrParams* p = &q;
  const PbrFrame f = pbr_frame(d, n);
  const PbrLobes lobes = pbr_lobes(p, f.wo.z);
  const Vec3 wi_local = v3(v3_dot(wi, f.t), v3_dot(wi, f.b), v3_dot(wi, f.n));
  const Vec3 f_cos = pbr_eval_local(p, &lobes, f.wo, wi_local, pdf);
  const bool ok = v3_all_finite(f_cos) && is_finite_real(*pdf);
  *pdf = ok ? *pdf : (real)0;
  return v3_select(ok, f_cos, v3_splat((real)0));
}

#endif /* CLPT_HAS_PBR */

#endif
