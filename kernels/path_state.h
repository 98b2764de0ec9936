/* path_state.h: the wavefront's per-path state, declared once.
 *
 * Valid C++ and OpenCL C. CLPT_PATH_STATE_FIELDS lists every structure-of-arrays buffer with its
 * element type, size in bytes and meaning; the device expands it into kernel parameters
 * (wavefront.cl), the host into buffer allocations and kernel arguments
 * (wavefront_renderer.cpp), so the two cannot drift apart. One element per path slot, one scalar
 * per buffer: scalar loads keep the kernels vectorisable on PoCL and coalesced on GPUs.
 * The persistent fields exist twice: compaction copies the surviving paths from one set into the
 * other, densely, so every stage kernel reads slot i for work-item i (no index indirection). */
#ifndef CLPT_PATH_STATE_H
#define CLPT_PATH_STATE_H

/*  X(type, name, bytes, meaning) */
#define CLPT_PATH_STATE_FIELDS(X)                                                                 \
  X(float, origin_x, 4, "ray origin, camera-relative world units")                               \
  X(float, origin_y, 4, "")                                                                      \
  X(float, origin_z, 4, "")                                                                      \
  X(float, direction_x, 4, "unit ray direction")                                                 \
  X(float, direction_y, 4, "")                                                                   \
  X(float, direction_z, 4, "")                                                                   \
  X(float, throughput_r, 4, "product of BSDF weights so far")                                    \
  X(float, throughput_g, 4, "")                                                                  \
  X(float, throughput_b, 4, "")                                                                  \
  X(float, radiance_r, 4, "light gathered so far")                                               \
  X(float, radiance_g, 4, "")                                                                    \
  X(float, radiance_b, 4, "")                                                                    \
  X(uint, job, 4, "job index in the pass: sample (job / pixel_count), pixel (job % pixel_count)") \
  X(uint, bounce, 4, "index of the current segment, 0 = camera ray")                            \
  X(uint, segments, 4, "segments traced so far")                                                 \
  X(int, skip_sphere, 4, "sphere the ray leaves on its outer side, or -1")

/* Per-iteration scratch, one set: written and read within one bounce. */
#define CLPT_PATH_SCRATCH_FIELDS(X)                                                               \
  X(float, hit_t, 4, "distance to the closest hit, INFINITY for a miss")                         \
  X(int, hit_sphere, 4, "sphere hit, -1 for a miss")                                             \
  X(int, alive, 4, "1 while the path continues after shading")

#endif
