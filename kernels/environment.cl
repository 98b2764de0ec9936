/* environment.cl: the environment light: radiance arriving from infinitely far along each
 * direction, from an equirectangular image or one colour (docs/environment.md).
 *
 * Mapping, in clpt's +Y-up world, of a direction d given in the environment's own frame (the world
 * direction turned by -rotation_deg about +Y, i.e. its azimuth plus the rotation, which is a shift
 * of u by rotation_deg / 360): the image's top row is the zenith,
 *   v = acos(d.y) / pi            (0 at the top row's top edge, 1 at the bottom row's bottom edge)
 *   u = 0.5 + atan2(d.z, d.x) / (2 pi)
 * so the image's horizontal centre looks along +X, u = 0.25 along -Z and u = 0.75 along +Z. The
 * lookup is nearest-texel: the radiance is piecewise constant over the texels, exactly the
 * distribution the sampler draws from, so a texel's samples carry radiance / pdf proportional to
 * 1 / sin(theta) within its row and nothing else (a bright sun of a few texels costs no noise of
 * its own).
 *
 * Sampling (nee, CLPT_HAS_ENVIRONMENT 1): a piecewise-constant 2D distribution over
 * f = luminance x sin(theta) (theta at the row's centre), built on the host in double
 * (scene/environment_map.h): a row by the rows' alias table, then a texel by that row's, each in
 * constant time (two reads and a select, as the light pick, light.cl), then a point uniformly in
 * the texel from what is left of the two draws. Its solid-angle density is
 * p(d) = p_uv(texel) / (2 pi^2 sin(theta)). A light sample is the environment's with probability
 * GpuEnvironment.pick_probability (u3 of the light draw decides), else the light list's; each
 * density includes its choice, and the BSDF-sampled ray that escapes is weighted against the
 * environment's density by the power heuristic (path.cl), as a hit on any other light is.
 *
 * CLPT_HAS_ENVIRONMENT (kernel_options.cpp): 0 none (nothing here is compiled), 1 an image,
 * 2 a constant colour, which escaping rays see and nothing samples: BSDF sampling alone is
 * already proportional to the integrand for a uniform light, so a light sample would only add
 * variance and a shadow ray (docs/environment.md). The generic kernel compiles 1 and reads the
 * host's packing, where a constant is a 1x1 image and no environment a black one never sampled. */
#ifndef CLPT_ENVIRONMENT_CL
#define CLPT_ENVIRONMENT_CL

#include "types.h"
#include "maths.cl"
#include "light.cl"

/* How far an environment light sample's shadow ray looks, world units (as a directional light's). */
#define CLPT_ENVIRONMENT_DISTANCE CLPT_DIRECTIONAL_DISTANCE

#if CLPT_HAS_ENVIRONMENT

/* atan2 and the angles of a texel without the library's atan2, acos, sin and cos: those are calls
 * that PoCL cannot vectorise across work-items ("instruction cannot be vectorized": with them the
 * image kernels ran 20x slower), as for unit_circle (maths.cl). Likewise no pair of operations of
 * one shape on two values (fabs of both arguments, a rotation's two rows): PoCL runs LLVM's SLP
 * vectoriser first, which packs such pairs into <2 x float>, and a work-item loop holding a
 * vector-typed value is not vectorised ("instruction return type cannot be vectorized"). atan on [0, 1]:
 * above tan(pi/12), atan t = pi/6 + atan((t sqrt 3 - 1) / (t + sqrt 3)), which brings the argument
 * to [0, tan(pi/12)] = [0, 0.268]; there the Taylor series to t^23, whose first omitted term is
 * below 3e-16. Branch-free (selects). */
CLPT_INLINE real environment_atan01(real t) {
  const real tan_pi_12 = (real)0.2679491924311227;
  const real sqrt3 = (real)1.7320508075688772;
  const bool reduce = t > tan_pi_12;
  const real x = reduce ? (t * sqrt3 - (real)1) / (t + sqrt3) : t;
  const real x2 = x * x;
  const real series =
      x * ((real)1 + x2 * ((real)-1 / 3 + x2 * ((real)1 / 5 + x2 * ((real)-1 / 7 + x2 * ((real)1 / 9 +
      x2 * ((real)-1 / 11 + x2 * ((real)1 / 13 + x2 * ((real)-1 / 15 + x2 * ((real)1 / 17 + x2 * ((real)-1 / 19 +
      x2 * ((real)1 / 21 + x2 * ((real)-1 / 23))))))))))));
  return reduce ? CLPT_PI / (real)6 + series : series;
}

