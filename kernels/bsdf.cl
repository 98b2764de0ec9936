/* bsdf.cl: sampling the book's three materials.
 *
 * Each sampler takes the incoming ray direction `d` (unit, travelling towards the surface), the
 * outward unit normal `n` and uniforms `u`, and returns the next direction; *weight receives
 * f cos / pdf, the factor by which the path throughput is multiplied (0 ends the path).
 * The estimator is the book's (gemspt-scenes.md section 3):
 *  - Lambertian: cosine-weighted around the normal facing the ray; weight rho.
 *  - Normalised Phong: f = rho (n+2)/(2 pi) cos^n(alpha) around the mirror direction, sampled
 *    from the cos^n lobe, weight rho (n+2)/(n+1) cos(theta_out); 0 below the surface.
 *  - Glass: exact unpolarised Fresnel, total internal reflection, reflect with probability Fr,
 *    else refract with radiance scaled by (n_from / n_to)^2; weight rho (times that scale). */
#ifndef CLPT_BSDF_CL
#define CLPT_BSDF_CL

#include "maths.cl"

/* Cosine-weighted direction around unit n; pdf cos(theta) / pi. */
CLPT_INLINE float3 sample_cosine_hemisphere(float3 n, float2 u) {
  const float2 circle = unit_circle(u.x);
  const float radius = sqrt(u.y);
  const float3 local_dir = (float3)(radius * circle.x, radius * circle.y, sqrt(fmax(0.0f, 1.0f - u.y)));
  return to_world(local_dir, n);
}

/* Direction around unit axis with pdf (exponent+1)/(2 pi) cos^exponent(alpha). */
CLPT_INLINE float3 sample_phong_lobe(float3 axis, float exponent, float2 u) {
  const float2 circle = unit_circle(u.x);
  const float cos_alpha = pow(u.y, 1.0f / (exponent + 1.0f));
  const float sin_alpha = sqrt(fmax(0.0f, 1.0f - cos_alpha * cos_alpha));
  return to_world((float3)(sin_alpha * circle.x, sin_alpha * circle.y, cos_alpha), axis);
}

CLPT_INLINE float3 reflect_about(float3 d, float3 n) { return d - 2.0f * dot(n, d) * n; }

CLPT_INLINE float3 bsdf_lambertian_sample(float3 d, float3 n, float3 rho, float4 u, float3* weight) {
  const float3 facing = dot(n, d) < 0.0f ? n : -n;
  *weight = rho;
  return sample_cosine_hemisphere(facing, u.xy);
}

CLPT_INLINE float3 bsdf_phong_sample(float3 d, float3 n, float3 rho, float exponent, float4 u,
                                float3* weight) {
  const float3 mirror = reflect_about(d, n);
  const float3 out = sample_phong_lobe(mirror, exponent, u.xy);
  const float cos_out = dot(n, out);
  *weight = cos_out > 0.0f ? rho * ((exponent + 2.0f) / (exponent + 1.0f) * cos_out) : (float3)(0.0f);
  return out;
}

/* Unpolarised Fresnel reflectance for relative index eta = n_from / n_to, cosines of the
 * incident and transmitted angles (both >= 0). */
CLPT_INLINE float fresnel_dielectric(float eta, float cos_i, float cos_t) {
  const float r_s = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const float r_p = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5f * (r_s * r_s + r_p * r_p);
}

CLPT_INLINE float3 bsdf_glass_sample(float3 d, float3 n, float3 rho, float ior, float4 u,
                                float3* weight) {
  const bool entering = dot(n, d) < 0.0f;
  const float3 facing = entering ? n : -n;
  const float eta = entering ? 1.0f / ior : ior; /* n_from / n_to */
  const float cos_i = -dot(d, facing);
  const float sin2_t = eta * eta * (1.0f - cos_i * cos_i);
  const float3 mirror = reflect_about(d, facing);
  *weight = rho;
  if (sin2_t >= 1.0f) return mirror; /* total internal reflection */
  const float cos_t = sqrt(1.0f - sin2_t);
  if (u.z < fresnel_dielectric(eta, cos_i, cos_t)) return mirror;
  *weight = rho * (eta * eta);
  return normalize(eta * d + (eta * cos_i - cos_t) * facing);
}

#endif
