/* path_state.h: the state of one path, declared once.
 *
 * Valid C++ and OpenCL C. CLPT_PATH_FIELDS is the one list of a path's fields; everything else is
 * generated from it, so adding a field is one line:
 *   - the PathState struct every stage function takes (path.cl, CLPT_PATH_STATE_MEMBERS),
 *   - path_select, the lockstep megakernel's per-field choice (path.cl, CLPT_PATH_SELECT_FIELDS),
 *   - the wavefront's structure-of-arrays buffers (CLPT_PATH_STATE_FIELDS below): its kernel
 *     parameters (wavefront.cl), its path_load / path_store (wavefront.cl, CLPT_PATH_LOAD_FIELDS
 *     and CLPT_PATH_STORE_FIELDS), and on the host the buffer allocations and kernel arguments
 *     (wavefront_renderer.cpp) and the memory estimate (limits.cpp).
 * StructLayout.PathStateBuffersMatchTheHost checks that a kernel compiled from this file and the
 * host expand it to the same buffers of the same element sizes.
 *
 *  X(kind, type, name, meaning and unit, B)  -- B is passed through for the buffer expansion
 * kind says where the field lives:
 *   VEC3      a Vec3 of `type` components; stored as three buffers name_x, name_y, name_z
 *   STORED    one value; stored as one buffer
 *   NEE       one value that only kernels with next-event estimation compiled in read or write;
 *             its buffer exists for every kernel (bound alike), unused without nee
 *   FROM_JOB  not stored: path_load derives it from the slot's job index (pixel, sample)
 *   LOCAL     not stored: only live within one kernel (alive: a stored path is always alive)
 *   AOV, AOV_VEC3  a value (a Vec3) that exists only in kernels built with CLPT_AOVS (the
 *             first-hit layers, aov.cl; kernel_options.cpp decides): without it the kernels expand
 *             it to nothing at all; the host allocates its buffers only for such a kernel
 *             (CLPT_PATH_AOV_BUFFER below)
 * `real` is float, or double under the double preset: the host passes CLPT_REAL_BYTES as the
 * size it allocates. One element per path slot, one scalar per buffer: scalar loads keep the
 * kernels vectorisable on PoCL and coalesced on GPUs. */
#ifndef CLPT_PATH_STATE_H
#define CLPT_PATH_STATE_H

#define CLPT_PATH_FIELDS(X, B)                                                                        \
  X(VEC3, real, origin, "ray origin, camera-relative world units", B)                                 \
  X(VEC3, real, direction, "unit ray direction", B)                                                   \
  X(VEC3, real, throughput, "product of BSDF weights so far, per channel", B)                         \
  X(VEC3, real, radiance, "light gathered so far, per channel", B)                                    \
  X(FROM_JOB, uint, pixel, "global pixel index, row-major, row 0 at the top", B)                      \
  X(FROM_JOB, uint, sample, "global sample index within the pixel", B)                                \
  X(NEE, real, bsdf_pdf,                                                                              \
    "solid-angle pdf of the BSDF sample that made the current ray; 0: camera ray or specular (no "    \
    "MIS at a light it hits)", B)                                                                     \
  X(STORED, uint, bounce, "index of the current segment: 0 = camera ray", B)                          \
  X(STORED, uint, segments, "ray segments traced so far (for rays/s)", B)                             \
  X(STORED, int, skip_sphere, "sphere the ray is leaving on its outer side (cannot be hit), or -1", B) \
  X(AOV_VEC3, real, aov_albedo,                                                                       \
    "first-hit layers (aov.cl): the recorded albedo; until a surface is recorded, the product of the " \
    "delta bounces' weights so far (1 at the camera)", B)                                             \
  X(AOV_VEC3, real, aov_normal,                                                                       \
    "the recorded surface's shading normal, world space; 0 until one is recorded (or for a miss)", B) \
  X(AOV, real, aov_depth, "distance along the camera ray to its first hit, world units; 0 for a miss", B) \
  X(LOCAL, int, alive, "0 once the path has ended", B)

/* Element bytes of a buffer of `type`. */
#define CLPT_PATH_BYTES_real CLPT_REAL_BYTES
#define CLPT_PATH_BYTES_uint 4
#define CLPT_PATH_BYTES_int 4

/* The stored buffers of one path slot, as B(type, name, bytes, meaning): every field expanded by
 * its kind, then the slot's job index (from which FROM_JOB fields derive). The wavefront keeps
 * two sets of them (shading stores the survivors densely from one set into the other). */
