/* types.h: every struct that crosses the host/device boundary.
 *
 * Valid C++17 (host, inside namespace clpt) and OpenCL C 1.2 (device). Only 32-bit scalars and
 * fixed arrays of them: no float3 (16 bytes in OpenCL, 12 in C++) and no implicit padding, so
 * both compilers agree on every offset. CLPT_LAYOUT_FIELDS lists every field once; the test
 * `StructLayout.HostMatchesDevice` compares sizeof/offsetof as each side computes them.
 *
 * Coordinates on the device are camera-relative: the host subtracts the camera position in
 * double precision, so the pinhole is the origin and large translations cost no precision. */
#ifndef CLPT_TYPES_H
#define CLPT_TYPES_H

#ifdef __OPENCL_C_VERSION__
typedef uint clpt_u32;
#else
#include <cstdint>
typedef uint32_t clpt_u32;
#endif

/* Material kinds (GpuMaterial.kind). */
#define CLPT_MATERIAL_LAMBERTIAN 0u
#define CLPT_MATERIAL_PHONG 1u
#define CLPT_MATERIAL_GLASS 2u
#define CLPT_MATERIAL_EMITTER 3u
#define CLPT_MATERIAL_MIRROR 4u /* perfect specular reflector, reflectance rho */
#define CLPT_MATERIAL_PBR 5u    /* glTF metallic-roughness (bsdf_pbr.cl, docs/materials.md) */

/* One material, as a sphere embeds it and a triangle's shading record does: 64 bytes. */
typedef struct GpuMaterial {
  clpt_u32 kind;           /* CLPT_MATERIAL_* */
  float reflectance[3];    /* albedo rho per channel, [0, 1]; Pbr: the base colour */
  float phong_exponent;    /* Phong lobe exponent n (Phong only) */
  float emission[3];       /* emitted radiance per channel (emitters; Pbr, where it may be 0) */
  float ior;               /* index of refraction inside (glass, Pbr); outside is 1 */
  /* Pbr only (0 for every other kind): */
  float metallic;          /* [0, 1] */
  float roughness;         /* [0, 1]; the GGX alpha is roughness^2 */
  float transmission;      /* [0, 1], KHR_materials_transmission */
  float thickness;         /* > 0: a closed volume the transmission refracts into
                              (KHR_materials_volume); 0: thin-walled. World units. */
  float attenuation[3];    /* Beer's law inside the volume: absorption coefficient per channel,
                              world units^-1 (-ln(attenuation_color) / attenuation_distance); 0: none */
} GpuMaterial;

/* Sample indices of the second half-film start at 2^CLPT_SAMPLE_STREAM_BIT (render/film.h,
 * render/pass_schedule.h): its samples are fresh for jitter and grid, and an independent Sobol
 * randomisation (sampler.cl). Each half holds fewer than 2^31 samples (kMaxSpp). */
#define CLPT_SAMPLE_STREAM_BIT 31u

/* Sub-pixel samplers (GpuRenderParams.sampler). */
#define CLPT_SAMPLER_JITTER 0u /* 4x4 strata, uniform inside each, strata order shuffled per 16 */
#define CLPT_SAMPLER_GRID 1u   /* the book's 4x4 fixed sub-pixel centres */
#define CLPT_SAMPLER_SOBOL 2u  /* padded, shuffled, Owen-scrambled Sobol points for every draw (sampler.cl) */
#define CLPT_SAMPLER_SOBOL_GRID 3u /* the same points, the camera's moved to the centre of its 4x4 stratum (camera.cl) */

/* One sphere and its material: 128 bytes.
 * The sphere is stored as a point s0 on its surface near the scene, the outward unit normal n0
 * there, and the radius, so that the centre is s0 - radius * n0. The intersection then never
 * forms a term of size radius^2 (docs/numerics.md: radius-1e5 walls keep their precision).
 * Each geometric value is a float plus the float of its remainder (*_lo: value - (double)float):
 * float kernels read the first, the double preset adds both and so sees the host's double values
 * to about 48 bits (a sphere 1e6 radii from the camera rounded to float alone moved by 6% of its
 * radius, and the double preset rendered it as wrongly as robust). */
