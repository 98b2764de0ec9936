/* probe_oclgrind.cl: kernels with deliberate bugs, run only on Oclgrind by OclgrindChecks.* to
 * show that each of the tier's checks reports what it should in the tier's environment (so a
 * clean render's empty report means the checks ran, not that nothing listened). Never built for
 * a real device: each one really is wrong. */

/* Out of bounds: work-item i writes out[i + 1], so the last of n work-items writes one element
 * past an n-element buffer. */
__kernel void probe_out_of_bounds(__global uint* out) {
  const size_t i = get_global_id(0);
  out[i + 1] = (uint)i;
}

/* Data race: every work-item stores its own id to out[0] with no ordering between them (distinct
 * values, so it is not the uniform write Oclgrind forgives unless OCLGRIND_UNIFORM_WRITES). */
__kernel void probe_data_race(__global uint* out) {
  out[0] = (uint)get_global_id(0);
}