#define CLPT_PATH_BUFFERS_VEC3(type, name, doc, B) \
  B(type, name##_x, CLPT_PATH_BYTES_##type, doc) B(type, name##_y, CLPT_PATH_BYTES_##type, "") \
  B(type, name##_z, CLPT_PATH_BYTES_##type, "")
#define CLPT_PATH_BUFFERS_STORED(type, name, doc, B) B(type, name, CLPT_PATH_BYTES_##type, doc)
#define CLPT_PATH_BUFFERS_NEE(type, name, doc, B) B(type, name, CLPT_PATH_BYTES_##type, doc)
#define CLPT_PATH_BUFFERS_FROM_JOB(type, name, doc, B)
#define CLPT_PATH_BUFFERS_LOCAL(type, name, doc, B)
#define CLPT_PATH_BUFFERS_AOV(type, name, doc, B) CLPT_PATH_AOV_BUFFER(B, type, name, CLPT_PATH_BYTES_##type, doc)
#define CLPT_PATH_BUFFERS_AOV_VEC3(type, name, doc, B)                              \
  CLPT_PATH_AOV_BUFFER(B, type, name##_x, CLPT_PATH_BYTES_##type, doc)             \
  CLPT_PATH_AOV_BUFFER(B, type, name##_y, CLPT_PATH_BYTES_##type, "")              \
  CLPT_PATH_AOV_BUFFER(B, type, name##_z, CLPT_PATH_BYTES_##type, "")
#define CLPT_PATH_BUFFERS_OF(kind, type, name, doc, B) CLPT_PATH_BUFFERS_##kind(type, name, doc, B)
#define CLPT_PATH_STATE_FIELDS(B)              \
  CLPT_PATH_FIELDS(CLPT_PATH_BUFFERS_OF, B) \
  B(uint, job, 4, "job index in the pass: sample (job / pixel_count), pixel (job % pixel_count)")

/* An AOV field's buffer. A kernel has it exactly when it is built with CLPT_AOVS. The host, which
 * serves both kinds of kernel, expands it to a statement that runs only when the bool
 * CLPT_HOST_AOVS, which the expanding code defines, is true (every host expansion is a list of
 * statements: allocations, sizes). */
#ifdef __OPENCL_C_VERSION__
#if defined(CLPT_AOVS) && CLPT_AOVS
#define CLPT_PATH_AOV_BUFFER(B, type, name, bytes, doc) B(type, name, bytes, doc)
#else
#define CLPT_PATH_AOV_BUFFER(B, type, name, bytes, doc)
#endif
#else
#define CLPT_PATH_AOV_BUFFER(B, type, name, bytes, doc) \
  if (CLPT_HOST_AOVS) {                                 \
    B(type, name, bytes, doc)                           \
  }
#endif

/* Per-iteration scratch of the wavefront, one set: written by wf_intersect, read by wf_shade in
 * the same bounce. Not part of a path (the megakernel keeps its Hit in registers). */
#define CLPT_PATH_SCRATCH_FIELDS(B)                                                            \
  B(real, hit_t, CLPT_REAL_BYTES, "distance to the closest hit, CLPT_NO_HIT for a miss") \
  B(int, hit_sphere, 4, "sphere hit, -1 for a miss or a triangle hit")                  \
  B(int, hit_triangle, 4, "triangle hit, -1 for a miss or a sphere hit")

#ifdef __OPENCL_C_VERSION__
/* The struct's members. */
#define CLPT_PATH_MEMBER_VEC3(type, name) Vec3 name;
#define CLPT_PATH_MEMBER_STORED(type, name) type name;
#define CLPT_PATH_MEMBER_NEE(type, name) type name;
#define CLPT_PATH_MEMBER_FROM_JOB(type, name) type name;
#define CLPT_PATH_MEMBER_LOCAL(type, name) type name;
#if defined(CLPT_AOVS) && CLPT_AOVS
#define CLPT_PATH_MEMBER_AOV(type, name) type name;
#define CLPT_PATH_MEMBER_AOV_VEC3(type, name) Vec3 name;
#else
#define CLPT_PATH_MEMBER_AOV(type, name)
#define CLPT_PATH_MEMBER_AOV_VEC3(type, name)
#endif
#define CLPT_PATH_MEMBER_OF(kind, type, name, doc, B) CLPT_PATH_MEMBER_##kind(type, name)
#define CLPT_PATH_STATE_MEMBERS CLPT_PATH_FIELDS(CLPT_PATH_MEMBER_OF, _)

/* p.name = c ? a.name : b.name, field by field (component-wise for a Vec3, which PoCL
 * vectorises where a select of a whole struct would stop it). */
#define CLPT_PATH_SELECT_VEC3(name) p.name = v3_select(c, a.name, b.name);
#define CLPT_PATH_SELECT_SCALAR(name) p.name = c ? a.name : b.name;
#define CLPT_PATH_SELECT_STORED(name) CLPT_PATH_SELECT_SCALAR(name)
#define CLPT_PATH_SELECT_NEE(name) CLPT_PATH_SELECT_SCALAR(name)
#define CLPT_PATH_SELECT_FROM_JOB(name) CLPT_PATH_SELECT_SCALAR(name)
#define CLPT_PATH_SELECT_LOCAL(name) CLPT_PATH_SELECT_SCALAR(name)
#if defined(CLPT_AOVS) && CLPT_AOVS
#define CLPT_PATH_SELECT_AOV(name) CLPT_PATH_SELECT_SCALAR(name)
#define CLPT_PATH_SELECT_AOV_VEC3(name) CLPT_PATH_SELECT_VEC3(name)
#else
#define CLPT_PATH_SELECT_AOV(name)
#define CLPT_PATH_SELECT_AOV_VEC3(name)
#endif
#define CLPT_PATH_SELECT_OF(kind, type, name, doc, B) CLPT_PATH_SELECT_##kind(name)
#define CLPT_PATH_SELECT_FIELDS CLPT_PATH_FIELDS(CLPT_PATH_SELECT_OF, _)

/* p.name from the buffers of `slot` (FROM_JOB and LOCAL fields: path_load sets them itself). */
#define CLPT_PATH_LOAD_VEC3(type, name) p.name = v3(name##_x[slot], name##_y[slot], name##_z[slot]);
#define CLPT_PATH_LOAD_STORED(type, name) p.name = name[slot];
#define CLPT_PATH_LOAD_NEE(type, name) p.name = CLPT_NEE_COMPILED ? name[slot] : (type)0;
#define CLPT_PATH_LOAD_FROM_JOB(type, name)
#define CLPT_PATH_LOAD_LOCAL(type, name)
#if defined(CLPT_AOVS) && CLPT_AOVS
#define CLPT_PATH_LOAD_AOV(type, name) CLPT_PATH_LOAD_STORED(type, name)
#define CLPT_PATH_LOAD_AOV_VEC3(type, name) CLPT_PATH_LOAD_VEC3(type, name)
#else
#define CLPT_PATH_LOAD_AOV(type, name)
#define CLPT_PATH_LOAD_AOV_VEC3(type, name)
#endif
#define CLPT_PATH_LOAD_OF(kind, type, name, doc, B) CLPT_PATH_LOAD_##kind(type, name)
#define CLPT_PATH_LOAD_FIELDS CLPT_PATH_FIELDS(CLPT_PATH_LOAD_OF, _)

/* The buffers of `slot` from p->name (path_store writes the job index itself). */
#define CLPT_PATH_STORE_VEC3(type, name) \
  name##_x[slot] = p->name.x;            \
  name##_y[slot] = p->name.y;            \
  name##_z[slot] = p->name.z;
#define CLPT_PATH_STORE_STORED(type, name) name[slot] = p->name;
#define CLPT_PATH_STORE_NEE(type, name) \
  if (CLPT_NEE_COMPILED) name[slot] = p->name;
#define CLPT_PATH_STORE_FROM_JOB(type, name)
#define CLPT_PATH_STORE_LOCAL(type, name)
#if defined(CLPT_AOVS) && CLPT_AOVS
#define CLPT_PATH_STORE_AOV(type, name) CLPT_PATH_STORE_STORED(type, name)
#define CLPT_PATH_STORE_AOV_VEC3(type, name) CLPT_PATH_STORE_VEC3(type, name)
#else
#define CLPT_PATH_STORE_AOV(type, name)
#define CLPT_PATH_STORE_AOV_VEC3(type, name)
#endif
#define CLPT_PATH_STORE_OF(kind, type, name, doc, B) CLPT_PATH_STORE_##kind(type, name)
#define CLPT_PATH_STORE_FIELDS CLPT_PATH_FIELDS(CLPT_PATH_STORE_OF, _)
#endif

#endif