typedef struct GpuSphere {
  float surface_point[3];  /* s0, camera-relative, world units */
  float radius;            /* world units, > 0 */
  float surface_normal[3]; /* n0, unit, outward at s0 */
  GpuMaterial material;
  float surface_point_lo[3];  /* remainders of surface_point, radius, surface_normal */
  float radius_lo;
  float surface_normal_lo[3];
  float pad[2];
} GpuSphere;

/* One node of the 4-wide bounding volume hierarchy over triangles (and spheres, when a scene has
 * more than a few): 128 bytes, the boxes of its (up to) four children stored by axis (SoA), so
 * that the kernels test all four with one vector operation per slab (bvh.cl). The host builds a
 * binary tree and collapses it (scene/bvh_build.cpp, collapse_bvh). Child slot i is
 *   - an interior child: count[i] == 0, child[i] the index of its node in the node buffer
 *     (never 0: node 0 is the root);
 *   - a leaf: count[i] = primitive count (>= 1) | CLPT_BVH_SPHERE_LEAF for spheres, child[i] the
 *     first primitive's index in the triangle buffer, or in the sphere buffer (a leaf holds one kind);
 *   - empty: count[i] == 0, child[i] == 0, and an inverted box (lower +inf, upper -inf) that no
 *     ray hits, so the kernels never read its entry. A node's occupied slots come first.
 * Bounds are camera-relative, rounded outwards. */
#define CLPT_BVH_SPHERE_LEAF 0x80000000u
#define CLPT_BVH_COUNT_MASK 0x7fffffffu
#define CLPT_BVH_WIDTH 4
/* Traversal stack entries (bvh.cl; 192 bytes of private memory, as the binary tree's): a node
 * pushes up to 3 children while one is visited, so the host computes the deepest stack its tree
 * can need (Bvh::stack_need: about 1.5x a balanced binary tree's depth, whose log2 of 2^27
 * triangles is 27) and refuses one past this; the builders' binary trees are held to this many
 * levels too. */
#define CLPT_BVH_STACK 48
typedef struct GpuBvhNode {
  float lower_x[4]; /* children's box minimum corners, camera-relative world units */
  float upper_x[4]; /* and maximum corners */
  float lower_y[4];
  float upper_y[4];
  float lower_z[4];
  float upper_z[4];
  clpt_u32 child[4]; /* interior child: node index; leaf: first primitive; empty: 0 */
  clpt_u32 count[4]; /* interior child or empty: 0; leaf: primitive count | CLPT_BVH_SPHERE_LEAF */
} GpuBvhNode;

/* The triangles of a hierarchy leaf as the traversal tests them (bvh.cl): up to four side by side,
 * each coordinate of each vertex as four lanes (v[vertex][axis][lane]), so that one vector
 * operation tests all four. 160 bytes. They follow the nodes in the hierarchy's buffer (at node
 * bvh_node_count); a triangle leaf's child[i] is the index of its first block there (not of its
 * first triangle, as the host's tree says: scene/device_scene.h, hierarchy_device_data), its count
 * the triangles, ceil(count / 4) blocks. Lanes past `count` are zero: a triangle of no area, which
 * no ray hits. */
typedef struct GpuTriangleBlock {
  float v[3][3][4];
  clpt_u32 first; /* lane 0's triangle (the triangle buffer's index); lane j's is first + j */
  clpt_u32 count; /* lanes in use, 1 to 4 */
  clpt_u32 pad[2];
} GpuTriangleBlock;

/* A triangle's vertices for intersection, camera-relative: 48 bytes (16-byte rows). Triangles are
 * stored in the hierarchy's leaf order. */
typedef struct GpuTriangle {
  float v0[3];
  float pad0;
  float v1[3];
  float pad1;
  float v2[3];
  float pad2;
} GpuTriangle;

/* What shading needs of triangle i (same index as GpuTriangle): 112 bytes, read only at hits. */
typedef struct GpuTriangleShading {
  float normal0[3];       /* unit shading normal at v0 (has_normals only) */
  float normal1[3];       /* at v1 */
  float normal2[3];       /* at v2 */
  clpt_u32 has_normals;   /* 1: interpolate the normals above; 0: the geometric normal shades */
  GpuMaterial material;
  /* Emitting triangles in the light list: the probability per unit area with which next-event
   * estimation samples a point of this triangle (its pick probability / its area, world
   * units^-2), which a BSDF hit on it needs for its MIS weight; 0 for every other triangle. */
  float light_area_density;
  float pad;
} GpuTriangleShading;

