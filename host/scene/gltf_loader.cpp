// glTF file -> Scene, and the contents a [[gltf]] table places (gltf_loader.h): the document
// (gltf_document.h), the scene's nodes (gltf_nodes.h), then materials, primitives, lights and
// the view, each in its own file.
#include "scene/gltf_loader.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <system_error>

#include "scene/gltf_camera.h"
#include "scene/gltf_document.h"
#include "scene/gltf_error.h"
#include "scene/gltf_glb.h"
#include "scene/gltf_lights.h"
#include "scene/gltf_material.h"
#include "scene/gltf_nodes.h"
#include "scene/gltf_primitives.h"
#include "scene/texture_load.h"
#include "util/error.h"
#include "util/hash.h"

namespace clpt {
namespace {

constexpr uint64_t kMaxFileBytes = uint64_t(1) << 30;

struct Contents {
  GltfDocument document;
  std::vector<TextureImage> images;
  std::vector<NodeInstance> nodes;
  std::vector<TriangleMesh> meshes;
  std::vector<PunctualLight> lights;
};

// Everything but the view: the document, the scene's nodes under `root`, meshes and lights.
Contents read_contents(std::string_view bytes, const std::string& path, const Affine& root) {
  Contents c;
  c.document = parse_gltf_document(bytes, path);
  const tinygltf::Model& model = c.document.model;
  std::vector<std::string>& warnings = c.document.warnings;
  const std::vector<Material> materials = convert_materials(model, path, c.images, warnings);
  c.nodes = scene_nodes(model, chosen_scene(model), root);
  PrimitiveContext primitives{model, materials, c.document.total_bytes, {}, {}};
  for (const NodeInstance& instance : c.nodes) append_node_meshes(primitives, instance, c.meshes);
  warnings.insert(warnings.end(), primitives.warnings.begin(), primitives.warnings.end());
  if (!primitives.skipped_modes.empty()) {
    std::string modes;
    for (const std::string& m : primitives.skipped_modes) modes += (modes.empty() ? "" : ", ") + m;
    warnings.push_back("meshes: primitives of mode " + modes + " skipped (clpt renders triangles)");
  }
  const double range_scale = std::cbrt(std::fabs(determinant(root.linear)));
  c.lights = convert_lights(model, c.nodes, range_scale, path);
  return c;
}

std::string read_file(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) gltf_fail("glTF", "cannot open the file: No such file or directory");
  if (!std::filesystem::is_regular_file(status)) gltf_fail("glTF", "cannot open the file: not a regular file");
  const uint64_t size = std::filesystem::file_size(path, ec);
  if (ec || size > kMaxFileBytes)
    gltf_fail("glTF", ec ? "cannot open the file: " + ec.message() : "the file is over the limit of 1 GiB");
  errno = 0;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) gltf_fail("glTF", std::string("cannot open the file: ") + std::strerror(errno));
  std::string bytes(size, '\0');
  if (size > 0 && std::fread(bytes.data(), 1, size, file.get()) != size)
    gltf_fail("glTF", "cannot read the file: it changed size while being read");
  return bytes;
}

// Light from a punctual light, the environment, or an emitting material (an emitter, or a
// pbr material with an emission) on a mesh or a sphere.
bool has_emission(const Scene& scene) {
  if (!scene.lights.empty() || scene.environment) return true;
  const auto emits = [](const Material& m) {
    return m.type == MaterialType::Emitter || m.emission[0] > 0 || m.emission[1] > 0 || m.emission[2] > 0;
  };
  for (const TriangleMesh& m : scene.meshes)
    if (emits(m.material)) return true;
  for (const Sphere& s : scene.spheres)
    if (emits(s.material)) return true;
  return false;
}

}  // namespace

bool is_gltf_file(const std::string& path, std::string_view bytes) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".gltf" || ext == ".glb" || has_glb_magic(bytes);
}

Scene load_gltf_scene(std::string_view bytes, const std::string& path, const GltfView& view) {
  try {
    Contents c = read_contents(bytes, path, Affine{});
    Scene scene;
    scene.file = path;
    // The document's hash, chained over its images (external files are not in it).
    uint64_t hash = fnv1a64(c.document.hash);
    for (const TextureImage& image : c.images) hash = fnv1a64(image.file + '\0' + image.hash + '\n', hash);
    scene.file_hash = c.images.empty() ? c.document.hash : hex64(hash);
    scene.images = std::move(c.images);
    scene.settings.estimator = "nee";
    scene.meshes = std::move(c.meshes);
    scene.lights = std::move(c.lights);
    if (scene.meshes.empty())
      gltf_fail("scenes[" + std::to_string(chosen_scene(c.document.model)) + "]", "the scene has no triangles to render");
    set_view(c.document.model, c.nodes, view, scene, c.document.warnings);
    for (const std::string& w : c.document.warnings) scene.warnings.push_back(path + ": " + w);
    for (TriangleMesh& m : scene.meshes) {
      m.file = path;
      m.file_hash = scene.file_hash;
      m.where = SourcePosition{path, 0, 0};
    }
    check_textured_meshes(scene);
    return scene;
  } catch (const GltfError& e) {
    throw Error(ExitCode::BadScene, path + ": " + e.what());
  }
}

std::string unlit_scene_warning(const Scene& scene) {
  if (has_emission(scene)) return "";
  return scene.file + ": the scene has no lights, no emissive material and no environment, so the image will be black "
                      "(--environment FILE lights it)";
}

GltfContents load_gltf_contents(const std::string& path, const MeshPlacement& placement) {
  const std::string bytes = read_file(path);
  Contents c = read_contents(bytes, path, placement_affine(placement));
  GltfContents out;
  out.meshes = std::move(c.meshes);
  for (TriangleMesh& m : out.meshes) {
    m.placement = placement;
    m.file_hash = c.document.hash;
  }
  out.lights = std::move(c.lights);
  out.warnings = std::move(c.document.warnings);
  out.hash = c.document.hash;
  out.images = std::move(c.images);
  for (TriangleMesh& m : out.meshes) m.file = path;  // the TOML loader renames it as the table names it
  return out;
}

}  // namespace clpt
