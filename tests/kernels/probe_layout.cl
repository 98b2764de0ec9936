/* probe_layout.cl: reports struct sizes and field offsets as this device's compiler lays them
 * out, in CLPT_LAYOUT_STRUCTS / CLPT_LAYOUT_FIELDS order, for StructLayout.HostMatchesDevice. */
#include "types.h"

__kernel void probe_layout(__global uint* out) {
  uint i = 0;
#define CLPT_PROBE_SIZE(T) out[i++] = (uint)sizeof(T);
/* OpenCL C has no offsetof: measure the distance inside a real (private) object instead. */
#define CLPT_PROBE_FIELD(T, f)                                                                    \
  {                                                                                               \
    T probe;                                                                                      \
    out[i++] = (uint)((char*)&probe.f - (char*)&probe);                                           \
  }
  CLPT_LAYOUT_STRUCTS(CLPT_PROBE_SIZE)
  CLPT_LAYOUT_FIELDS(CLPT_PROBE_FIELD)
}