/* Textures (kernels/texture.cl, docs/textures.md): one read-only byte buffer, the "texturing"
 * buffer, holds a GpuTexturing header at byte 0 and the sections it points to, each 16-byte
 * aligned: the texture table, the textured materials, one GpuTriangleTexturing per triangle
 * (same index as GpuTriangle), one GpuTriangleTangents per triangle (normal maps only), one
 * GpuTriangleColors per triangle (glTF COLOR_0 only) and the texels. Scenes without textures get a zeroed header (triangles 0: no texturing), which only
 * the generic kernel reads (texture.cl, triangle_texture_material). */
#define CLPT_TEXTURE_NONE 0xffffffffu
#define CLPT_TEXEL_U8 0u    /* one byte per channel, value / 255 */
#define CLPT_TEXEL_HALF 1u  /* binary16 per channel (texture.cl, half_bits_to_float) */
#define CLPT_TEXEL_FLOAT 2u /* float per channel */
#define CLPT_WRAP_REPEAT 0u
#define CLPT_WRAP_CLAMP 1u
#define CLPT_WRAP_MIRROR 2u
#define CLPT_TEXTURE_SRGB 1u    /* GpuTexture.flags: 8-bit texels are sRGB-encoded (decoded per texel) */
#define CLPT_TEXTURE_NEAREST 2u /* GpuTexture.flags: nearest texel, else bilinear */

typedef struct GpuTexturing { /* 32 bytes: byte offsets of the sections */
  clpt_u32 textures;  /* GpuTexture[] */
  clpt_u32 materials; /* GpuMaterialTextures[] */
  clpt_u32 triangles; /* GpuTriangleTexturing[], one per triangle */
  clpt_u32 tangents;  /* GpuTriangleTangents[], one per triangle; 0: none */
  clpt_u32 colors;    /* GpuTriangleColors[], one per triangle (glTF COLOR_0); 0: none */
  clpt_u32 spheres;   /* per-sphere textured-material indices; 0: none */
  clpt_u32 pad[2];
} GpuTexturing;

/* One use of an image: 64 bytes. Mesh coordinates (u, v) (OBJ's convention: (0, 0) at the
 * image's bottom-left) map to u' = t0 u + t1 v + t2, v' = t3 u + t4 v + t5, read at image
 * position x = u' width, y = (1 - v') height (texel centres at i + 0.5). */
typedef struct GpuTexture {
  clpt_u32 texels;    /* byte offset of the top-left texel; rows top to bottom, channels interleaved */
  clpt_u32 width;     /* texels */
  clpt_u32 height;
  clpt_u32 channels;  /* 1 to 4 */
  clpt_u32 storage;   /* CLPT_TEXEL_* */
  clpt_u32 wrap_u;    /* CLPT_WRAP_* */
  clpt_u32 wrap_v;
  clpt_u32 flags;     /* CLPT_TEXTURE_SRGB | CLPT_TEXTURE_NEAREST */
  float transform[6]; /* t0 .. t5 above */
  clpt_u32 channel;   /* a scalar parameter reads this channel of the RGBA lookup */
  float pad;
} GpuTexture;

/* glTF alphaMode (GpuMaterialTextures.alpha_mode; kernels/alpha.cl). */
#define CLPT_ALPHA_OPAQUE 0u /* alpha ignored */
#define CLPT_ALPHA_MASK 1u   /* the surface is there where alpha >= alpha_cutoff */
#define CLPT_ALPHA_BLEND 2u  /* the surface is there with probability alpha (coverage) */

/* A textured material's textures (indices into the texture table, or CLPT_TEXTURE_NONE): each
 * multiplies its factor in the triangle's GpuMaterial; and its alpha (glTF alphaMode: alpha =
 * `alpha` x the base colour texture's alpha channel). A material with a MASK or BLEND alpha has a
 * record even without textures. 48 bytes. */
