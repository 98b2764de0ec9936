/* probe_maths.cl: the maths replacements of kernels/maths.cl in the precision the program is
 * built with (`real`: float, or double with -DCLPT_PRECISION=2), so a test can check the double
 * preset's own sin/cos and pow polynomials against the host's libm. */
#include "maths.cl"

/* (cos 2 pi u[i], sin 2 pi u[i]) as out[2 i], out[2 i + 1]. */
__kernel void probe_unit_circle_real(__global const real* u, __global real* out) {
  const size_t i = get_global_id(0);
  const Float2 c = unit_circle(u[i]);
  out[2 * i] = c.x;
  out[2 * i + 1] = c.y;
}

/* pow_unit(in[2 i], in[2 i + 1]). */
__kernel void probe_pow_unit_real(__global const real* in, __global real* out) {
  const size_t i = get_global_id(0);
  out[i] = pow_unit(in[2 * i], in[2 * i + 1]);
}
