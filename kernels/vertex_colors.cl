/* vertex_colors.cl: glTF COLOR_0, a mesh's per-vertex colours, as the base colour's multiplier
 * (docs/textures.md "Vertex colours"). The texturing buffer's colors section (types.h,
 * GpuTriangleColors) holds each triangle's three linear RGBA corners; the colour at a hit is their
 * barycentric interpolation, clamped to [0, 1]. Its RGB multiplies the material's reflectance
 * after the base colour texture (path.cl, apply_textures; the first-hit albedo layer sees the
 * product), its A the alpha that MASK and BLEND read (alpha.cl, alpha_cut). Triangles of meshes
 * without COLOR_0 hold white corners; a buffer without the section (colors 0: no mesh has
 * COLOR_0, which only the generic kernel meets) reads as white.
 *
 * Specialisation (kernel_options.cpp): CLPT_HAS_VERTEX_COLORS, named only when a mesh has COLOR_0
 * (absent: off in a specialised kernel, on in the generic one); it needs the texturing buffer
 * (CLPT_HAS_TEXTURES), which such a scene has. Without it nothing here is compiled. */
#ifndef CLPT_VERTEX_COLORS_CL
#define CLPT_VERTEX_COLORS_CL

#include "types.h"
#include "maths.cl"
#include "texture.cl"

#ifndef CLPT_HAS_VERTEX_COLORS
#ifdef CLPT_ESTIMATOR
#define CLPT_HAS_VERTEX_COLORS 0
#else
#define CLPT_HAS_VERTEX_COLORS 1
#endif
#endif
#if CLPT_HAS_VERTEX_COLORS && !CLPT_HAS_TEXTURES
#error "CLPT_HAS_VERTEX_COLORS needs the texturing buffer (CLPT_HAS_TEXTURES)"
#endif

#if CLPT_HAS_VERTEX_COLORS
/* Triangle `triangle`'s colour at barycentrics (b0, b1, b2) (weights of its corners 0, 1, 2):
 * linear RGBA in [0, 1]; white where the buffer has no colors section. */
CLPT_INLINE TexelRgba triangle_vertex_color(__global const uchar* texturing, uint triangle, float b0, float b1, float b2) {
  __global const GpuTexturing* header = (__global const GpuTexturing*)texturing;
  TexelRgba c;
  c.r = c.g = c.b = c.a = 1.0f;
  if (header->colors == 0u) return c;
  __global const GpuTriangleColors* k = (__global const GpuTriangleColors*)(texturing + header->colors) + triangle;
  c.r = clamp(b0 * k->c0[0] + b1 * k->c1[0] + b2 * k->c2[0], 0.0f, 1.0f);
  c.g = clamp(b0 * k->c0[1] + b1 * k->c1[1] + b2 * k->c2[1], 0.0f, 1.0f);
  c.b = clamp(b0 * k->c0[2] + b1 * k->c1[2] + b2 * k->c2[2], 0.0f, 1.0f);
  c.a = clamp(b0 * k->c0[3] + b1 * k->c1[3] + b2 * k->c2[3], 0.0f, 1.0f);
  return c;
}
#endif

#endif
