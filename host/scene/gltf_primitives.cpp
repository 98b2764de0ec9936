// Mesh primitives -> TriangleMeshes (gltf_primitives.h).
#include "scene/gltf_primitives.h"

#include <cmath>
#include <limits>

#include "scene/gltf_accessor.h"
#include "scene/gltf_error.h"
#include "scene/mesh_placement.h"

namespace clpt {
namespace {

const char* kModeNames[] = {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP", "TRIANGLES", "TRIANGLE_STRIP", "TRIANGLE_FAN"};

// The glTF default material (section 3.9.6): base colour 1, metallic 1, roughness 1, single-sided.
Material default_material() {
  Material m;
  m.type = MaterialType::Pbr;
  m.reflectance = {1, 1, 1};
  m.double_sided = false;
  return m;
}

std::vector<Vec3> vec3s(const std::vector<double>& values) {
  std::vector<Vec3> out(values.size() / 3);
  for (size_t i = 0; i < out.size(); ++i) out[i] = {values[3 * i], values[3 * i + 1], values[3 * i + 2]};
  return out;
}

// The vertex indices of the primitive: its index accessor's values (each checked against the
// vertex count and the primitive-restart value), or 0 .. vertices - 1.
std::vector<uint32_t> vertex_sequence(PrimitiveContext& c, const tinygltf::Primitive& p, size_t vertices,
                                      const std::string& element) {
  std::vector<uint32_t> out;
  if (p.indices < 0) {
    out.resize(vertices);
    for (size_t i = 0; i < vertices; ++i) out[i] = uint32_t(i);
    return out;
  }
  const std::vector<double> values =
      read_accessor(c.model, p.indices, AccessorUse::Indices, element + ".indices", c.total_bytes);
  const int type = c.model.accessors[size_t(p.indices)].componentType;
  const double restart = type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 255.0
                         : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 65535.0
                                                                           : 4294967295.0;
  out.reserve(values.size());
  for (size_t i = 0; i < values.size(); ++i) {
    if (values[i] == restart)
      gltf_fail(element + ".indices", "index " + std::to_string(i) + " is the primitive-restart value " +
                                          std::to_string(uint64_t(restart)) + ", which glTF does not allow");
    if (values[i] >= double(vertices))
      gltf_fail(element + ".indices", "index " + std::to_string(i) + " is " + std::to_string(uint64_t(values[i])) +
                                          ", out of range (the primitive has " + std::to_string(vertices) + " vertices)");
    out.push_back(uint32_t(values[i]));
  }
  return out;
}

// Triangles of a list, strip (glTF 2.0 section 3.7.2.1: odd triangles reversed to keep the
// winding) or fan.
std::vector<std::array<uint32_t, 3>> assemble(const std::vector<uint32_t>& v, int mode, const std::string& element) {
  const size_t n = v.size();
  const std::string what = mode == TINYGLTF_MODE_TRIANGLES ? "TRIANGLES" : kModeNames[mode];
  if (n < 3 || (mode == TINYGLTF_MODE_TRIANGLES && n % 3 != 0))
    gltf_fail(element, std::to_string(n) + " vertices cannot make " + what +
                           (mode == TINYGLTF_MODE_TRIANGLES ? " (a multiple of 3 is needed)" : " (3 or more are needed)"));
  std::vector<std::array<uint32_t, 3>> out;
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    for (size_t i = 0; i < n; i += 3) out.push_back({v[i], v[i + 1], v[i + 2]});
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (size_t i = 0; i + 2 < n; ++i)
      out.push_back(i % 2 == 0 ? std::array<uint32_t, 3>{v[i], v[i + 1], v[i + 2]}
                               : std::array<uint32_t, 3>{v[i + 1], v[i], v[i + 2]});
  } else {
    for (size_t i = 1; i + 1 < n; ++i) out.push_back({v[i], v[i + 1], v[0]});
  }
  return out;
}

// The primitive's vertices and triangles in world space (normals not yet normalised).
LocalMesh world_primitive(PrimitiveContext& c, const tinygltf::Primitive& p, const Affine& world, int mode,
                          const std::string& element, int uv_set, std::vector<std::array<double, 2>>& uvs,
                          std::vector<std::array<double, 4>>& tangents, std::vector<std::array<double, 4>>& colors) {
  LocalMesh local;
  const int position = p.attributes.at("POSITION");
  const size_t vertices = accessor_count(c.model, position, AccessorUse::Position, element + ".attributes.POSITION");
  if (vertices > std::numeric_limits<uint32_t>::max())
    gltf_fail(element + ".attributes.POSITION", "more than 2^32 - 1 vertices");
  for (const Vec3& q : vec3s(read_accessor(c.model, position, AccessorUse::Position, element + ".attributes.POSITION",
                                           c.total_bytes)))
    local.positions.push_back(transform_point(world, q));
  const auto same_count = [&](const char* name, int accessor, AccessorUse use) {
    const std::string attribute = element + ".attributes." + name;
    if (accessor_count(c.model, accessor, use, attribute) != vertices)
      gltf_fail(attribute, "has " + std::to_string(accessor_count(c.model, accessor, use, attribute)) +
                               " elements, POSITION has " + std::to_string(vertices));
    return read_accessor(c.model, accessor, use, attribute, c.total_bytes);
  };
  if (const auto n = p.attributes.find("NORMAL"); n != p.attributes.end()) {
    for (const Vec3& q : vec3s(same_count("NORMAL", n->second, AccessorUse::Normal))) {
      if (q[0] == 0 && q[1] == 0 && q[2] == 0)
        gltf_fail(element + ".attributes.NORMAL", "normal " + std::to_string(local.normals.size()) + " is zero");
      local.normals.push_back(transform_normal(world, q));
    }
  }
  // The one coordinate set the material's textures read (gltf_material.cpp: their texCoord).
  const std::string texcoord = "TEXCOORD_" + std::to_string(uv_set);
  if (const auto t = p.attributes.find(texcoord); t != p.attributes.end()) {
    const std::vector<double> values = same_count(texcoord.c_str(), t->second, AccessorUse::Texcoord);
    // glTF's (0, 0) is the image's top-left; clpt keeps OBJ's bottom-left (scene.h).
    for (size_t i = 0; i + 1 < values.size(); i += 2) uvs.push_back({values[i], 1 - values[i + 1]});
  }
  if (const auto t = p.attributes.find("TANGENT"); t != p.attributes.end()) {
    // xyz a direction (the world transform's linear part), w the bitangent's sign: flipped where
    // the transform mirrors, as the normal's side and the winding are (docs/textures.md).
    const std::vector<double> values = same_count("TANGENT", t->second, AccessorUse::Tangent);
    const bool mirrored = determinant(world.linear) < 0;
    for (size_t i = 0; i + 3 < values.size(); i += 4) {
      const Vec3 d = transform_vector(world, {values[i], values[i + 1], values[i + 2]});
      const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      if (!(length > 0) || (values[i + 3] != 1 && values[i + 3] != -1))
        gltf_fail(element + ".attributes.TANGENT",
                  "tangent " + std::to_string(i / 4) + " must have a non-zero xyz and w = 1 or -1");
      const double w = mirrored ? -values[i + 3] : values[i + 3];
      tangents.push_back({d[0] / length, d[1] / length, d[2] / length, w});
    }
  }
  if (const auto k = p.attributes.find("COLOR_0"); k != p.attributes.end()) {
    // Linear RGB(A) multipliers of the base colour (glTF 2.0 section 3.7.2.1); a VEC3's alpha is 1.
    const std::vector<double> values = same_count("COLOR_0", k->second, AccessorUse::Color);
    const size_t n = values.size() / vertices;  // 3 or 4
    for (size_t i = 0; i + n <= values.size(); i += n) {
      std::array<double, 4> rgba = {values[i], values[i + 1], values[i + 2], n == 4 ? values[i + 3] : 1.0};
      for (double x : rgba)
        if (x < 0)
          gltf_fail(element + ".attributes.COLOR_0", "colour " + std::to_string(i / n) + " has a negative component");
      colors.push_back(rgba);
    }
  }
  local.triangles = assemble(vertex_sequence(c, p, vertices, element), mode, element);
  c.triangles += local.triangles.size();
  if (c.triangles > kMaxGltfTriangles)
    gltf_fail(element, "the scene's placements add up to more than 2^27 triangles, the most clpt renders");
  if (determinant(world.linear) < 0)
    for (auto& t : local.triangles) std::swap(t[1], t[2]);
  return local;
}

// One primitive as a TriangleMesh appended to `out`, or nothing (a warning says why).
void append_primitive(PrimitiveContext& c, const NodeInstance& instance, int mesh_index, size_t index,
                      std::vector<TriangleMesh>& out) {
  const tinygltf::Mesh& mesh = c.model.meshes[size_t(mesh_index)];
  const tinygltf::Primitive& p = mesh.primitives[index];
  const std::string element = "meshes[" + std::to_string(mesh_index) + "].primitives[" + std::to_string(index) + "]";
  const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
  if (mode > TINYGLTF_MODE_TRIANGLE_FAN) gltf_fail(element + ".mode", std::to_string(p.mode) + " is not a glTF primitive mode");
  if (mode < TINYGLTF_MODE_TRIANGLES) {
    c.skipped_modes.insert(kModeNames[mode]);
    return;
  }
  if (p.material >= 0 && size_t(p.material) >= c.materials.size())
    gltf_fail(element + ".material", std::to_string(p.material) + " is out of range (the file has " +
                                         std::to_string(c.materials.size()) + " materials)");
  if (!p.attributes.count("POSITION")) {
    c.warnings.push_back(element + ": no POSITION attribute; skipped");
    return;
  }
  TriangleMesh m;
  m.name = (mesh.name.empty() ? "meshes[" + std::to_string(mesh_index) + "]" : mesh.name) + "/primitive " + std::to_string(index);
  m.gltf_element = "nodes[" + std::to_string(instance.node) + "] " + element;
  m.material = p.material >= 0 ? c.materials[size_t(p.material)] : default_material();
  const int uv_set = m.material.textures.uv_set;
  if (uv_set > 0 && m.material.textures.any() && !p.attributes.count("TEXCOORD_" + std::to_string(uv_set)))
    gltf_fail(element + ".attributes", "no TEXCOORD_" + std::to_string(uv_set) + ", which the textures of its material (materials[" +
                                           std::to_string(p.material) + "]) read by their texCoord");
  const LocalMesh local = world_primitive(c, p, instance.world, mode, element, uv_set, m.uvs, m.tangents, m.colors);
  const size_t dropped = place_mesh(local, m);  // the identity placement: drops degenerate triangles
  for (size_t i = 0; i < m.positions.size(); ++i)
    for (double x : m.positions[i])
      if (!std::isfinite(x))
        gltf_fail(m.gltf_element, "vertex " + std::to_string(i) + " is not finite after the node's transform");
  if (m.triangles.empty()) {
    c.warnings.push_back(m.gltf_element + ": all " + std::to_string(dropped) + " triangles have zero area; skipped");
    return;
  }
  if (dropped > 0)
    c.warnings.push_back(m.gltf_element + ": mesh '" + m.name + "': " + std::to_string(dropped) + " of " +
                         std::to_string(local.triangles.size()) + " triangles have zero area and were dropped");
  out.push_back(std::move(m));
}

}  // namespace

void append_node_meshes(PrimitiveContext& context, const NodeInstance& instance, std::vector<TriangleMesh>& out) {
  const int mesh = context.model.nodes[size_t(instance.node)].mesh;
  if (mesh < 0) return;
  if (size_t(mesh) >= context.model.meshes.size())
    gltf_fail("nodes[" + std::to_string(instance.node) + "].mesh",
              std::to_string(mesh) + " is out of range (the file has " + std::to_string(context.model.meshes.size()) +
                  " meshes)");
  for (size_t i = 0; i < context.model.meshes[size_t(mesh)].primitives.size(); ++i)
    append_primitive(context, instance, mesh, i, out);
}

}  // namespace clpt