typedef struct GpuMaterialTextures {
  clpt_u32 base_color;   /* RGB x reflectance (the base colour); its alpha x `alpha` */
  clpt_u32 metallic;     /* its channel x metallic */
  clpt_u32 roughness;    /* its channel x roughness */
  clpt_u32 emission;     /* RGB x emission */
  clpt_u32 normal;       /* tangent-space normal map */
  float normal_scale;    /* scales the map's x and y (glTF normalTexture.scale) */
  clpt_u32 alpha_mode;   /* CLPT_ALPHA_* */
  float alpha_cutoff;    /* MASK: the surface is there where alpha >= this */
  float alpha;           /* baseColorFactor's alpha */
  clpt_u32 pad[3];
} GpuMaterialTextures;

/* Texture coordinates of a triangle's corners and its material's textures: 32 bytes. */
typedef struct GpuTriangleTexturing {
  float uv0[2];
  float uv1[2];
  float uv2[2];
  clpt_u32 material;  /* index into the GpuMaterialTextures, or CLPT_TEXTURE_NONE: untextured */
  clpt_u32 pad;
} GpuTriangleTexturing;

/* Per-corner tangents of a normal-mapped triangle: xyz unit (world space), w the bitangent's
 * sign (bitangent = w cross(normal, tangent)), as glTF's TANGENT. 48 bytes. */
typedef struct GpuTriangleTangents {
  float t0[4];
  float t1[4];
  float t2[4];
} GpuTriangleTangents;

/* Per-corner colours of a triangle (glTF COLOR_0; kernels/vertex_colors.cl): linear RGBA, VEC3's
 * alpha 1. Present (GpuTexturing.colors != 0) only when some mesh has COLOR_0, then one record per
 * triangle; every triangle of a mesh with COLOR_0 has a textured-material record (even without an
 * image), and the records of the other triangles are white (1, 1, 1, 1), which multiplies nothing.
 * Interpolated at the hit's barycentrics, RGB x the base colour, A x its alpha. 48 bytes. */
typedef struct GpuTriangleColors {
  float c0[4];
  float c1[4];
  float c2[4];
} GpuTriangleColors;

/* Estimators (GpuRenderParams.estimator; a specialised kernel fixes it with CLPT_ESTIMATOR). */
#define CLPT_ESTIMATOR_BOOK 0u /* the book's: light only where a path hits an emitter */
#define CLPT_ESTIMATOR_NEE 1u  /* next-event estimation + MIS with BSDF sampling (light.cl) */

/* No Russian roulette (GpuRenderParams.rr_from). */
#define CLPT_RR_NEVER 0xffffffffu

/* A light as next-event estimation samples it: 80 bytes. The light list holds the emitter spheres
 * first (their count is CLPT_LIGHT_COUNT in a specialised kernel), then the emitting triangles,
 * then the punctual lights.
 * Sphere lights: only a spherical cap of the emitter is sampled, uniformly by area: the part that
 * no other sphere hides (the host computes it in double, device_scene.cpp). The book's light is a
 * radius-100 sphere of which only a cap of radius about 1.41 pokes through the ceiling; sampling
 * the whole sphere would waste all but 5e-5 of the shadow rays on it. Triangle lights: a point
 * uniformly by area on the triangle. Punctual lights (point, spot, directional; KHR_lights_punctual
 * in W/sr or W/m^2, docs/materials.md "Lights"): delta lights, reached by next-event estimation
 * only.
 * Which light: in kernels without triangle or punctual lights, uniformly (1 / light count, as
 * before triangle lights existed); with them (CLPT_LIGHT_PICK_BY_POWER, light.cl), by the alias
 * table below over each light's power (light_pick.h on the host). */
