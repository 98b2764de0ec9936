// Packing the scene's textures for the kernels (device_textures.h).
#include "scene/device_textures.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "kernels/types.h"
#include "scene/vec3_ops.h"
#include "util/error.h"
#include "util/half_float.h"

namespace clpt {
namespace {

const TextureRef* refs_of(const MaterialTextures& t, int i) {
  const TextureRef* all[5] = {&t.base_color, &t.metallic, &t.roughness, &t.emission, &t.normal};
  return all[i];
}

// The slot whose lookup reads refs_of(t, i).
TextureSlot slot_of_ref(int i) {
  const TextureSlot slots[5] = {kBaseSlot, kMetalRoughSlot, kMetalRoughSlot, kEmissionSlot, kNormalSlot};
  return slots[i];
}

size_t aligned(size_t n) { return (n + 15) & ~size_t(15); }

template <typename T>
void put(std::vector<uint8_t>& buffer, size_t at, const T& value) {
  std::memcpy(buffer.data() + at, &value, sizeof(T));
}

GpuTexture to_gpu(const TextureRef& ref, const TextureImage& image, uint32_t texels) {
  GpuTexture g{};
  g.texels = texels;
  g.width = uint32_t(image.width);
  g.height = uint32_t(image.height);
  g.channels = uint32_t(image.channels);
  g.storage = static_cast<clpt_u32>(image.storage);
  g.wrap_u = static_cast<clpt_u32>(ref.wrap_u);
  g.wrap_v = static_cast<clpt_u32>(ref.wrap_v);
  g.flags = (image.storage == TexelStorage::U8 && image.color_space == ColorSpace::Srgb ? CLPT_TEXTURE_SRGB : 0u) |
            (ref.filter == TextureFilter::Nearest ? CLPT_TEXTURE_NEAREST : 0u);
  for (int i = 0; i < 6; ++i) g.transform[i] = static_cast<float>(ref.uv_transform[size_t(i)]);
  g.channel = uint32_t(ref.channel);
  return g;
}

// The texels of `image` as the device stores them.
void put_texels(std::vector<uint8_t>& buffer, size_t at, const TextureImage& image) {
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const float v = image.pixels[i];
    switch (image.storage) {
      case TexelStorage::U8:
        buffer[at + i] = uint8_t(std::lround(std::clamp(double(v), 0.0, 1.0) * 255.0));
        break;
      case TexelStorage::Half:
        put(buffer, at + 2 * i, float_to_half_bits(v));
        break;
      default:
        put(buffer, at + 4 * i, v);
    }
  }
}

double corner_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e1 = sub(b, a), e2 = sub(c, a);
  const double l = length(e1) * length(e2);
  return l > 0 ? std::acos(std::clamp(dot(e1, e2) / l, -1.0, 1.0)) : 0;
}

Vec3 any_orthogonal(const Vec3& n) {
  const Vec3 axis = std::fabs(n[0]) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  return normalize(cross(axis, n));
}

}  // namespace

bool alpha_in_effect(const MaterialTextures& t, const std::vector<TextureImage>& images) {
  if (t.alpha_mode == AlphaMode::Opaque) return false;
  if (t.alpha_mode == AlphaMode::Mask && t.alpha_cutoff <= 0) return false;  // alpha >= 0 everywhere
  const bool texture_alpha = t.base_color.used() && images[size_t(t.base_color.image)].channels % 2 == 0;
  return texture_alpha || t.alpha < (t.alpha_mode == AlphaMode::Mask ? t.alpha_cutoff : 1.0);
}

bool has_vertex_colors(const TriangleMesh& mesh) {
  return !mesh.triangles.empty() && !mesh.colors.empty() && mesh.colors.size() == mesh.positions.size();
}

bool mesh_alpha_in_effect(const TriangleMesh& mesh, const std::vector<TextureImage>& images) {
  if (!has_vertex_colors(mesh)) return alpha_in_effect(mesh.material.textures, images);
  double least = 1;
  for (const auto& c : mesh.colors) least = std::min(least, c[3]);
  MaterialTextures t = mesh.material.textures;
  t.alpha *= least;
  return alpha_in_effect(t, images);
}

