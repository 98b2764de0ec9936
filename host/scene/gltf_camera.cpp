// glTF cameras -> Camera and the image size (gltf_camera.h).
#include "scene/gltf_camera.h"

#include <algorithm>
#include <cmath>

#include "scene/gltf_error.h"
#include "scene/vec3_ops.h"
#include "util/error.h"

namespace clpt {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kDefaultWidth = 640, kDefaultHeight = 480;

void check_camera(const tinygltf::Camera& c, const std::string& element) {
  const auto positive = [&](double v, const std::string& key) {
    if (!(std::isfinite(v) && v > 0)) gltf_fail(element + key, "must be > 0 (got " + std::to_string(v) + ")");
  };
  if (c.type == "perspective") {
    const auto& p = c.perspective;
    if (!(std::isfinite(p.yfov) && p.yfov > 0 && p.yfov < kPi))
      gltf_fail(element + ".perspective.yfov", "must be in (0, pi) radians (got " + std::to_string(p.yfov) + ")");
    positive(p.znear, ".perspective.znear");
    if (p.zfar != 0 && !(std::isfinite(p.zfar) && p.zfar > p.znear))
      gltf_fail(element + ".perspective.zfar", "must be greater than znear (got " + std::to_string(p.zfar) + ")");
    if (p.aspectRatio != 0) positive(p.aspectRatio, ".perspective.aspectRatio");
  } else if (c.type == "orthographic") {
    const auto& o = c.orthographic;
    for (const auto& [value, key] : {std::pair{o.xmag, ".orthographic.xmag"}, std::pair{o.ymag, ".orthographic.ymag"}})
      if (!(std::isfinite(value) && value != 0)) gltf_fail(element + key, "must be finite and not zero");
    if (!(std::isfinite(o.znear) && o.znear >= 0)) gltf_fail(element + ".orthographic.znear", "must be >= 0");
    if (!(std::isfinite(o.zfar) && o.zfar > o.znear)) gltf_fail(element + ".orthographic.zfar", "must be greater than znear");
  } else {
    gltf_fail(element + ".type", "'" + c.type + "' (expected perspective or orthographic)");
  }
}

// The camera's width / height, or 0 when the file does not say.
double aspect_of(const tinygltf::Camera& c) {
  if (c.type == "orthographic") return std::fabs(c.orthographic.xmag / c.orthographic.ymag);
  return c.perspective.aspectRatio;
}

int clamp_size(double pixels) { return int(std::clamp(std::round(pixels), 1.0, 16384.0)); }

// The image size rule (docs/gltf.md): both given, as given; one given, the other from the
// camera's aspect ratio when it has one; none, 640 wide and the height from the aspect (else 480).
void set_size(const GltfView& view, double aspect, RenderSettings& settings) {
  settings.width = view.width.value_or(kDefaultWidth);
  settings.height = view.height.value_or(kDefaultHeight);
  if (aspect <= 0 || (view.width && view.height)) return;
  if (view.height) settings.width = clamp_size(*view.height * aspect);
  else settings.height = clamp_size(settings.width / aspect);
}

struct Placed {
  int camera;
  const NodeInstance* instance;
};

std::string describe_cameras(const tinygltf::Model& model, const std::vector<Placed>& placed) {
  std::string out;
  for (size_t i = 0; i < model.cameras.size(); ++i) {
    out += (i ? ", " : "") + std::to_string(i);
    if (!model.cameras[i].name.empty()) out += " '" + model.cameras[i].name + "'";
    for (const Placed& p : placed)
      if (p.camera == int(i)) {
        out += " (nodes[" + std::to_string(p.instance->node) + "])";
        break;
      }
  }
  return out;
}

// The placement --camera names: an index into `cameras`, else a camera's name, else the name of
// a node that carries a camera.
const Placed& named_camera(const tinygltf::Model& model, const std::vector<Placed>& placed, const std::string& name) {
  const bool is_index = !name.empty() && name.size() < 10 && std::all_of(name.begin(), name.end(), ::isdigit);
  for (const Placed& p : placed)
    if (is_index ? p.camera == std::stoi(name) : model.cameras[size_t(p.camera)].name == name) return p;
  for (const Placed& p : placed)
    if (!is_index && model.nodes[size_t(p.instance->node)].name == name) return p;
  if (model.cameras.empty()) throw Error(ExitCode::Usage, "--camera " + name + ": the file has no cameras");
  throw Error(ExitCode::Usage, "--camera " + name + ": no camera of the scene has that index or name (the file's cameras: " +
                                   describe_cameras(model, placed) + ")");
}

Camera camera_from(const tinygltf::Camera& c, const Affine& world) {
  Camera out;
  out.position = world.translation;
  const Vec3 forward = normalize(transform_vector(world, {0, 0, -1}));
  const Vec3 up = transform_vector(world, {0, 1, 0});
  out.look_at = add(out.position, forward);
  out.up = normalize(sub(up, scale(forward, dot(up, forward))));  // orthonormalised: scale and shear drop out
  if (c.type == "orthographic") {
    out.projection = Projection::Orthographic;
    out.ortho_height = 2 * std::fabs(c.orthographic.ymag);
  } else {
    out.vertical_fov_deg = c.perspective.yfov * 180 / kPi;
  }
  return out;
}

// No camera: the default field of view, looking along -Z at the centre of the bounds of every
// vertex (and light position), from far enough that their bounding sphere fits the image.
Camera framing_camera(const Scene& scene) {
  Vec3 lower{HUGE_VAL, HUGE_VAL, HUGE_VAL}, upper{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  const auto grow = [&](const Vec3& p) {
    for (int i = 0; i < 3; ++i) lower[i] = std::min(lower[i], p[i]), upper[i] = std::max(upper[i], p[i]);
  };
  for (const TriangleMesh& m : scene.meshes)
    for (const Vec3& p : m.positions) grow(p);
  if (scene.meshes.empty())
    for (const PunctualLight& l : scene.lights) grow(l.position);
  if (lower[0] > upper[0]) lower = upper = {0, 0, 0};
  const Vec3 centre = scale(add(lower, upper), 0.5);
  double radius = 0.5 * length(sub(upper, lower));
  if (!(radius > 0)) radius = 1;
  Camera out;
  const double vertical = out.vertical_fov_deg * kPi / 180;
  const double aspect = double(scene.settings.width) / scene.settings.height;
  const double horizontal = 2 * std::atan(std::tan(vertical / 2) * aspect);
  out.look_at = centre;
  out.position = add(centre, {0, 0, radius / std::sin(std::min(vertical, horizontal) / 2)});
  return out;
}

}  // namespace

void set_view(const tinygltf::Model& model, const std::vector<NodeInstance>& nodes, const GltfView& view, Scene& scene,
              std::vector<std::string>& warnings) {
  for (size_t i = 0; i < model.cameras.size(); ++i) check_camera(model.cameras[i], "cameras[" + std::to_string(i) + "]");
  std::vector<Placed> placed;
  for (const NodeInstance& instance : nodes) {
    const int camera = model.nodes[size_t(instance.node)].camera;
    if (camera < 0) continue;
    if (size_t(camera) >= model.cameras.size())
      gltf_fail("nodes[" + std::to_string(instance.node) + "].camera",
                std::to_string(camera) + " is out of range (the file has " + std::to_string(model.cameras.size()) + " cameras)");
    placed.push_back({camera, &instance});
  }
  if (placed.empty() && !view.camera) {
    set_size(view, 0, scene.settings);
    scene.camera = framing_camera(scene);
    warnings.push_back("cameras: the scene has no camera; a view from +Z framing its bounds is rendered (docs/gltf.md)");
    return;
  }
  const Placed& chosen = view.camera ? named_camera(model, placed, *view.camera) : placed.front();
  const tinygltf::Camera& c = model.cameras[size_t(chosen.camera)];
  set_size(view, aspect_of(c), scene.settings);
  scene.camera = camera_from(c, chosen.instance->world);
}

}  // namespace clpt