#define CLPT_LIGHT_SPHERE 0xffffffffu /* GpuLight.triangle of a sphere or punctual light */
/* GpuLight.punctual: 0 for sphere and triangle lights. */
#define CLPT_LIGHT_POINT 1u
#define CLPT_LIGHT_SPOT 2u
#define CLPT_LIGHT_DIRECTIONAL 3u
typedef struct GpuLight {
  float cap_axis[3];       /* sphere: unit, from the emitter's centre through the middle of the cap;
                              spot, directional: unit, the direction the light travels */
  clpt_u32 sphere;         /* sphere: index of the emitter in the sphere buffer; otherwise 0 */
  float one_minus_cos_cap; /* sphere: the cap, points p with 1 - axis.(p - c)/r <= this, in (0, 2];
                              triangle: 0, punctual: -1 (so no sphere hit ever lies in it) */
  float cap_area;          /* sphere: 2 pi r^2 one_minus_cos_cap; triangle: its area; world units^2;
                              punctual: 0 */
  clpt_u32 triangle;       /* triangle: index in the triangle buffer; otherwise CLPT_LIGHT_SPHERE */
  float pick_probability;  /* probability that the power pick chooses this entry (power-pick kernels) */
  float alias_threshold;   /* alias table: entry i is kept when the draw's fraction is below this */
  clpt_u32 alias;          /* alias table: else entry `alias` is taken */
  clpt_u32 punctual;       /* CLPT_LIGHT_POINT/SPOT/DIRECTIONAL, or 0 */
  float range;             /* point, spot: the glTF range window's range, world units; 0: none */
  float position[3];       /* point, spot: camera-relative world units */
  float spot_scale;        /* spot: the cone ramp saturate(cos * scale + offset)^2 (glTF's
                              lightAngleScale, lightAngleOffset); point: 0 and 1 */
  float intensity[3];      /* point, spot: radiant intensity, W/sr; directional: irradiance, W/m^2 */
  float spot_offset;
} GpuLight;

/* The camera at the origin: 48 bytes. Perspective (a pinhole): a sample at image position
 * (fx, fy) in [0,1)^2, fy measured upwards, looks along
 * sensor_center + sensor_right*(fx-0.5) + sensor_up*(fy-0.5). Orthographic: the ray starts at
 * sensor_right*(fx-0.5) + sensor_up*(fy-0.5) and travels along sensor_center (unit). */
#define CLPT_PROJECTION_PERSPECTIVE 0u
#define CLPT_PROJECTION_ORTHOGRAPHIC 1u
typedef struct GpuCamera {
  float sensor_center[3]; /* perspective: from the pinhole to the sensor centre; orthographic: the
                             unit view direction; world units */
  clpt_u32 projection;    /* CLPT_PROJECTION_* */
  float sensor_right[3]; /* full sensor width, pointing right */
  float pad1;
  float sensor_up[3]; /* full sensor height, pointing up */
  float pad2;
} GpuCamera;

/* Everything one pass needs besides the sphere and light buffers: 120 bytes, passed by value. */
typedef struct GpuRenderParams {
  GpuCamera camera;
  clpt_u32 width;            /* pixels */
  clpt_u32 height;           /* pixels */
  clpt_u32 sphere_count;     /* entries in the sphere buffer */
  clpt_u32 max_bounces;      /* bounce rays after the camera ray */
  clpt_u32 seed_lo;          /* RNG key, low 32 bits of the user seed */
  clpt_u32 seed_hi;          /* RNG key, high 32 bits */
  clpt_u32 sample_begin;     /* index of this pass's first sample in each pixel (half 1: from 2^31) */
  clpt_u32 samples_per_pass; /* samples per pixel in this pass */
  clpt_u32 sampler;          /* CLPT_SAMPLER_* */
  float ray_epsilon;         /* hits closer than this along a ray are ignored, world units */
  clpt_u32 pixel_begin;      /* first pixel (row-major, row 0 at the top) of this launch */
  clpt_u32 pixel_count;      /* pixels in this launch */
  clpt_u32 estimator;        /* CLPT_ESTIMATOR_* (read only by the generic kernel) */
  clpt_u32 rr_from;          /* Russian roulette at scattering events from this bounce on, or CLPT_RR_NEVER */
  clpt_u32 light_count;      /* entries in the light buffer (next-event estimation) */
  clpt_u32 bvh_node_count;   /* entries in the node buffer; 0: no hierarchy (spheres in a loop) */
  clpt_u32 slotted;          /* 0: the launch's slot s is pixel pixel_begin + s from sample_begin; 1: it is
                                the launch's GpuSampleSlot s (an adaptive pass, film.cl) */
  clpt_u32 scatter_draw_pairs; /* 1: one draw serves the scattering of two bounces (path.cl, scatter_draw;
                                  read by the generic kernel, fixed in a specialised one) */
} GpuRenderParams;

/* One slot of an adaptive pass (render/adaptive_sampling.h): a pixel and the index of the first of
 * its samples_per_pass samples in this slot: 8 bytes. */
typedef struct GpuSampleSlot {
  clpt_u32 pixel;        /* row-major, row 0 at the top */
  clpt_u32 sample_begin; /* half 1's samples: from 2^31 (CLPT_SAMPLE_STREAM_BIT) */
} GpuSampleSlot;

