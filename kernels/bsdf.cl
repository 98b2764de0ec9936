/* bsdf.cl: sampling the book's three materials and the mirror.
 *
 * Each sampler takes the incoming ray direction `d` (unit, travelling towards the surface), the
 * outward unit normal `n` and uniforms `u`, and returns the next direction; *weight receives
 * f cos / pdf, the factor by which the path throughput is multiplied (0 ends the path).
 * The estimator is the book's (docs/book-scenes.md, "The estimator"):
 *  - Lambertian: cosine-weighted around the normal facing the ray; weight rho.
 *  - Normalised Phong: f = rho (n+2)/(2 pi) cos^n(alpha) around the mirror direction, sampled
 *    from the cos^n lobe, weight rho (n+2)/(n+1) cos(theta_out); 0 below the surface.
 *  - Glass: exact unpolarised Fresnel, total internal reflection, reflect with probability Fr,
 *    else refract with radiance scaled by (n_from / n_to)^2; weight rho (times that scale).
 *  - Mirror: the perfect specular reflection about n; weight rho. */
#ifndef CLPT_BSDF_CL
#define CLPT_BSDF_CL

#include "maths.cl"

/* Cosine-weighted direction around unit n; pdf cos(theta) / pi. */
CLPT_INLINE Vec3 sample_cosine_hemisphere(Vec3 n, real u0, real u1) {
  const Float2 circle = unit_circle(u0);
  const real radius = clpt_sqrt(u1);
  /* cos(theta) from the radius rather than from u1: two independent square roots side by side get
   * paired by LLVM's SLP vectoriser under fast maths (<2 x float> sqrt), and PoCL's work-item
   * vectoriser then keeps the whole lockstep megakernel scalar (docs/performance.md, "Presets"). */
  const real cos_theta = clpt_sqrt(fmax((real)0, (real)1 - radius * radius));
  return to_world(v3(radius * circle.x, radius * circle.y, cos_theta), n);
}

/* Direction around unit axis with pdf (exponent+1)/(2 pi) cos^exponent(alpha). */
CLPT_INLINE Vec3 sample_phong_lobe(Vec3 axis, real exponent, real u0, real u1) {
  const Float2 circle = unit_circle(u0);
  const real cos_alpha = pow_unit(u1, (real)1 / (exponent + (real)1));
  const real sin_alpha = clpt_sqrt(fmax((real)0, (real)1 - cos_alpha * cos_alpha));
  return to_world(v3(sin_alpha * circle.x, sin_alpha * circle.y, cos_alpha), axis);
}

CLPT_INLINE Vec3 reflect_about(Vec3 d, Vec3 n) { return v3_add_scaled(d, n, (real)-2 * v3_dot(n, d)); }

CLPT_INLINE Vec3 bsdf_lambertian_sample(Vec3 d, Vec3 n, Vec3 rho, Uniform4 u, Vec3* weight) {
  const Vec3 facing = v3_select(v3_dot(n, d) < 0.0f, n, v3_neg(n));
  *weight = rho;
  return sample_cosine_hemisphere(facing, u.u0, u.u1);
}

CLPT_INLINE Vec3 bsdf_phong_sample(Vec3 d, Vec3 n, Vec3 rho, real exponent, Uniform4 u, Vec3* weight) {
  const Vec3 out = sample_phong_lobe(reflect_about(d, n), exponent, u.u0, u.u1);
  const real cos_out = v3_dot(n, out);
  *weight = v3_scale(rho, cos_out > (real)0 ? (exponent + (real)2) / (exponent + (real)1) * cos_out : (real)0);
  return out;
}

/* Perfect mirror: the reflection about n (either side), weight rho; a delta lobe like glass's. */
CLPT_INLINE Vec3 bsdf_mirror_sample(Vec3 d, Vec3 n, Vec3 rho, Vec3* weight) {
  *weight = rho;
  return reflect_about(d, n);
}

/* Evaluation for next-event estimation: f cos(theta_wi) towards wi (unit, leaving the surface)
 * and, in *pdf, the solid-angle density with which the sampler above would have chosen wi. */
CLPT_INLINE Vec3 bsdf_lambertian_eval(Vec3 d, Vec3 n, Vec3 rho, Vec3 wi, real* pdf) {
  const Vec3 facing = v3_select(v3_dot(n, d) < (real)0, n, v3_neg(n));
  const real cos_wi = v3_dot(facing, wi);
  *pdf = cos_wi > (real)0 ? cos_wi / CLPT_PI : (real)0;
  return v3_scale(rho, *pdf); /* rho / pi * cos */
}

CLPT_INLINE Vec3 bsdf_phong_eval(Vec3 d, Vec3 n, Vec3 rho, real exponent, Vec3 wi, real* pdf) {
  const real cos_alpha = v3_dot(reflect_about(d, n), wi);
  const real lobe = cos_alpha > (real)0 ? pow_unit(cos_alpha, exponent) / ((real)2 * CLPT_PI) : (real)0;
  const real cos_out = v3_dot(n, wi);
  *pdf = (exponent + (real)1) * lobe;
  return v3_scale(rho, cos_out > (real)0 ? (exponent + (real)2) * lobe * cos_out : (real)0);
}

/* Unpolarised Fresnel reflectance for relative index eta = n_from / n_to, cosines of the
 * incident and transmitted angles (both >= 0). */
CLPT_INLINE real fresnel_dielectric(real eta, real cos_i, real cos_t) {
  const real r_s = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const real r_p = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return (real)0.5f * (r_s * r_s + r_p * r_p);
}

CLPT_INLINE Vec3 bsdf_glass_sample(Vec3 d, Vec3 n, Vec3 rho, real ior, Uniform4 u, Vec3* weight) {
  const bool entering = v3_dot(n, d) < (real)0;
  const Vec3 facing = v3_select(entering, n, v3_neg(n));
  const real eta = entering ? (real)1 / ior : ior; /* n_from / n_to */
  const real cos_i = -v3_dot(d, facing);
  const real sin2_t = eta * eta * ((real)1 - cos_i * cos_i);
  const real cos_t = clpt_sqrt(fmax((real)0, (real)1 - sin2_t));
  /* Total internal reflection, or reflection with probability Fr. */
  const bool reflect = sin2_t >= (real)1 || u.u2 < fresnel_dielectric(eta, cos_i, cos_t);
  *weight = v3_scale(rho, reflect ? (real)1 : eta * eta);
  const Vec3 refracted = v3_normalize(v3_add_scaled(v3_scale(d, eta), facing, eta * cos_i - cos_t));
  return v3_select(reflect, reflect_about(d, facing), refracted);
}

#endif