TextureUse texture_use(const Scene& scene) {
  TextureUse use;
  const auto uses = [&](const Material& m) {
    for (int i = 0; i < 5; ++i) {
      const TextureRef& r = *refs_of(m.textures, i);
      if (!r.used()) continue;
      const TextureImage& image = scene.images[size_t(r.image)];
      use.any = true;
      use.storages |= 1u << static_cast<uint32_t>(image.storage);
      use.slot_storages[size_t(slot_of_ref(i))] |= 1u << static_cast<uint32_t>(image.storage);
      use.channel_counts |= 1u << (image.channels - 1);
      use.wraps |= 1u << static_cast<uint32_t>(r.wrap_u);
      use.wraps |= 1u << static_cast<uint32_t>(r.wrap_v);
    }
    use.normal_maps |= m.textures.normal.used();
    use.emission |= m.textures.emission.used();
    use.alpha |= alpha_in_effect(m.textures, scene.images);
  };
  for (const TriangleMesh& mesh : scene.meshes)
    if (!mesh.triangles.empty()) {
      uses(mesh.material);
      use.alpha |= mesh_alpha_in_effect(mesh, scene.images);
      use.vertex_colors |= has_vertex_colors(mesh);
    }
  for (const Sphere& sphere : scene.spheres) {
    use.spheres |= sphere.material.textures.any();
    if (sphere.material.textures.any()) uses(sphere.material);
  }
  return use;
}

std::vector<std::array<double, 4>> generate_tangents(const TriangleMesh& mesh) {
  const size_t n = mesh.positions.size();
  std::vector<Vec3> normal(n, Vec3{0, 0, 0}), tangent(n, Vec3{0, 0, 0}), bitangent(n, Vec3{0, 0, 0});
  for (const auto& t : mesh.triangles) {
    const Vec3 &p0 = mesh.positions[t[0]], &p1 = mesh.positions[t[1]], &p2 = mesh.positions[t[2]];
    const Vec3 e1 = sub(p1, p0), e2 = sub(p2, p0);
    const Vec3 face = cross(e1, e2);  // area-weighted geometric normal
    const auto &uv0 = mesh.uvs[t[0]], &uv1 = mesh.uvs[t[1]], &uv2 = mesh.uvs[t[2]];
    const double du1 = uv1[0] - uv0[0], dv1 = uv1[1] - uv0[1], du2 = uv2[0] - uv0[0], dv2 = uv2[1] - uv0[1];
    const double det = du1 * dv2 - du2 * dv1;
    Vec3 tu{0, 0, 0}, tv{0, 0, 0};
    if (std::fabs(det) > 1e-20) {
      // dp/du and dp/dv: e1 = du1 T + dv1 B, e2 = du2 T + dv2 B.
      tu = scale(sub(scale(e1, dv2), scale(e2, dv1)), 1 / det);
      tv = scale(sub(scale(e2, du1), scale(e1, du2)), 1 / det);
      const double lu = length(tu), lv = length(tv);
      tu = lu > 0 ? scale(tu, 1 / lu) : tu;
      tv = lv > 0 ? scale(tv, 1 / lv) : tv;
    }
    const double angles[3] = {corner_angle(p0, p1, p2), corner_angle(p1, p2, p0), corner_angle(p2, p0, p1)};
    for (int c = 0; c < 3; ++c) {
      normal[t[c]] = add(normal[t[c]], face);
      tangent[t[c]] = add(tangent[t[c]], scale(tu, angles[c]));
      bitangent[t[c]] = add(bitangent[t[c]], scale(tv, angles[c]));
    }
  }
  std::vector<std::array<double, 4>> out(n);
  for (size_t i = 0; i < n; ++i) {
    Vec3 nrm = mesh.normals.empty() ? normal[i] : mesh.normals[i];
    nrm = length(nrm) > 0 ? normalize(nrm) : Vec3{0, 0, 1};
    Vec3 t = sub(tangent[i], scale(nrm, dot(nrm, tangent[i])));
    t = length(t) > 1e-12 ? normalize(t) : any_orthogonal(nrm);
    const double w = dot(cross(nrm, t), bitangent[i]) < 0 ? -1 : 1;
    out[i] = {t[0], t[1], t[2], w};
  }
  return out;
}