/* The environment light (kernels/environment.cl, docs/environment.md): radiance arriving from
 * infinitely far along each direction, an equirectangular image or one colour. One buffer holds
 * this 64-byte header and then its data as 32-bit words (offsets below count words from the
 * buffer's start): the texels' RGB radiance (strength included), row 0 the zenith; each texel's
 * density in (u, v), f / mean(f) with f = luminance x sin(theta) at the row's centre; the rows'
 * alias table (threshold float, alias uint) over the rows' sums of f; each row's alias table over
 * its texels' f. Built on the host in double (scene/environment_map.h). A scene without an
 * environment uploads a header of kind NONE over one black texel (read only by the generic kernel). */
#define CLPT_ENVIRONMENT_NONE 0u
#define CLPT_ENVIRONMENT_IMAGE 1u
#define CLPT_ENVIRONMENT_CONSTANT 2u
typedef struct GpuEnvironment {
  clpt_u32 kind;             /* CLPT_ENVIRONMENT_*: what the scene has (a constant is packed as a 1x1 image too) */
  clpt_u32 width;            /* texels per row (u) */
  clpt_u32 height;           /* rows (v) */
  float pick_probability;    /* nee: probability that a light sample is the environment's (1 without
                                other lights, else 1/2); 0 for NONE */
  float radiance[3];         /* CONSTANT: colour x strength (what a CLPT_HAS_ENVIRONMENT=2 kernel reads) */
  float rotation_turns;      /* rotation_deg / 360: about +Y the world direction of azimuth phi looks at the
                                environment's azimuth phi + 2 pi rotation_turns (u shifted by it) */
  clpt_u32 texel_offset;     /* word index of texel 0's R (RGB floats, row-major from the top row) */
  clpt_u32 density_offset;   /* word index of texel 0's density in (u, v) */
  clpt_u32 row_alias_offset; /* word index of the rows' alias table: height (threshold, alias) pairs */
  clpt_u32 column_alias_offset; /* word index of row 0's alias table: width pairs per row */
  float pad[4];
} GpuEnvironment;

/* Per-pixel statistics of one pass, written (not accumulated) by the device: 32 bytes. The
 * host adds them into double-precision sums, so no float sum ever spans more than one pass. */
typedef struct GpuPixelPass {
  float sum[3];          /* sum of sample radiance per channel */
  float valid_samples;   /* samples that reached the film (exact below 2^24) */
  float sum_sq[3];       /* sum of squared sample radiance per channel */
  clpt_u32 segments;     /* ray segments traced (camera rays included) */
} GpuPixelPass;

/* Samples whose radiance had a NaN or Inf are dropped and counted in valid_samples' shortfall. */

