/* camera.cl: the book's pinhole camera, the orthographic camera and the sub-pixel samplers.
 *
 * Reads GpuRenderParams (camera, image size, sampler; the random numbers come from sampler.cl). Produces a unit direction from the
 * pinhole, which sits at the origin of the camera-relative device frame. Image row 0 is the
 * top of the picture; the sensor's "up" axis counts rows from the bottom, as in the book.
 * CLPT_HAS_ORTHOGRAPHIC (kernel_options.cpp; named only by a specialised kernel whose camera is
 * orthographic, 1 in the generic kernel, which reads GpuCamera.projection): parallel rays from
 * the sensor's points, which then lies around the camera-relative origin. */
#ifndef CLPT_CAMERA_CL
#define CLPT_CAMERA_CL

#include "types.h"
#include "maths.cl"
#include "rng.cl"
#include "sampler.cl"

#ifndef CLPT_HAS_ORTHOGRAPHIC
#ifdef CLPT_ESTIMATOR
#define CLPT_HAS_ORTHOGRAPHIC 0
#else
#define CLPT_HAS_ORTHOGRAPHIC 1
#endif
#endif

/* Position inside the pixel, in [0,1)^2, of sample `sample` of pixel `pixel`.
 * Grid: the centres of 4x4 strata, in order (the book's sampling).
 * Jitter: uniform inside one of 4x4 strata; within each group of 16 samples the strata are visited
 * in an order k -> (a k + b) mod 16 with random odd a and random b per (pixel, group), so every
 * single sample is uniform over the pixel and any sample count is unbiased.
 * Sobol: the first pair of sampler dimension 0 as it is (sampler.cl): every 2^k samples are
 * stratified in the pixel's elementary intervals of area 2^-k.
 * Sobol-grid: that pair's 4x4 stratum, at its centre: one of the grid's 16 positions. Each Sobol
 * point is uniform over the pixel, so each position has probability 1/16 and any sample count
 * converges to the grid's (the book's) image, which differs from the pixel's area average where an
 * edge crosses the pixel (sharpest at the light's rim). Every aligned block of 16 samples is a
 * (0,4,2)-net, one point per 4x4 stratum, so it visits each of the 16 positions exactly once:
 * 16 samples are the grid's own (in another order), fewer are a well-spread subset of them. */
CLPT_INLINE Float2 camera_subpixel(RngKey key, uint sampler, uint pixel, uint sample) {
  const uint k = sample & 15u;
  const Philox4 shuffle = philox4x32_10(philox4(pixel, sample >> 4, CLPT_DIM_STRATA, 0u), key.k0, key.k1);
  const Uniform4 u = sampler_uniform4(key, sampler, pixel, sample, 0u);
  const uint in_use = CLPT_SAMPLER_IN_USE(sampler);
  const bool grid = in_use == CLPT_SAMPLER_GRID;
  const bool sobol = in_use == CLPT_SAMPLER_SOBOL;
  const bool sobol_grid = in_use == CLPT_SAMPLER_SOBOL_GRID;
  /* u0, u1 are multiples of 2^-24 below 1, so 4 u is exact and its floor at most 3. */
  const uint sobol_stratum = (uint)floor((real)u.u0 * 4.0f) + 4u * (uint)floor((real)u.u1 * 4.0f);
  const uint stratum = grid ? k : sobol_grid ? sobol_stratum : ((shuffle.x | 1u) * k + shuffle.y) & 15u;
  const bool centred = grid || sobol_grid;
  const real jx = centred ? 0.5f : u.u0;
  const real jy = centred ? 0.5f : u.u1;
  const real sx = ((real)(stratum & 3u) + jx) * 0.25f;
  const real sy = ((real)(stratum >> 2) + jy) * 0.25f;
  return f2(sobol ? (real)u.u0 : sx, sobol ? (real)u.u1 : sy);
}

/* Unit direction of the camera ray through image position (col + sx, row + sy). */
CLPT_INLINE Vec3 camera_ray_direction(const GpuCamera* camera, uint width, uint height, uint col,
                                      uint row, Float2 subpixel) {
  const real fx = ((real)col + subpixel.x) / (real)width;
  const real fy = ((real)(height - 1u - row) + subpixel.y) / (real)height;
  Vec3 on_sensor = v3_load_apart(camera->sensor_center);
  on_sensor = v3_add_scaled(on_sensor, v3_load_apart(camera->sensor_right), fx - 0.5f);
  on_sensor = v3_add_scaled(on_sensor, v3_load_apart(camera->sensor_up), fy - 0.5f);
  return v3_normalize(on_sensor);
}

/* The camera ray through image position (col + sx, row + sy): its unit direction, and in *origin
 * where it starts (the pinhole at the origin, or the orthographic sensor's point). */
CLPT_INLINE Vec3 camera_ray(const GpuCamera* camera, uint width, uint height, uint col, uint row, Float2 subpixel,
                            Vec3* origin) {
#if CLPT_HAS_ORTHOGRAPHIC
  const real fx = ((real)col + subpixel.x) / (real)width;
  const real fy = ((real)(height - 1u - row) + subpixel.y) / (real)height;
  const bool ortho = camera->projection == CLPT_PROJECTION_ORTHOGRAPHIC;
  const Vec3 on_sensor = v3_add_scaled(v3_scale(v3_load_apart(camera->sensor_right), fx - 0.5f),
                                       v3_load_apart(camera->sensor_up), fy - 0.5f);
  *origin = v3_select(ortho, on_sensor, v3_splat((real)0));
  return v3_select(ortho, v3_load_apart(camera->sensor_center),
                   camera_ray_direction(camera, width, height, col, row, subpixel));
#else
  *origin = v3_splat((real)0);
  return camera_ray_direction(camera, width, height, col, row, subpixel);
#endif
}

#endif