/* atan2(y, x) in [-pi, pi]; 0 at the origin. */
CLPT_INLINE real environment_atan2(real y, real x) {
  /* |x| and |y| and then the larger and the smaller, each formed differently: two operations of
   * one shape side by side are what LLVM's SLP vectoriser packs into a <2 x float> (see above). */
  const real ax = fabs(x), ay = y < (real)0 ? -y : y;
  const bool steep = ay > ax;
  const real big = steep ? ay : ax, small = (ax + ay) - big;
  const real t = big > (real)0 ? small / big : (real)0;
  const real a0 = environment_atan01(t);
  const real a1 = steep ? CLPT_PI * (real)0.5f - a0 : a0;
  const real a2 = x < (real)0 ? CLPT_PI - a1 : a1;
  return y < (real)0 ? -a2 : a2;
}

CLPT_INLINE __global const float* environment_words(__global const GpuEnvironment* env) {
  return (__global const float*)env;
}

/* The texel (row-major index) that world direction d looks at, and sin(theta) there. */
CLPT_INLINE uint environment_texel(__global const GpuEnvironment* env, Vec3 d, real* sin_theta) {
  const real length2 = v3_dot(d, d);
  const real y0 = length2 > (real)0 ? d.y / clpt_sqrt(length2) : (real)1;
  const real y = y0 > (real)1 ? (real)1 : (y0 < (real)-1 ? (real)-1 : y0);
  const real s2 = (real)1 - y * y;
  const real s = clpt_sqrt(s2 > (real)0 ? s2 : (real)0);
  const real v = environment_atan2(s, y) * ((real)1 / CLPT_PI); /* acos(y) / pi */
  /* The rotation about +Y is a shift of u: wrapped into [0, 1). */
  const real u0 = (real)0.5f + environment_atan2(d.z, d.x) * ((real)0.5f / CLPT_PI) + (real)env->rotation_turns;
  const real u1 = u0 - floor(u0);
  const real u = u1 > (real)0 ? u1 : (real)0;
  const uint width = env->width, height = env->height;
  const uint column = min((uint)(u * (real)width), width - 1u);
  const uint row = min((uint)(v * (real)height), height - 1u);
  *sin_theta = s;
  return row * width + column;
}

CLPT_INLINE Vec3 environment_texel_radiance(__global const GpuEnvironment* env, uint texel) {
  __global const float* rgb = environment_words(env) + env->texel_offset + 3u * texel;
  return v3((real)rgb[0], (real)CLPT_Y_APART(rgb), (real)rgb[2]); /* y apart: as above */
}

/* Radiance arriving along -d, i.e. seen looking along world direction d. */
CLPT_INLINE Vec3 environment_radiance(__global const GpuEnvironment* env, Vec3 d) {
#if CLPT_HAS_ENVIRONMENT == 2
  (void)d;
  return v3_load_global(env->radiance);
#else
  real sin_theta;
  return environment_texel_radiance(env, environment_texel(env, d, &sin_theta));
#endif
}

#if CLPT_HAS_ENVIRONMENT == 1
/* Solid-angle density p_uv / (2 pi^2 sin(theta)) from a texel's density in (u, v). */
CLPT_INLINE real environment_solid_angle_pdf(real density_uv, real sin_theta) {
  const real denominator = (real)2 * CLPT_PI * CLPT_PI * sin_theta;
  return denominator > (real)0 ? density_uv / denominator : (real)0;
}

/* Density with which environment_sample draws world direction d (the pick not included). */
CLPT_INLINE real environment_pdf(__global const GpuEnvironment* env, Vec3 d) {
  real sin_theta;
  const uint texel = environment_texel(env, d, &sin_theta);
  return environment_solid_angle_pdf((real)environment_words(env)[env->density_offset + texel], sin_theta);
}

/* Walker's alias draw over the n (threshold, alias) pairs at `table`: slot floor(u n), kept when
 * the fraction of u n is below its threshold, else its alias. *rest: the fraction rescaled to
 * [0, 1), a uniform number independent of the choice (what positions the point in the texel). */
