/* path_state.h: the wavefront's per-path state, declared once.
 *
 * Valid C++ and OpenCL C. CLPT_PATH_STATE_FIELDS lists every structure-of-arrays buffer with its
 * element type, size in bytes and meaning; the device expands it into kernel parameters and
 * load/store helpers (wavefront.cl), the host into buffer allocations and kernel arguments
 * (wavefront_renderer.cpp), so the two cannot drift apart. One element per path slot. */
#ifndef CLPT_PATH_STATE_H
#define CLPT_PATH_STATE_H

/*  X(type,   name,        bytes, meaning) */
#define CLPT_PATH_STATE_FIELDS(X)                                                                 \
  X(float4, origin, 16, "xyz: ray origin, camera-relative world units")                          \
  X(float4, direction, 16, "xyz: unit ray direction")                                            \
  X(float4, throughput, 16, "rgb: product of BSDF weights so far")                               \
  X(float4, radiance, 16, "rgb: light gathered so far")                                          \
  X(uint4, ids, 16, "x: job index in the pass, y: bounce, z: segments traced, w: skip sphere + 1") \
  X(float, hit_t, 4, "distance to the closest hit, INFINITY for a miss")                         \
  X(int, hit_sphere, 4, "sphere hit, -1 for a miss")                                             \
  X(int, alive, 4, "1 while the path continues after shading")

#endif
