// The scene's textures as the kernels read them (kernels/types.h, GpuTexturing; kernels/texture.cl):
// one byte buffer holding the texture table, the textured materials, every triangle's texture
// coordinates, tangents where a material has a normal map (the mesh's, else generated), every
// triangle's corner colours where a mesh has vertex colours (glTF COLOR_0) and the texels, packed
// 8-bit, half or float with 1 to 4 channels; each textured material's alpha mode.
// Empty for a scene without textures, vertex colours and a material whose alpha is in effect.
#pragma once

#include <array>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace clpt {

// The material slots whose lookups the kernels compile apart (kernels/texture.cl): base colour
// (and its alpha), metallic-roughness (metallic and roughness), normal map, emission.
enum TextureSlot : int { kBaseSlot, kMetalRoughSlot, kNormalSlot, kEmissionSlot };
inline constexpr int kTextureSlots = 4;

// What the kernels compile for the scene's textures (kernel_options.cpp reads it): bit
// (1 << CLPT_TEXEL_*) of each storage used, (1 << (channels - 1)) of each channel count,
// (1 << CLPT_WRAP_*) of each wrap mode, and whether a material has a normal map.
struct TextureUse {
  bool any = false;
  uint32_t storages = 0;
  std::array<uint32_t, kTextureSlots> slot_storages{};  // the storages of each slot's images
  uint32_t channel_counts = 0;
  uint32_t wraps = 0;
  bool normal_maps = false;
  bool emission = false;  // an emission texture (light sampling then reads it too)
  bool alpha = false;     // a material whose alpha cuts its surface (alpha_in_effect): CLPT_HAS_ALPHA
  bool spheres = false;   // a sphere's material is textured (CLPT_HAS_SPHERE_TEXTURES; its images count above)
  bool vertex_colors = false;  // a mesh with vertex colours (glTF COLOR_0): CLPT_HAS_VERTEX_COLORS
};
TextureUse texture_use(const Scene& scene);

// Whether a material's alpha can make its surface absent anywhere (kernels/alpha.cl): MASK or
// BLEND, with a base colour texture that has an alpha channel (2 or 4 channels) or a factor that
// cuts by itself (MASK: alpha < alpha_cutoff; BLEND: alpha < 1); never for a MASK cutoff <= 0.
// Other materials render as OPAQUE ones (the same image, no alpha code).
bool alpha_in_effect(const MaterialTextures& t, const std::vector<TextureImage>& images);

// Whether a mesh has vertex colours (TriangleMesh::colors, glTF COLOR_0) and triangles.
bool has_vertex_colors(const TriangleMesh& mesh);

// alpha_in_effect for a mesh: its material's, the factor's alpha taken times the least alpha of
// its vertex colours (the alpha interpolated over a triangle is never below its corners' least).
bool mesh_alpha_in_effect(const TriangleMesh& mesh, const std::vector<TextureImage>& images);

// The texturing buffer for the scene's triangles in the order `triangle_order` gives (entry i of
// the device's triangles is the scene's triangle triangle_order[i], counting mesh by mesh) and its
// spheres in the order `sphere_order` gives (entry i of the device's spheres is the scene's sphere
// sphere_order[i]; empty: the scene's order), whose section (GpuTexturing.spheres, one u32 each:
// a textured-material index or CLPT_TEXTURE_NONE) is there only when a sphere is textured; empty
// when no material is textured or cut by its alpha and no mesh has vertex colours. Throws
// Error(BadScene) naming the mesh and the material's key when a textured material's mesh has no
// texture coordinates, or when the buffer would need more than 2^32 bytes (the offsets are 32-bit).
std::vector<uint8_t> pack_texturing(const Scene& scene, const std::vector<uint32_t>& triangle_order,
                                    const std::vector<uint32_t>& sphere_order = {});

// Per-vertex tangents of a mesh with texture coordinates (MikkTSpace-style, docs/textures.md):
// each triangle's tangent and bitangent from its uv gradients, summed per vertex weighted by the
// corner's angle, made orthogonal to the vertex normal (the mesh's, else the area-weighted
// geometric one); w = the bitangent's sign. A vertex with no usable uv gradient gets any unit
// vector orthogonal to its normal.
std::vector<std::array<double, 4>> generate_tangents(const TriangleMesh& mesh);

// One line per image: "  file: W x H, C channel(s), STORAGE, COLOURSPACE, N bytes on the device".
std::string explain_textures(const Scene& scene);

// Throws Error(BadScene) when the scene's texels exceed `max_alloc_bytes` (the device's largest
// allocation), naming the largest image and the device.
void check_texture_memory(const Scene& scene, uint64_t max_alloc_bytes, const std::string& device);

}  // namespace clpt