CLPT_INLINE uint environment_alias_draw(__global const float* table, uint n, float u, float* rest) {
  const float scaled = u * (float)n;
  const uint slot = min((uint)scaled, n - 1u);
  const float f0 = scaled - (float)slot;
  const float fraction = f0 < 1.0f ? f0 : 0.99999994f;
  const float threshold = table[2u * slot];
  const uint alias = ((__global const uint*)table)[2u * slot + 1u];
  const bool keep = fraction < threshold;
  const float kept = threshold > 0.0f ? fraction / threshold : 0.0f;
  const float other = threshold < 1.0f ? (fraction - threshold) / (1.0f - threshold) : 0.0f;
  const float r = keep ? kept : other;
  *rest = r < 0.99999994f ? (r > 0.0f ? r : 0.0f) : 0.99999994f;
  return keep ? slot : alias;
}

/* A direction drawn from the environment's distribution with u0 (the row) and u1 (the texel in
 * it): world direction, the radiance it brings, its solid-angle density (the pick not included). */
typedef struct EnvironmentSample {
  Vec3 direction;
  Vec3 radiance;
  real pdf;
} EnvironmentSample;

CLPT_INLINE EnvironmentSample environment_sample(__global const GpuEnvironment* env, Uniform4 u) {
  __global const float* words = environment_words(env);
  const uint width = env->width, height = env->height;
  float row_rest, column_rest;
  const uint row = environment_alias_draw(words + env->row_alias_offset, height, u.u0, &row_rest);
  const uint column =
      environment_alias_draw(words + env->column_alias_offset + 2u * row * width, width, u.u1, &column_rest);
  const real uu = ((real)column + (real)column_rest) / (real)width;
  const real vv = ((real)row + (real)row_rest) / (real)height;
  /* In the world, phi = 2 pi (uu - rotation_turns - 1/2): (cos, sin) = -unit_circle(that + 1/2),
   * its argument wrapped into [0, 1); theta = pi vv = 2 pi (vv / 2). */
  const real turned0 = uu - (real)env->rotation_turns;
  const Float2 azimuth = unit_circle(turned0 - floor(turned0));
  const Float2 polar = unit_circle(vv * (real)0.5f);
  const real sin_theta = polar.y > (real)0 ? polar.y : (real)0;
  const Vec3 in_frame = v3(-sin_theta * azimuth.x, polar.x, -sin_theta * azimuth.y);
  const uint texel = row * width + column;
  EnvironmentSample s;
  s.direction = in_frame;
  s.radiance = environment_texel_radiance(env, texel);
  s.pdf = environment_solid_angle_pdf((real)words[env->density_offset + texel], sin_theta);
  return s;
}

/* Next-event estimation's choice between the environment and the light list for the light draw u
 * at x: with probability pick_probability (u3 below it) *ls becomes the environment's sample, a
 * direction with no end (its shadow ray runs CLPT_ENVIRONMENT_DISTANCE, stopped by anything, no
 * sphere or triangle skipped at the far end); either way its density includes the choice. */
CLPT_INLINE void environment_light_choice(__global const GpuEnvironment* env, Vec3 x, Uniform4 u, LightSample* ls) {
  const real pick = (real)env->pick_probability;
  const bool chosen = (real)u.u3 < pick;
  const EnvironmentSample es = environment_sample(env, u);
  ls->direction = v3_select(chosen, es.direction, ls->direction);
  ls->distance = chosen ? CLPT_ENVIRONMENT_DISTANCE : ls->distance;
  ls->pdf = chosen ? pick * es.pdf : ((real)1 - pick) * ls->pdf;
  ls->pdf = is_finite_real(ls->pdf) ? ls->pdf : (real)0;
  ls->sphere = chosen ? -1 : ls->sphere;
  ls->triangle = chosen ? -1 : ls->triangle;
  ls->delta = chosen ? 0 : ls->delta;
  ls->emission = v3_select(chosen, es.radiance, ls->emission);
  ls->target = v3_select(chosen, v3_add_scaled(x, es.direction, CLPT_ENVIRONMENT_DISTANCE), ls->target);
}
#endif /* CLPT_HAS_ENVIRONMENT == 1 */

#endif /* CLPT_HAS_ENVIRONMENT */

#endif
