/* probe_path_state.cl: the wavefront's path-state buffers as this device's compiler sees them,
 * for StructLayout.PathStateBuffersMatchTheHost. The kernel takes the buffers through the
 * wavefront's own parameter list (CLPT_STATE_PARAMS, generated from kernels/path_state.h), reports
 * each buffer's element size in CLPT_PATH_STATE_FIELDS order, and moves slot 0's state through
 * path_load and path_store into slot 1: every stored field must survive the round trip. */
#include "wavefront.cl"

__kernel void probe_path_state(__global uint* sizes, const GpuRenderParams params,
                               __global const GpuSampleSlot* sample_slots CLPT_STATE_PARAMS) {
  uint i = 0;
#define CLPT_PROBE_ELEMENT(type, name, bytes, doc) sizes[i++] = (uint)sizeof(*name);
  CLPT_PATH_STATE_FIELDS(CLPT_PROBE_ELEMENT)
#undef CLPT_PROBE_ELEMENT
  const PathState p = path_load(0, &params, sample_slots CLPT_STATE_ARGS);
  path_store(1, job[0], &p CLPT_STATE_ARGS);
}
