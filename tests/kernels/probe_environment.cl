/* probe_environment.cl: the environment light's device functions (kernels/environment.cl) on
 * buffers from the host, for tests/test_environment.cpp: draws and their densities, and lookups. */
#include "types.h"
#include "maths.cl"
#include "rng.cl"
#include "environment.cl"

/* Sample i: environment_sample of Philox draw (i, seed); out[2i] = (direction, pdf),
 * out[2i + 1] = (environment_pdf of that direction, radiance). */
__kernel void probe_environment_sample(__global const GpuEnvironment* env, uint seed, __global float4* out) {
  const uint i = (uint)get_global_id(0);
  const Philox4 bits = philox4x32_10(philox4(i, seed, 7u, 0u), 0x1234u, 0x5678u);
  Uniform4 u;
  u.u0 = rng_to_unit_float(bits.x);
  u.u1 = rng_to_unit_float(bits.y);
  u.u2 = rng_to_unit_float(bits.z);
  u.u3 = rng_to_unit_float(bits.w);
  const EnvironmentSample s = environment_sample(env, u);
  out[2u * i] = (float4)((float)s.direction.x, (float)s.direction.y, (float)s.direction.z, (float)s.pdf);
  const Vec3 r = environment_radiance(env, s.direction);
  out[2u * i + 1u] = (float4)((float)environment_pdf(env, s.direction), (float)r.x, (float)r.y, (float)r.z);
}
