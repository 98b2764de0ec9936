/* path_state.h: the wavefront's per-path state, declared once.
 *
 * Valid C++ and OpenCL C. CLPT_PATH_STATE_FIELDS lists every structure-of-arrays buffer with its
 * element type, size in bytes and meaning; the device expands it into kernel parameters
 * (wavefront.cl), the host into buffer allocations and kernel arguments
 * (wavefront_renderer.cpp), so the two cannot drift apart. One element per path slot, one scalar
 * per buffer: scalar loads keep the kernels vectorisable on PoCL and coalesced on GPUs.
 * The persistent fields exist twice: shading stores the surviving paths from one set into the
 * other, densely, so every stage kernel reads slot i for work-item i (no index indirection). */
#ifndef CLPT_PATH_STATE_H
#define CLPT_PATH_STATE_H

/*  X(type, name, bytes, meaning)
 * `real` is float, or double under the double preset: the host passes CLPT_REAL_BYTES as the
 * size it allocates. bsdf_pdf is read and written only by kernels that compile nee in. */
#define CLPT_PATH_STATE_FIELDS(X)                                                                 \
  X(real, origin_x, CLPT_REAL_BYTES, "ray origin, camera-relative world units")               \
  X(real, origin_y, CLPT_REAL_BYTES, "")                                                      \
  X(real, origin_z, CLPT_REAL_BYTES, "")                                                      \
  X(real, direction_x, CLPT_REAL_BYTES, "unit ray direction")                                 \
  X(real, direction_y, CLPT_REAL_BYTES, "")                                                   \
  X(real, direction_z, CLPT_REAL_BYTES, "")                                                   \
  X(real, throughput_r, CLPT_REAL_BYTES, "product of BSDF weights so far")                    \
  X(real, throughput_g, CLPT_REAL_BYTES, "")                                                  \
  X(real, throughput_b, CLPT_REAL_BYTES, "")                                                  \
  X(real, radiance_r, CLPT_REAL_BYTES, "light gathered so far")                               \
  X(real, radiance_g, CLPT_REAL_BYTES, "")                                                    \
  X(real, radiance_b, CLPT_REAL_BYTES, "")                                                    \
  X(real, bsdf_pdf, CLPT_REAL_BYTES, "pdf of the BSDF sample that made the ray (nee)") \
  X(uint, job, 4, "job index in the pass: sample (job / pixel_count), pixel (job % pixel_count)") \
  X(uint, bounce, 4, "index of the current segment, 0 = camera ray")                         \
  X(uint, segments, 4, "segments traced so far")                                              \
  X(int, skip_sphere, 4, "sphere the ray leaves on its outer side, or -1")

/* Per-iteration scratch, one set: written and read within one bounce. */
#define CLPT_PATH_SCRATCH_FIELDS(X)                                                               \
  X(real, hit_t, CLPT_REAL_BYTES, "distance to the closest hit, CLPT_NO_HIT for a miss")      \
  X(int, hit_sphere, 4, "sphere hit, -1 for a miss")

#endif
