#include "scene/device_scene.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "scene/device_textures.h"
#include "scene/environment_map.h"
#include "scene/light_pick.h"
#include "scene/vec3_ops.h"
#include "util/error.h"

namespace clpt {
namespace {

void store(float out[3], const Vec3& v) {
  for (int i = 0; i < 3; ++i) out[i] = static_cast<float>(v[i]);
}
// v as a float and the float of what that float left out (types.h: the *_lo fields).
float store_split(double v, float& lo) {
  const float hi = static_cast<float>(v);
  lo = static_cast<float>(v - double(hi));
  return hi;
}
void store_split(float hi[3], float lo[3], const Vec3& v) {
  for (int i = 0; i < 3; ++i) hi[i] = store_split(v[i], lo[i]);
}

GpuMaterial to_gpu(const Material& m) {
  GpuMaterial g{};
  g.kind = static_cast<clpt_u32>(m.type);
  store(g.reflectance, m.reflectance);
  g.phong_exponent = static_cast<float>(m.phong_exponent);
  store(g.emission, m.emission);
  g.ior = static_cast<float>(m.ior);
  if (m.type == MaterialType::Pbr) {
    g.metallic = static_cast<float>(m.metallic);
    g.roughness = static_cast<float>(m.roughness);
    g.transmission = static_cast<float>(m.transmission);
    g.thickness = static_cast<float>(m.thickness);
    // Beer's law: attenuation_color is what is left after attenuation_distance.
    for (int i = 0; i < 3; ++i)
      g.attenuation[i] = m.thickness > 0 && m.attenuation_distance > 0
                             ? static_cast<float>(-std::log(std::max(m.attenuation_color[i], 1e-30)) / m.attenuation_distance)
                             : 0.0f;
  }
  return g;
}

GpuSphere to_gpu(const Sphere& s, const Vec3& anchor, const Vec3& camera_position) {
  GpuSphere g{};
  const SurfaceFrame frame = surface_frame(s, anchor);
  store_split(g.surface_point, g.surface_point_lo, sub(frame.point, camera_position));
  store_split(g.surface_normal, g.surface_normal_lo, frame.normal);
  g.radius = store_split(s.radius, g.radius_lo);
  g.material = to_gpu(s.material);
  return g;
}

// The triangles of every mesh, camera-relative (subtracted in double, then rounded once: a
// vertex shared by two triangles becomes the same float in both, which watertightness needs),
// with their hierarchy primitives; spheres too when they are hierarchy primitives.
void add_triangles(const Scene& scene, DeviceScene& out, std::vector<BvhPrimitive>& prims) {
  const Vec3& camera = scene.camera.position;
  for (const TriangleMesh& mesh : scene.meshes) {
    std::vector<std::array<float, 3>> vertices;
    vertices.reserve(mesh.positions.size());
    for (const Vec3& p : mesh.positions) {
      const Vec3 r = sub(p, camera);
      vertices.push_back({static_cast<float>(r[0]), static_cast<float>(r[1]), static_cast<float>(r[2])});
    }
    GpuTriangleShading shading{};
    shading.material = to_gpu(mesh.material);
    shading.has_normals = mesh.normals.empty() ? 0u : 1u;
    for (const auto& t : mesh.triangles) {
      GpuTriangle g{};
      BvhPrimitive prim;
      float* corners[3] = {g.v0, g.v1, g.v2};
      float* normals[3] = {shading.normal0, shading.normal1, shading.normal2};
      for (int c = 0; c < 3; ++c) {
        for (int k = 0; k < 3; ++k) corners[c][k] = vertices[t[c]][k];
        prim.box.grow(vertices[t[c]]);
        if (shading.has_normals) store(normals[c], mesh.normals[t[c]]);
      }
      prim.kind = PrimitiveKind::Triangle;
      prim.index = static_cast<uint32_t>(out.triangles.size());
      prims.push_back(prim);
      out.triangles.push_back(g);
      out.triangle_shading.push_back(shading);
    }
  }
}

// Reorders `v` so that entry i becomes v[order[i]].
template <typename T>
std::vector<T> permuted(const std::vector<T>& v, const std::vector<uint32_t>& order) {
  std::vector<T> out;
  out.reserve(order.size());
  for (uint32_t i : order) out.push_back(v[i]);
  return out;
}

// Area of a triangle as the kernels see it (its float vertices), in double, world units^2.
double triangle_area(const GpuTriangle& t) {
  const Vec3 a{t.v0[0], t.v0[1], t.v0[2]}, b{t.v1[0], t.v1[1], t.v1[2]}, c{t.v2[0], t.v2[1], t.v2[2]};
  return 0.5 * length(cross(sub(b, a), sub(c, a)));
}

// Appends a light entry for every emitting triangle of positive area, in the scene's order of the
// triangles (meshes, then triangles within each: `order[i]` is the scene's index of the triangle
// buffer's entry i), so that the list and its picks do not depend on the hierarchy's leaf order
// (the builder, or the meshes kept apart for the triangle loop: the same seed gives the same
// image); then fills the pick distribution of the whole list: by power when there are triangle
// lights, else uniform (what kernels without triangle lights draw); uniform also when every power
// is 0. Each emitting triangle's light_area_density is set from its pick.
void add_triangle_lights(DeviceScene& out, const std::vector<uint32_t>& order, const std::vector<GpuLight>& punctual) {
  const size_t sphere_lights = out.lights.size();
  std::vector<uint32_t> buffer_index(order.size());
  for (size_t i = 0; i < order.size(); ++i) buffer_index[order[i]] = static_cast<uint32_t>(i);
  for (const uint32_t i : buffer_index) {
    if (!emits(out.triangle_shading[i].material)) continue;
    const double area = triangle_area(out.triangles[i]);
    if (!(area > 0)) continue;  // a degenerate triangle cannot be sampled (BSDF rays never hit it)
    GpuLight light{};
    light.triangle = static_cast<clpt_u32>(i);
    light.cap_area = static_cast<float>(area);
    out.lights.push_back(light);
  }
  out.lights.insert(out.lights.end(), punctual.begin(), punctual.end());
  std::vector<double> weights(out.lights.size(), 1.0);
  if (out.lights.size() > sphere_lights) {
    std::vector<double> power;
    double total = 0;
    for (const GpuLight& l : out.lights) {
      if (l.punctual != 0) {
        power.push_back(punctual_light_power(l, out.scene_radius));
      } else {
        const GpuMaterial& m = l.triangle == CLPT_LIGHT_SPHERE ? out.spheres[l.sphere].material
                                                               : out.triangle_shading[l.triangle].material;
        power.push_back(light_power(l, m.emission));
      }
      total += power.back();
    }
    if (total > 0) weights = power;
    // Defensive: with punctual lights, half of each pick is uniform. A directional light's power
    // is an upper bound (its irradiance over the whole scene's disc, light_pick.h), which a
    // radius-1000 ground sphere makes a million times the lit area's: by power alone the other
    // lights were picked once in 16000 and rendered as fireflies. No light falls below 1 / (2 n).
    if (total > 0 && !punctual.empty())
      for (double& w : weights) w = 0.5 * w / total + 0.5 / double(weights.size());
  }
  fill_light_pick(out.lights, weights);
  for (const GpuLight& l : out.lights)
    if (l.triangle != CLPT_LIGHT_SPHERE)
      out.triangle_shading[l.triangle].light_area_density = static_cast<float>(double(l.pick_probability) / double(l.cap_area));
}

// A punctual light's entry (types.h, GpuLight): camera-relative position, the spot's cone ramp as
// KHR_lights_punctual's reference code forms it.
GpuLight to_gpu(const PunctualLight& light, const Vec3& camera_position) {
  GpuLight g{};
  g.one_minus_cos_cap = -1;  // no sphere hit lies in it
  g.triangle = CLPT_LIGHT_SPHERE;
  g.punctual = light.type == LightType::Point ? CLPT_LIGHT_POINT
               : light.type == LightType::Spot ? CLPT_LIGHT_SPOT
                                               : CLPT_LIGHT_DIRECTIONAL;
  store(g.cap_axis, normalize(light.direction));
  store(g.position, sub(light.position, camera_position));
  store(g.intensity, light.intensity);
  g.range = static_cast<float>(light.range);
  g.spot_scale = 0;
  g.spot_offset = 1;
  if (light.type == LightType::Spot) {
    const double cos_inner = std::cos(light.inner_cone_rad), cos_outer = std::cos(light.outer_cone_rad);
    const double scale = 1.0 / std::max(0.001, cos_inner - cos_outer);
    g.spot_scale = static_cast<float>(scale);
    g.spot_offset = static_cast<float>(-cos_outer * scale);
  }
  return g;
}

// Radius of a sphere around every sphere and triangle of the scene, camera-relative (a directional
// light's power estimate: its irradiance over the scene's bounding disc).
double bounding_radius(const Scene& scene) {
  Vec3 lower{1e300, 1e300, 1e300}, upper{-1e300, -1e300, -1e300};
  const auto grow = [&](const Vec3& p, double r) {
    for (int i = 0; i < 3; ++i) lower[i] = std::min(lower[i], p[i] - r), upper[i] = std::max(upper[i], p[i] + r);
  };
  for (const Sphere& s : scene.spheres) grow(s.center, s.radius);
  for (const TriangleMesh& m : scene.meshes)
    for (const Vec3& p : m.positions) grow(p, 0);
  return lower[0] <= upper[0] ? 0.5 * length(sub(upper, lower)) : 1.0;
}

}  // namespace

bool emits(const GpuMaterial& m) {
  return m.kind == CLPT_MATERIAL_EMITTER ||
         (m.kind == CLPT_MATERIAL_PBR && (m.emission[0] > 0 || m.emission[1] > 0 || m.emission[2] > 0));
}

bool emits(const Material& m) {
  return m.type == MaterialType::Emitter ||
         (m.type == MaterialType::Pbr && (m.emission[0] > 0 || m.emission[1] > 0 || m.emission[2] > 0));
}

bool has_triangle_lights(const Scene& scene) {
  for (const TriangleMesh& m : scene.meshes)
    if (emits(m.material) && !m.triangles.empty()) return true;
  return false;
}

SurfaceFrame surface_frame(const Sphere& s, const Vec3& anchor) {
  const Vec3 towards_anchor = sub(anchor, s.center);
  // A sphere centred on the anchor has no closest point: any direction will do.
  const Vec3 n0 = length(towards_anchor) > 0 ? normalize(towards_anchor) : Vec3{0, 1, 0};
  return {add(s.center, scale(n0, s.radius)), n0};
}

LightSampling light_sampling_of(const RenderSettings& settings) {
  return settings.light_sampling == "sphere" ? LightSampling::Sphere : LightSampling::Cap;
}

std::vector<GpuLight> light_caps(const Scene& scene) {
  const LightSampling sampling = light_sampling_of(scene.settings);
  const double pi = 3.14159265358979323846;
  std::vector<GpuLight> lights;
  for (size_t i = 0; i < scene.spheres.size(); ++i) {
    const Sphere& a = scene.spheres[i];
    if (!emits(a.material)) continue;
    double one_minus_cos = 2;      // the whole sphere
    Vec3 axis = {0, 1, 0};
    bool hidden = false;
    for (size_t j = 0; j < scene.spheres.size() && sampling == LightSampling::Cap; ++j) {
      const Sphere& b = scene.spheres[j];
      if (j == i) continue;
      const Vec3 offset = sub(a.center, b.center);
      const double d = length(offset);
      if (d + a.radius <= b.radius) {  // a lies inside b: never seen
        hidden = true;
        break;
      }
      if (d >= a.radius + b.radius || d + b.radius <= a.radius) continue;  // b does not cut a
      // Points of a at angle theta from the axis (from b's centre through a's) are outside b when
      // 1 - cos(theta) < ((d + ra)^2 - rb^2) / (2 d ra), factored so that the walls' 1e5 radii
      // do not cancel: (d + ra - rb)(d + ra + rb) / (2 d ra).
      const double cut = (d + a.radius - b.radius) * (d + a.radius + b.radius) / (2 * d * a.radius);
      if (cut < one_minus_cos) {
        one_minus_cos = cut;
        axis = scale(offset, 1.0 / d);
      }
    }
    if (hidden || one_minus_cos <= 0) continue;
    GpuLight light{};
    store(light.cap_axis, axis);
    light.sphere = static_cast<clpt_u32>(i);
    light.one_minus_cos_cap = static_cast<float>(one_minus_cos);
    light.cap_area = static_cast<float>(2 * pi * a.radius * a.radius * one_minus_cos);
    light.triangle = CLPT_LIGHT_SPHERE;
    lights.push_back(light);
  }
  return lights;
}

double ray_epsilon_for(const Camera& camera, Precision precision) {
  // Float: 1e-5 of the view distance, measured on the book's scene (docs/numerics.md). Double rounds
  // 2^29 times finer, so its epsilon is that much smaller: otherwise a ball far away, with the
  // look-at point on it, would skip hits closer than 1e-5 of its distance, i.e. its own interior.
  const double scale = precision == Precision::Double ? 0x1p-29 : 1.0;
  return 1e-5 * scale * length(sub(camera.look_at, camera.position));
}

size_t hierarchy_device_bytes(const DeviceScene& scene) {
  size_t blocks = 0;
  for (const GpuBvhNode& node : scene.bvh.nodes)
    for (int i = 0; i < CLPT_BVH_WIDTH; ++i)
      if (node.count[i] != 0u && !(node.count[i] & CLPT_BVH_SPHERE_LEAF)) blocks += (node.count[i] + kTriangleBlockLanes - 1u) / kTriangleBlockLanes;
  return scene.bvh.nodes.size() * sizeof(GpuBvhNode) + blocks * sizeof(GpuTriangleBlock);
}

std::vector<uint8_t> hierarchy_device_data(const DeviceScene& scene) {
  // Written in place: for a million triangles the buffer is tens of megabytes, and every temporary
  // copy of it is as many fresh pages for the process to fault in.
  std::vector<uint8_t> bytes(hierarchy_device_bytes(scene));
  const size_t node_bytes = scene.bvh.nodes.size() * sizeof(GpuBvhNode);
  const size_t blocks = (bytes.size() - node_bytes) / sizeof(GpuTriangleBlock);
  size_t next = 0;  // the next block to write
  for (size_t n = 0; n < scene.bvh.nodes.size(); ++n) {
    GpuBvhNode node = scene.bvh.nodes[n];
    for (int i = 0; i < CLPT_BVH_WIDTH; ++i) {
      const uint32_t count = node.count[i];
      if (count == 0u || (count & CLPT_BVH_SPHERE_LEAF)) continue;
      const uint32_t first = node.child[i];
      node.child[i] = static_cast<uint32_t>(next);
      for (uint32_t b = 0; b < count; b += kTriangleBlockLanes, ++next) {
        if (next >= blocks) throw std::logic_error("hierarchy_device_data: more blocks than counted");
        GpuTriangleBlock block{};
        block.first = first + b;
        block.count = std::min(kTriangleBlockLanes, count - b);
        for (uint32_t lane = 0; lane < block.count; ++lane) {
          const GpuTriangle& t = scene.triangles.at(first + b + lane);
          const float* v[3] = {t.v0, t.v1, t.v2};
          for (int k = 0; k < 3; ++k)
            for (int axis = 0; axis < 3; ++axis) block.v[k][axis][lane] = v[k][axis];
        }
        std::memcpy(bytes.data() + node_bytes + next * sizeof(GpuTriangleBlock), &block, sizeof block);
      }
    }
    std::memcpy(bytes.data() + n * sizeof(GpuBvhNode), &node, sizeof node);
  }
  if (next != blocks) throw std::logic_error("hierarchy_device_data: fewer blocks than counted");
  return bytes;
}

// The box of all of `node`'s occupied slots.
void union_of_slots(const GpuBvhNode& node, float lower[3], float upper[3]) {
  lower[0] = lower[1] = lower[2] = INFINITY;
  upper[0] = upper[1] = upper[2] = -INFINITY;
  for (int i = 0; i < CLPT_BVH_WIDTH; ++i) {
    if (!(node.lower_x[i] <= node.upper_x[i])) continue;  // empty: inverted (types.h)
    lower[0] = std::min(lower[0], node.lower_x[i]), upper[0] = std::max(upper[0], node.upper_x[i]);
    lower[1] = std::min(lower[1], node.lower_y[i]), upper[1] = std::max(upper[1], node.upper_y[i]);
    lower[2] = std::min(lower[2], node.lower_z[i]), upper[2] = std::max(upper[2], node.upper_z[i]);
  }
}

// Adds `by` to every interior child index of `nodes` (a tree moved by `by` places).
void shift_interior(std::vector<GpuBvhNode>& nodes, uint32_t by) {
  for (GpuBvhNode& n : nodes)
    for (int i = 0; i < CLPT_BVH_WIDTH; ++i)
      if (n.count[i] == 0u && n.lower_x[i] <= n.upper_x[i]) n.child[i] += by;
}

// The hierarchy of a scene with meshes in the loop beside others (DeviceScene::loop_triangles):
// a new root (node 0) over two subtrees, slot 0 `rest` (the hierarchy of the other triangles,
// from node 1, where a kernel with the loop starts) and slot 1 `loop` (a hierarchy of the loop's
// triangles, after it, which the kernels without the loop traverse). The loop's triangles come
// first in the triangle order, in `loop`'s leaf order; `rest`'s leaves move up past them.
Bvh graft_loop_tree(Bvh rest, Bvh loop) {
  const uint32_t loop_count = static_cast<uint32_t>(loop.triangle_order.size());
  for (GpuBvhNode& n : rest.nodes)
    for (int i = 0; i < CLPT_BVH_WIDTH; ++i)
      if (n.count[i] != 0u && !(n.count[i] & CLPT_BVH_SPHERE_LEAF)) n.child[i] += loop_count;
  const uint32_t rest_nodes = static_cast<uint32_t>(rest.nodes.size());
  shift_interior(rest.nodes, 1);
  shift_interior(loop.nodes, 1 + rest_nodes);
  GpuBvhNode root{};
  for (int i = 0; i < CLPT_BVH_WIDTH; ++i) {
    root.lower_x[i] = root.lower_y[i] = root.lower_z[i] = INFINITY;
    root.upper_x[i] = root.upper_y[i] = root.upper_z[i] = -INFINITY;
  }
  float lower[3], upper[3];
  union_of_slots(rest.nodes.front(), lower, upper);
  root.lower_x[0] = lower[0], root.lower_y[0] = lower[1], root.lower_z[0] = lower[2];
  root.upper_x[0] = upper[0], root.upper_y[0] = upper[1], root.upper_z[0] = upper[2];
  root.child[0] = 1;
  union_of_slots(loop.nodes.front(), lower, upper);
  root.lower_x[1] = lower[0], root.lower_y[1] = lower[1], root.lower_z[1] = lower[2];
  root.upper_x[1] = upper[0], root.upper_y[1] = upper[1], root.upper_z[1] = upper[2];
  root.child[1] = 1 + rest_nodes;
  Bvh out = std::move(rest);
  out.nodes.insert(out.nodes.begin(), root);
  out.nodes.insert(out.nodes.end(), loop.nodes.begin(), loop.nodes.end());
  std::vector<uint32_t> order = loop.triangle_order;
  order.insert(order.end(), out.triangle_order.begin(), out.triangle_order.end());
  out.triangle_order = std::move(order);
  // One level above both; the root's other child pushed while one is visited.
  out.depth = std::max(out.depth, loop.depth) + 1;
  out.stack_need = std::max(out.stack_need, loop.stack_need) + 1;
  out.build_seconds += loop.build_seconds;
  out.build_cpu_seconds += loop.build_cpu_seconds;
  if (out.stack_need > CLPT_BVH_STACK)
    throw Error(ExitCode::BadScene, "the bounding volume hierarchy could need " + std::to_string(out.stack_need) +
                                        " entries of the kernels' traversal stack, which holds " +
                                        std::to_string(CLPT_BVH_STACK));
  return out;
}

DeviceScene make_device_scene(const Scene& scene, int width, int height, Precision precision, BvhBuilder builder,
                              bool loop_meshes_apart) {
  DeviceScene out;
  const Camera& cam = scene.camera;
  for (const Sphere& s : scene.spheres) out.spheres.push_back(to_gpu(s, cam.look_at, cam.position));
  out.lights = light_caps(scene);

  std::vector<BvhPrimitive> prims;
  add_triangles(scene, out, prims);
  // The loop's meshes, when the hierarchy has other triangles: theirs leave the build and go
  // first (loop_triangles).
  std::vector<BvhPrimitive> loop_prims;
  const TriangleLoopChoice loop = loop_meshes_apart ? triangle_loop_choice(scene) : TriangleLoopChoice{};
  if (loop.hierarchy_triangles) {
    const std::vector<bool>& in_loop = loop.meshes;
    std::vector<BvhPrimitive> rest;
    size_t next = 0;
    for (size_t m = 0; m < scene.meshes.size(); ++m)
      for (size_t t = 0; t < scene.meshes[m].triangles.size(); ++t, ++next)
        (in_loop[m] ? loop_prims : rest).push_back(prims[next]);
    if (!loop_prims.empty()) prims = std::move(rest);
  }
  const bool spheres_in_bvh = spheres_in_hierarchy(scene);
  const std::vector<bool> in_loop = loop_spheres(scene);
  // The sphere buffer: the loop's spheres first (scene order), then the hierarchy's (leaf order).
  std::vector<uint32_t> sphere_order;
  for (size_t i = 0; i < in_loop.size(); ++i)
    if (in_loop[i]) sphere_order.push_back(static_cast<uint32_t>(i));
  out.loop_spheres = static_cast<uint32_t>(sphere_order.size());
  if (spheres_in_bvh) {
    for (size_t i = 0; i < scene.spheres.size(); ++i) {
      if (in_loop[i]) continue;
      BvhPrimitive prim;
      prim.box = sphere_box(sub(scene.spheres[i].center, cam.position), scene.spheres[i].radius);
      prim.kind = PrimitiveKind::Sphere;
      prim.index = static_cast<uint32_t>(i);
      prims.push_back(prim);
    }
  }
  // A hierarchy of triangles alone: its leaves are read as blocks of four (GpuTriangleBlock), so
  // the SAH charges a leaf by its blocks and fills them (docs/performance.md, "Traversal").
  BvhBuildOptions build;
  if (!spheres_in_bvh) build.leaf_group = int(kTriangleBlockLanes);
  out.bvh = build_bvh_with(builder, prims, build);
  if (!loop_prims.empty()) {
    out.bvh = graft_loop_tree(std::move(out.bvh), build_bvh_with(builder, loop_prims, build));
    out.loop_triangles = static_cast<uint32_t>(loop_prims.size());
  }
  out.triangles = permuted(out.triangles, out.bvh.triangle_order);
  out.triangle_shading = permuted(out.triangle_shading, out.bvh.triangle_order);
  if (spheres_in_bvh) {
    sphere_order.insert(sphere_order.end(), out.bvh.sphere_order.begin(), out.bvh.sphere_order.end());
    for (GpuBvhNode& node : out.bvh.nodes)
      for (int i = 0; i < CLPT_BVH_WIDTH; ++i)
        if (node.count[i] & CLPT_BVH_SPHERE_LEAF) node.child[i] += out.loop_spheres;
    out.spheres = permuted(out.spheres, sphere_order);
    std::vector<uint32_t> new_index(scene.spheres.size());
    for (size_t i = 0; i < sphere_order.size(); ++i) new_index[sphere_order[i]] = uint32_t(i);
    for (GpuLight& light : out.lights) light.sphere = new_index[light.sphere];
  }
  out.texturing = pack_texturing(scene, out.bvh.triangle_order, sphere_order);
  out.scene_radius = bounding_radius(scene);
  std::vector<GpuLight> punctual;
  for (const PunctualLight& l : scene.lights) punctual.push_back(to_gpu(l, cam.position));
  add_triangle_lights(out, out.bvh.triangle_order, punctual);
  out.environment = environment_device_data(scene.environment, !out.lights.empty());

  // The book's sensor, scaled to unit distance: only directions matter for a pinhole. An
  // orthographic camera's sensor is ortho_height world units high, its rays parallel.
  const Vec3 dir = normalize(sub(cam.look_at, cam.position));
  const double pi = 3.14159265358979323846;
  const bool ortho = cam.projection == Projection::Orthographic;
  const double sensor_height = ortho ? cam.ortho_height : 2.0 * std::tan(cam.vertical_fov_deg * pi / 360.0);
  const double sensor_width = sensor_height * width / height;
  out.camera.projection = ortho ? CLPT_PROJECTION_ORTHOGRAPHIC : CLPT_PROJECTION_PERSPECTIVE;
  const Vec3 right = scale(normalize(cross(dir, cam.up)), sensor_width);
  const Vec3 up = scale(normalize(cross(right, dir)), sensor_height);
  store(out.camera.sensor_center, dir);
  store(out.camera.sensor_right, right);
  store(out.camera.sensor_up, up);
  out.ray_epsilon = static_cast<float>(ray_epsilon_for(cam, precision));
  return out;
}

}  // namespace clpt