std::vector<uint8_t> pack_texturing(const Scene& scene, const std::vector<uint32_t>& triangle_order,
                                    const std::vector<uint32_t>& sphere_order) {
  const TextureUse use = texture_use(scene);
  if (!use.any && !use.alpha && !use.vertex_colors) return {};
  std::vector<GpuTexture> textures;
  std::vector<GpuMaterialTextures> materials;
  std::vector<GpuTriangleTexturing> triangles;
  std::vector<GpuTriangleTangents> tangents;
  std::vector<GpuTriangleColors> colors;
  // Texel offsets are relative to the texel section until the layout is known.
  std::vector<size_t> image_offset(scene.images.size());
  size_t texel_bytes = 0;
  for (size_t i = 0; i < scene.images.size(); ++i) {
    image_offset[i] = texel_bytes;
    texel_bytes = aligned(texel_bytes + scene.images[i].device_bytes());
  }
  // A textured material's record and its textures' table entries; its index.
  const auto add_material = [&](const MaterialTextures& mt, bool alpha) {
    GpuMaterialTextures g{};
    clpt_u32* slots[5] = {&g.base_color, &g.metallic, &g.roughness, &g.emission, &g.normal};
    for (int i = 0; i < 5; ++i) {
      const TextureRef& r = *refs_of(mt, i);
      *slots[i] = CLPT_TEXTURE_NONE;
      if (!r.used()) continue;
      *slots[i] = uint32_t(textures.size());
      textures.push_back(to_gpu(r, scene.images[size_t(r.image)], uint32_t(image_offset[size_t(r.image)])));
    }
    g.normal_scale = static_cast<float>(mt.normal_scale);
    g.alpha_mode = static_cast<clpt_u32>(alpha ? mt.alpha_mode : AlphaMode::Opaque);
    g.alpha_cutoff = static_cast<float>(mt.alpha_cutoff);
    g.alpha = static_cast<float>(mt.alpha);
    materials.push_back(g);
    return uint32_t(materials.size() - 1);
  };
  for (const TriangleMesh& mesh : scene.meshes) {
    const MaterialTextures& mt = mesh.material.textures;
    uint32_t material = CLPT_TEXTURE_NONE;
    std::vector<std::array<double, 4>> mesh_tangents;
    const bool alpha = mesh_alpha_in_effect(mesh, scene.images);
    const bool colored = has_vertex_colors(mesh);
    const bool has_uvs = mesh.uvs.size() == mesh.positions.size();
    if ((mt.any() || alpha || colored) && !mesh.triangles.empty()) {
      if (mt.any() && !has_uvs) {
        const TextureRef* named = nullptr;
        for (int i = 0; i < 5 && !named; ++i)
          if (refs_of(mt, i)->used()) named = refs_of(mt, i);
        throw Error(ExitCode::BadScene, mesh.where.str() + ": mesh '" + mesh.name +
                                            (mesh.gltf_element.empty() ? "" : "' (" + mesh.gltf_element + ")") +
                                            "' has no texture coordinates, and its material is textured (" +
                                            named->where + ")");
      }
      material = add_material(mt, alpha);
      if (mt.normal.used()) mesh_tangents = mesh.tangents.size() == mesh.positions.size() ? mesh.tangents : generate_tangents(mesh);
    }
    for (const auto& t : mesh.triangles) {
      GpuTriangleTexturing g{};
      float* uv[3] = {g.uv0, g.uv1, g.uv2};
      if (material != CLPT_TEXTURE_NONE && has_uvs)
        for (int c = 0; c < 3; ++c)
          for (int k = 0; k < 2; ++k) uv[c][k] = static_cast<float>(mesh.uvs[t[c]][size_t(k)]);
      g.material = material;
      triangles.push_back(g);
      if (use.normal_maps) {
        GpuTriangleTangents tg{};
        float* corner[3] = {tg.t0, tg.t1, tg.t2};
        if (!mesh_tangents.empty())
          for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 4; ++k) corner[c][k] = static_cast<float>(mesh_tangents[t[c]][size_t(k)]);
        tangents.push_back(tg);
      }
      if (use.vertex_colors) {
        GpuTriangleColors k{};
        float* corner[3] = {k.c0, k.c1, k.c2};
        for (int c = 0; c < 3; ++c)
          for (int i = 0; i < 4; ++i) corner[c][i] = colored ? static_cast<float>(mesh.colors[t[c]][size_t(i)]) : 1.0f;
        colors.push_back(k);
      }
    }
  }
  // Spheres (scene order): their records, the spherical mapping's (no alpha: spheres are opaque).
  std::vector<uint32_t> sphere_material(scene.spheres.size(), CLPT_TEXTURE_NONE);
  if (use.spheres)
    for (size_t i = 0; i < scene.spheres.size(); ++i)
      if (scene.spheres[i].material.textures.any()) {
        const Sphere& sphere = scene.spheres[i];
        if (sphere.material.textures.normal.used())
          throw Error(ExitCode::BadScene, sphere.material.textures.normal.where + ": sphere '" + sphere.name +
                                              "': normal maps apply to meshes only (docs/textures.md)");
        sphere_material[i] = add_material(sphere.material.textures, false);
      }
  GpuTexturing header{};
  size_t at = aligned(sizeof(GpuTexturing));
  header.textures = uint32_t(at);
  at = aligned(at + textures.size() * sizeof(GpuTexture));
  header.materials = uint32_t(at);
  at = aligned(at + materials.size() * sizeof(GpuMaterialTextures));
  header.triangles = uint32_t(at);
  at = aligned(at + triangle_order.size() * sizeof(GpuTriangleTexturing));
  header.tangents = use.normal_maps ? uint32_t(at) : 0u;
  if (use.normal_maps) at = aligned(at + triangle_order.size() * sizeof(GpuTriangleTangents));
  header.colors = use.vertex_colors ? uint32_t(at) : 0u;
  if (use.vertex_colors) at = aligned(at + triangle_order.size() * sizeof(GpuTriangleColors));
  header.spheres = use.spheres ? uint32_t(at) : 0u;
  if (use.spheres) at = aligned(at + scene.spheres.size() * sizeof(uint32_t));
  const size_t texels = at;
  const uint64_t total = uint64_t(texels) + texel_bytes;
  if (total > 0xffffffffull)
    throw Error(ExitCode::BadScene, scene.file + ": the scene's textures and texture coordinates need " + std::to_string(total) +
                                        " bytes, more than the 4 GiB one texturing buffer holds (docs/textures.md)");
  for (GpuTexture& t : textures) t.texels += uint32_t(texels);
  std::vector<uint8_t> buffer(size_t(total), 0);
  put(buffer, 0, header);
  for (size_t i = 0; i < textures.size(); ++i) put(buffer, header.textures + i * sizeof(GpuTexture), textures[i]);
  for (size_t i = 0; i < materials.size(); ++i)
    put(buffer, header.materials + i * sizeof(GpuMaterialTextures), materials[i]);
  for (size_t i = 0; i < triangle_order.size(); ++i) {
    put(buffer, header.triangles + i * sizeof(GpuTriangleTexturing), triangles[triangle_order[i]]);
    if (use.normal_maps) put(buffer, header.tangents + i * sizeof(GpuTriangleTangents), tangents[triangle_order[i]]);
    if (use.vertex_colors) put(buffer, header.colors + i * sizeof(GpuTriangleColors), colors[triangle_order[i]]);
  }
  for (size_t i = 0; use.spheres && i < scene.spheres.size(); ++i)
    put(buffer, header.spheres + i * sizeof(uint32_t), sphere_material[sphere_order.empty() ? i : sphere_order[i]]);
  for (size_t i = 0; i < scene.images.size(); ++i) put_texels(buffer, texels + image_offset[i], scene.images[i]);
  return buffer;
}

