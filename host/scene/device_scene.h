// Conversion of a loaded Scene (double, world space) into what the kernels read (float,
// camera-relative), done once on the host in double precision.
#pragma once

#include <vector>

#include "kernels/types.h"
#include "scene/bvh_build.h"
#include "scene/bvh_builders.h"
#include "scene/loop_spheres.h"
#include "scene/precision_preset.h"
#include "scene/scene.h"

namespace clpt {

struct DeviceScene {
  // Every sphere: first the loop's (loop_spheres.h) in the scene's order, then
  // the hierarchy's primitives in its leaf order.
  std::vector<GpuSphere> spheres;
  uint32_t loop_spheres = 0;  // spheres the kernels test in their loop (the first ones)
  // What next-event estimation samples (types.h, GpuLight): the emitter spheres' caps
  // (light_caps()), then every emitting triangle of positive area, then the punctual lights; with
  // the pick distribution.
  std::vector<GpuLight> lights;
  // Every mesh's triangles, in the hierarchy's leaf order, and what shading reads of each; the
  // loop's meshes' first when they are some of the meshes (loop_triangles).
  std::vector<GpuTriangle> triangles;
  std::vector<GpuTriangleShading> triangle_shading;
  // The textures, every triangle's texture coordinates and tangents (device_textures.h); empty
  // without textures.
  std::vector<uint8_t> texturing;
  Bvh bvh;  // over the triangles, and the spheres when they are in it; no nodes when neither
  // The triangles of the loop's meshes (loop_meshes) when other meshes are in the hierarchy
  // only: they come first, and the root (node 0) holds two subtrees, node 1 the hierarchy of the
  // others, where a kernel that tests these in its loop starts (CLPT_BVH_ROOT=1), and after it a
  // hierarchy of these, which the other kernels traverse. 0 otherwise: node 0 is the root of a
  // hierarchy of every triangle, and a kernel with the triangle loop has no traversal.
  uint32_t loop_triangles = 0;
  // The environment light's header and data (types.h GpuEnvironment, scene/environment_map.h);
  // an empty one (kind NONE) when the scene has none.
  std::vector<float> environment;
  GpuCamera camera{};
  float ray_epsilon = 0;  // world units; see ray_epsilon_for()
  // Radius of a sphere around all the scene's geometry, world units (light_pick.h: a directional
  // light's power estimate).
  double scene_radius = 1;
};

// Triangles a leaf block holds side by side (GpuTriangleBlock's lanes, kernels/types.h).
constexpr uint32_t kTriangleBlockLanes = 4;

// The hierarchy's buffer as the kernels read it (kernels/types.h, GpuTriangleBlock): scene.bvh.nodes,
// each triangle leaf's child made the index of its first block, followed by the blocks, which hold
// every triangle leaf's triangles four by four in leaf order. The host's tree (scene.bvh, which the
// replica and the tests read) keeps the first triangle there. Empty when the scene has no nodes.
std::vector<uint8_t> hierarchy_device_data(const DeviceScene& scene);
// Its size in bytes, without building it.
size_t hierarchy_device_bytes(const DeviceScene& scene);

// The point s0 of sphere s nearest `anchor` (the camera's look-at point) and the outward unit
// normal n0 there, in world units: how every sphere is stored (kernels/types.h, GpuSphere).
struct SurfaceFrame {
  Vec3 point;
  Vec3 normal;
};
SurfaceFrame surface_frame(const Sphere& s, const Vec3& anchor);

// Each sphere becomes (s0, n0, r): s0 the surface point closest to the camera's look-at point,
// n0 the outward normal there, both relative to the camera position. Then every float the
// kernels see is of the size of distances inside the scene, never of a huge radius or a large
// world coordinate.
// `precision` sets the ray epsilon (ray_epsilon_for); `builder` makes the hierarchy (only
// `clpt bench --bvh-builders` passes another than clpt's own). `loop_meshes_apart`: the meshes of
// large triangles (loop_meshes), where other meshes are in the hierarchy only, in a subtree of
// their own beside the others' (loop_triangles), as a kernel that tests them in its triangle loop
// needs (RenderPlan::loop_meshes_apart; every kernel can traverse it); false: one hierarchy over
// every triangle.
DeviceScene make_device_scene(const Scene& scene, int width, int height, Precision precision = Precision::Robust,
                              BvhBuilder builder = BvhBuilder::Clpt, bool loop_meshes_apart = true);

// How next-event estimation samples an emitter (RenderSettings::light_sampling).
//   Cap:    uniformly by area over the part of it that no other sphere hides, found as the
//           smallest cap left outside any one other sphere (the default)
//   Sphere: uniformly by area over the whole sphere (for comparison: README "Estimators")
enum class LightSampling { Cap, Sphere };
LightSampling light_sampling_of(const RenderSettings& settings);  // from settings.light_sampling

// The light entries for `scene`'s emitters, in double: an emitter entirely inside another sphere
// can never be seen and gets none. The cap is where the light is sampled; points of the emitter
// outside it are still lit by BSDF sampling, which the kernels weight accordingly, so any cap is
// unbiased and a smaller one only wastes fewer shadow rays.
// Sampled as the scene's settings.light_sampling says.
std::vector<GpuLight> light_caps(const Scene& scene);

// Whether a material emits light: an emitter, or a Pbr material with an emission above 0 (which
// both emits and scatters). Emitting spheres get caps (light_caps), emitting triangles entries.
bool emits(const Material& m);
bool emits(const GpuMaterial& m);

// Whether the scene has emitting triangles (a mesh whose material emits): then next-event
// estimation samples them too, and its kernels compile triangle lights (kernel_options.cpp).
bool has_triangle_lights(const Scene& scene);

// Minimum hit distance: 1e-5 of the camera-to-look-at distance (1.0e-4 for the book's scenes,
// the value docs/numerics.md measured as robust there), so it scales with the scene; 2^-29 of that for
// the double preset.
double ray_epsilon_for(const Camera& camera, Precision precision = Precision::Robust);

}  // namespace clpt
