/* megakernel.cl: the megakernel execution form.
 *
 * One work-item per pixel of the launch; it traces that pixel's samples of the pass one path at
 * a time, each path an iterative loop over the stages of path.cl, and writes the pixel's pass
 * statistics. Reads: the sphere buffer and GpuRenderParams. Writes: pass[pixel - pixel_begin]. */
#include "types.h"
#include "path.cl"
#include "film.cl"

__kernel void render_megakernel(__global const GpuSphere* spheres, const GpuRenderParams params,
                                __global GpuPixelPass* pass) {
  const uint local_pixel = (uint)get_global_id(0);
  if (local_pixel >= params.pixel_count) return;
  const uint pixel = params.pixel_begin + local_pixel;

  PixelAccumulator acc = pixel_accumulator_new();
  for (uint s = 0; s < params.samples_per_pass; ++s) {
    PathState path = path_begin(&params, pixel, params.sample_begin + s);
    while (path.alive) {
      const Hit hit = path_intersect(&path, spheres, &params);
      path_shade(&path, hit, spheres, &params);
    }
    pixel_accumulator_add(&acc, path.radiance, path.segments);
  }
  film_write_pass(&pass[local_pixel], &acc);
}