std::string explain_textures(const Scene& scene) {
  std::ostringstream o;
  for (const TextureImage& image : scene.images)
    o << "  " << image.file << ": " << image.width << " x " << image.height << ", " << image.channels << " channel"
      << (image.channels > 1 ? "s" : "") << ", " << texel_storage_name(image.storage) << ", "
      << (image.storage == TexelStorage::U8 ? color_space_name(image.color_space) : "linear") << ", "
      << image.device_bytes() << " bytes on the device\n";
  return o.str();
}

void check_texture_memory(const Scene& scene, uint64_t max_alloc_bytes, const std::string& device) {
  uint64_t total = 0;
  const TextureImage* largest = nullptr;
  for (const TextureImage& image : scene.images) {
    total += image.device_bytes();
    if (!largest || image.device_bytes() > largest->device_bytes()) largest = &image;
  }
  if (!largest || total <= max_alloc_bytes) return;
  throw Error(ExitCode::BadScene,
              scene.file + ": the scene's textures take " + std::to_string(total) + " bytes, more than " + device +
                  " allocates at once (" + std::to_string(max_alloc_bytes) + " bytes); the largest is " + largest->file +
                  " (" + std::to_string(largest->width) + " x " + std::to_string(largest->height) + ", " +
                  std::to_string(largest->device_bytes()) + " bytes)");
}

}  // namespace clpt