/* X-macro over every field, for the layout test on both sides. */
#define CLPT_LAYOUT_FIELDS(X)                                                                     \
  X(GpuMaterial, kind)                                                                            \
  X(GpuMaterial, reflectance)                                                                     \
  X(GpuMaterial, phong_exponent)                                                                  \
  X(GpuMaterial, emission)                                                                        \
  X(GpuMaterial, ior)                                                                             \
  X(GpuMaterial, metallic)                                                                        \
  X(GpuMaterial, roughness)                                                                       \
  X(GpuMaterial, transmission)                                                                    \
  X(GpuMaterial, thickness)                                                                       \
  X(GpuMaterial, attenuation)                                                                     \
  X(GpuBvhNode, lower_x)                                                                          \
  X(GpuBvhNode, upper_x)                                                                          \
  X(GpuBvhNode, lower_y)                                                                          \
  X(GpuBvhNode, upper_y)                                                                          \
  X(GpuBvhNode, lower_z)                                                                          \
  X(GpuBvhNode, upper_z)                                                                          \
  X(GpuBvhNode, child)                                                                            \
  X(GpuBvhNode, count)                                                                            \
  X(GpuTriangleBlock, v)                                                                          \
  X(GpuTriangleBlock, first)                                                                      \
  X(GpuTriangleBlock, count)                                                                      \
  X(GpuTriangle, v0)                                                                              \
  X(GpuTriangle, v1)                                                                              \
  X(GpuTriangle, v2)                                                                              \
  X(GpuTriangleShading, normal0)                                                                  \
  X(GpuTriangleShading, normal1)                                                                  \
  X(GpuTriangleShading, normal2)                                                                  \
  X(GpuTriangleShading, has_normals)                                                              \
  X(GpuTriangleShading, material)                                                                 \
  X(GpuTriangleShading, light_area_density)                                                       \
  X(GpuTexturing, textures)                                                                       \
  X(GpuTexturing, materials)                                                                      \
  X(GpuTexturing, triangles)                                                                      \
  X(GpuTexturing, tangents)                                                                       \
  X(GpuTexturing, colors)                                                                         \
  X(GpuTexturing, spheres)                                                                        \
  X(GpuTexture, texels)                                                                           \
  X(GpuTexture, width)                                                                            \
  X(GpuTexture, height)                                                                           \
  X(GpuTexture, channels)                                                                         \
  X(GpuTexture, storage)                                                                          \
  X(GpuTexture, wrap_u)                                                                           \
  X(GpuTexture, wrap_v)                                                                           \
  X(GpuTexture, flags)                                                                            \
  X(GpuTexture, transform)                                                                        \
  X(GpuTexture, channel)                                                                          \
  X(GpuMaterialTextures, base_color)                                                              \
  X(GpuMaterialTextures, metallic)                                                                \
  X(GpuMaterialTextures, roughness)                                                               \
  X(GpuMaterialTextures, emission)                                                                \
  X(GpuMaterialTextures, normal)                                                                  \
  X(GpuMaterialTextures, normal_scale)                                                            \
  X(GpuMaterialTextures, alpha_mode)                                                              \
  X(GpuMaterialTextures, alpha_cutoff)                                                            \
  X(GpuMaterialTextures, alpha)                                                                   \
  X(GpuTriangleTexturing, uv0)                                                                    \
  X(GpuTriangleTexturing, uv1)                                                                    \
  X(GpuTriangleTexturing, uv2)                                                                    \
  X(GpuTriangleTexturing, material)                                                               \
  X(GpuTriangleTangents, t0)                                                                      \
  X(GpuTriangleTangents, t1)                                                                      \
  X(GpuTriangleTangents, t2)                                                                      \
  X(GpuTriangleColors, c0)                                                                        \
  X(GpuTriangleColors, c1)                                                                        \
  X(GpuTriangleColors, c2)                                                                        \
  X(GpuSphere, surface_point)                                                                     \
  X(GpuSphere, radius)                                                                            \
  X(GpuSphere, surface_normal)                                                                    \
  X(GpuSphere, material)                                                                          \
  X(GpuSphere, surface_point_lo)                                                                  \
  X(GpuSphere, radius_lo)                                                                         \
  X(GpuSphere, surface_normal_lo)                                                                 \
  X(GpuCamera, sensor_center)                                                                     \
  X(GpuCamera, projection)                                                                        \
  X(GpuCamera, sensor_right)                                                                      \
  X(GpuCamera, sensor_up)                                                                         \
  X(GpuRenderParams, camera)                                                                      \
  X(GpuRenderParams, width)                                                                       \
  X(GpuRenderParams, height)                                                                      \
  X(GpuRenderParams, sphere_count)                                                                \
  X(GpuRenderParams, max_bounces)                                                                 \
  X(GpuRenderParams, seed_lo)                                                                     \
  X(GpuRenderParams, seed_hi)                                                                     \
  X(GpuRenderParams, sample_begin)                                                                \
  X(GpuRenderParams, samples_per_pass)                                                            \
  X(GpuRenderParams, sampler)                                                                     \
  X(GpuRenderParams, ray_epsilon)                                                                 \
  X(GpuRenderParams, pixel_begin)                                                                 \
  X(GpuRenderParams, pixel_count)                                                                 \
  X(GpuRenderParams, estimator)                                                                   \
  X(GpuRenderParams, rr_from)                                                                     \
  X(GpuRenderParams, light_count)                                                                 \
  X(GpuRenderParams, bvh_node_count)                                                              \
  X(GpuRenderParams, slotted)                                                                     \
  X(GpuRenderParams, scatter_draw_pairs)                                                          \
  X(GpuSampleSlot, pixel)                                                                         \
  X(GpuSampleSlot, sample_begin)                                                                  \
  X(GpuLight, cap_axis)                                                                           \
  X(GpuLight, sphere)                                                                             \
  X(GpuLight, one_minus_cos_cap)                                                                  \
  X(GpuLight, cap_area)                                                                           \
  X(GpuLight, triangle)                                                                           \
  X(GpuLight, pick_probability)                                                                   \
  X(GpuLight, alias_threshold)                                                                    \
  X(GpuLight, alias)                                                                              \
  X(GpuLight, punctual)                                                                           \
  X(GpuLight, range)                                                                              \
  X(GpuLight, position)                                                                           \
  X(GpuLight, spot_scale)                                                                         \
  X(GpuLight, intensity)                                                                          \
  X(GpuLight, spot_offset)                                                                        \
  X(GpuEnvironment, kind)                                                                         \
  X(GpuEnvironment, width)                                                                        \
  X(GpuEnvironment, height)                                                                       \
  X(GpuEnvironment, pick_probability)                                                             \
  X(GpuEnvironment, radiance)                                                                     \
  X(GpuEnvironment, rotation_turns)                                                               \
  X(GpuEnvironment, texel_offset)                                                                 \
  X(GpuEnvironment, density_offset)                                                               \
  X(GpuEnvironment, row_alias_offset)                                                             \
  X(GpuEnvironment, column_alias_offset)                                                          \
  X(GpuPixelPass, sum)                                                                            \
  X(GpuPixelPass, valid_samples)                                                                  \
  X(GpuPixelPass, sum_sq)                                                                         \
  X(GpuPixelPass, segments)

#define CLPT_LAYOUT_STRUCTS(X) X(GpuMaterial) X(GpuBvhNode) X(GpuTriangleBlock) X(GpuTriangle) X(GpuTriangleShading) X(GpuSphere) X(GpuLight) X(GpuCamera) X(GpuRenderParams) X(GpuSampleSlot) X(GpuEnvironment) X(GpuPixelPass) \
  X(GpuTexturing) X(GpuTexture) X(GpuMaterialTextures) X(GpuTriangleTexturing) X(GpuTriangleTangents) X(GpuTriangleColors)

/* The sizes stated above, checked when each side compiles this header: by static_assert on the
 * host, and on the device by an array type whose size is negative when the size differs (OpenCL C
 * 1.2 has no static_assert), so a drifted struct fails the build of the host or of every kernel.
 * StructLayout.HostMatchesDevice then compares every field's offset at run time. */
#ifdef __OPENCL_C_VERSION__
#define CLPT_CHECK_SIZE(T, bytes) typedef char clpt_size_check_##T[(sizeof(T) == (bytes)) ? 1 : -1];
#else
#include <type_traits>
#define CLPT_CHECK_SIZE(T, bytes)                                                       \
  static_assert(sizeof(T) == (bytes), #T " must be " #bytes " bytes on both sides"); \
  static_assert(std::is_trivially_copyable_v<T> && std::is_standard_layout_v<T>,    \
                #T " is copied to the device byte for byte");
#endif
CLPT_CHECK_SIZE(GpuMaterial, 64)
CLPT_CHECK_SIZE(GpuBvhNode, 128)
CLPT_CHECK_SIZE(GpuTriangle, 48)
CLPT_CHECK_SIZE(GpuTriangleShading, 112)
CLPT_CHECK_SIZE(GpuSphere, 128)
CLPT_CHECK_SIZE(GpuLight, 80)
CLPT_CHECK_SIZE(GpuCamera, 48)
CLPT_CHECK_SIZE(GpuRenderParams, 120)
CLPT_CHECK_SIZE(GpuSampleSlot, 8)
CLPT_CHECK_SIZE(GpuEnvironment, 64)
CLPT_CHECK_SIZE(GpuPixelPass, 32)
CLPT_CHECK_SIZE(GpuTexturing, 32)
CLPT_CHECK_SIZE(GpuTexture, 64)
CLPT_CHECK_SIZE(GpuMaterialTextures, 48)
CLPT_CHECK_SIZE(GpuTriangleTexturing, 32)
CLPT_CHECK_SIZE(GpuTriangleTangents, 48)
CLPT_CHECK_SIZE(GpuTriangleColors, 48)
#undef CLPT_CHECK_SIZE

#endif /* CLPT_TYPES_H */
