#include "tools/kernel_variants.h"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <set>
#include <tuple>

#include "render/render_plan.h"
#include "util/error.h"

namespace clpt {
namespace {

// Dimension positions in KernelVariant::choice.
enum Dim {
  kForm, kPrecision, kEstimator, kRussianRoulette, kSpecialisation, kSceneLoops, kPhong, kGlass, kGeometry,
  kPbr, kLights, kCamera, kEnvironment, kAovs, kTextures, kDimCount
};

// Whether a combination can be rendered: the book estimator cannot see punctual lights (the plan
// refuses them, kernel_options.h), so it goes only with "no-punctual".
// The textured tile goes with meshes: it is a mesh beside the octahedron (textured spheres go
// with either geometry).
bool renderable(const std::vector<int>& choice) {
  return !(choice[kEstimator] == 0 && choice[kLights] != 0) &&
         !((choice[kTextures] == 1 || choice[kTextures] == 2) && choice[kGeometry] == 0);
}

// (dimension a, value of a, dimension b, value of b) with a < b.
using Pair = std::tuple<int, int, int, int>;

// Every pair of values of two dimensions that a renderable combination contains.
std::set<Pair> all_pairs() {
  const auto& dims = kernel_variant_dimensions();
  std::set<Pair> pairs;
  for (int a = 0; a < int(dims.size()); ++a)
    for (int b = a + 1; b < int(dims.size()); ++b)
      for (int va = 0; va < int(dims[a].values.size()); ++va)
        for (int vb = 0; vb < int(dims[b].values.size()); ++vb) {
          const bool book_and_punctual = (a == kEstimator && va == 0 && b == kLights && vb != 0);
          const bool spheres_and_textures = (a == kGeometry && va == 0 && b == kTextures && (vb == 1 || vb == 2));
          if (!book_and_punctual && !spheres_and_textures) pairs.insert({a, va, b, vb});
        }
  return pairs;
}

std::vector<Pair> pairs_of(const std::vector<int>& choice) {
  std::vector<Pair> pairs;
  for (int a = 0; a < int(choice.size()); ++a)
    for (int b = a + 1; b < int(choice.size()); ++b) pairs.push_back({a, choice[a], b, choice[b]});
  return pairs;
}

Material phong_ball() {  // the specular scene's left ball
  Material m;
  m.type = MaterialType::Phong;
  m.reflectance = {0.999, 0.999, 0.999};
  m.phong_exponent = 100;
  return m;
}

Material glass_ball() {  // the glass scene's right ball
  Material m;
  m.type = MaterialType::Glass;
  m.reflectance = {0.999999, 0.999999, 0.999999};
  m.ior = 1.5;
  return m;
}

// A mirror octahedron just above the diffuse room's floor between the balls: triangles, so
// the kernel traverses a hierarchy with triangle leaves, and a mirror.
TriangleMesh mirror_octahedron() {
  TriangleMesh m;
  m.name = "variant_octahedron";
  m.material.type = MaterialType::Mirror;
  m.material.reflectance = {0.9, 0.9, 0.9};
  const Vec3 centre = {0, 0.8, 1.5};  // between the balls at x = -2 and 2, in front of them
  const double r = 0.7;
  for (int axis = 0; axis < 3; ++axis)
    for (double side : {-1.0, 1.0}) {
      Vec3 p = centre;
      p[size_t(axis)] += side * r;
      m.positions.push_back(p);
    }
  // Vertices 0/1: -x/+x, 2/3: -y/+y, 4/5: -z/+z; one face per octant, counter-clockwise outside.
  for (uint32_t x : {0u, 1u})
    for (uint32_t y : {2u, 3u})
      for (uint32_t z : {4u, 5u}) {
        const bool flip = ((x == 1) + (y == 3) + (z == 5)) % 2 == 0;
        m.triangles.push_back(flip ? std::array<uint32_t, 3>{x, z, y} : std::array<uint32_t, 3>{x, y, z});
      }
  return m;
}

// Small Lambertian pebbles along the room's floor: with them the scene has more than
// kMaxLoopSpheres spheres, so the small ones (and the book's balls) become hierarchy primitives
// beside the triangles while the walls and the light stay in the loop (loop_spheres).
std::vector<Sphere> pebbles() {
  std::vector<Sphere> out;
  for (int i = 0; i < 12; ++i) {
    Sphere s;
    s.name = "variant_pebble" + std::to_string(i);
    s.center = {-2.0 + 0.35 * i, 0.15, 2.6 + 0.3 * (i % 3)};  // a row on the floor, in view
    s.radius = 0.15;
    s.material.type = MaterialType::Lambertian;
    s.material.reflectance = {0.2 + 0.05 * (i % 4), 0.5, 0.75 - 0.05 * (i % 5)};
    out.push_back(s);
  }
  return out;
}

// A ball of the glTF material between the book's two, in front of them: rough half-metal, or a
// thin-walled transmitting one that also emits (so it is a sphere light as well), or a volume
// (thickness > 0) that refracts and absorbs.
Sphere pbr_ball(bool transmission, bool volume) {
  Sphere s;
  s.name = "variant_pbr_ball";
  s.center = {0, 0.6, 1.0};
  s.radius = 0.6;
  s.material.type = MaterialType::Pbr;
  s.material.reflectance = {0.9, 0.6, 0.3};
  s.material.metallic = transmission ? 0.0 : 0.5;
  s.material.roughness = transmission ? 0.2 : 0.4;
  s.material.transmission = transmission ? 0.7 : 0.0;
  if (transmission && !volume) s.material.emission = {0.2, 0.1, 0.05};
  if (volume) {
    s.material.thickness = 1.2;
    s.material.attenuation_color = {0.9, 0.5, 0.3};
    s.material.attenuation_distance = 1.0;
  }
  return s;
}

// The environment seen through the room's open front: a 16 x 8 sky, brighter towards the zenith,
// with a sun of one texel at 1000 times the sky (image), or a constant pale blue (constant).
Environment variant_environment(bool image) {
  Environment e;
  e.what = "variant environment";
  e.color = {0.3, 0.4, 0.6};
  e.rotation_deg = 30;
  if (!image) return e;
  e.file = "variant_sky";
  e.width = 16;
  e.height = 8;
  auto rgb = std::make_shared<std::vector<float>>(16 * 8 * 3);
  for (int row = 0; row < 8; ++row)
    for (int column = 0; column < 16; ++column) {
      const float sky = 1.0f - 0.1f * float(row);
      float* p = &(*rgb)[3 * (row * 16 + column)];
      p[0] = 0.4f * sky, p[1] = 0.6f * sky, p[2] = sky;
    }
  for (int c = 0; c < 3; ++c) (*rgb)[3 * (2 * 16 + 11) + c] = 1000.0f;
  e.rgb = std::move(rgb);
  e.hash = "variant";
  return e;
}

// One punctual light of the kind `value` names (1 point, 2 spot, 3 directional), inside the room.
PunctualLight punctual_light(int value) {
  PunctualLight l;
  l.type = value == 1 ? LightType::Point : value == 2 ? LightType::Spot : LightType::Directional;
  l.name = std::string("variant_") + light_type_name(l.type);
  l.position = {0.5, 3.0, 2.0};
  l.direction = value == 3 ? Vec3{0.3, -1, -0.5} : Vec3{0, -1, 0};
  l.intensity = value == 3 ? Vec3{0.5, 0.5, 0.5} : Vec3{3, 3, 3};
  l.range = value == 1 ? 6.0 : 0.0;
  l.inner_cone_rad = 0.3;
  l.outer_cone_rad = 0.7;
  return l;
}

// A texture image of w x h texels, `channels` channels, made up of a smooth pattern in [0, 1].
TextureImage pattern_image(const std::string& name, int w, int h, int channels, TexelStorage storage, ColorSpace space) {
  TextureImage image;
  image.file = name;
  image.hash = name;
  image.width = w;
  image.height = h;
  image.channels = channels;
  image.storage = storage;
  image.color_space = space;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c)
        image.pixels.push_back(float(0.25 + 0.5 * ((x * 3 + y * 5 + c * 7) % 11) / 10.0));
  return image;
}

// A textured tile on the floor in front of the balls (docs/textures.md): an 8-bit RGBA sRGB base
// colour (repeat, bilinear) and a half normal map (clamp in u) on every textured variant; with
// `pbr` (the variant's pbr dimension) the tile is a Pbr material and adds a half two-channel
// metallic-roughness map and a float one-channel emission map (mirror, nearest): every storage,
// four channel counts, every wrap mode, both filters, normal maps and emission textures. The tile's
// alpha (the base colour's alpha channel, kernels/alpha.cl) is in effect: MASK, or BLEND with `pbr`,
// so every textured variant compiles CLPT_HAS_ALPHA and cuts the tile in its ray queries. With
// `vertex_colors` the tile's corners carry colours (glTF COLOR_0, kernels/vertex_colors.cl), one
// with alpha below 1.
void add_textured_tile(Scene& scene, bool pbr, bool vertex_colors) {
  TriangleMesh m;
  m.name = "variant_tile";
  m.positions = {{-1.2, 0.02, 2.2}, {1.2, 0.02, 2.2}, {1.2, 0.02, 3.4}, {-1.2, 0.02, 3.4}};
  m.uvs = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  m.triangles = {{0, 2, 1}, {0, 3, 2}};
  if (vertex_colors) m.colors = {{1, 0.5, 0.25, 1}, {0.25, 1, 0.5, 1}, {0.5, 0.25, 1, 0.6}, {1, 1, 1, 1}};
  const int first = int(scene.images.size());
  scene.images.push_back(pattern_image("variant_rgba8", 8, 4, 4, TexelStorage::U8, ColorSpace::Srgb));
  scene.images.push_back(pattern_image("variant_normal_half", 4, 4, 3, TexelStorage::Half, ColorSpace::Linear));
  MaterialTextures& t = m.material.textures;
  t.base_color.image = first;
  t.normal.image = first + 1;
  t.normal.wrap_u = TextureWrap::Clamp;
  t.normal_scale = 0.5;
  t.alpha_mode = pbr ? AlphaMode::Blend : AlphaMode::Mask;
  t.alpha = 0.9;
  m.material.type = MaterialType::Lambertian;
  m.material.reflectance = {0.8, 0.8, 0.8};
  if (pbr) {
    scene.images.push_back(pattern_image("variant_mr_half", 4, 4, 2, TexelStorage::Half, ColorSpace::Linear));
    scene.images.push_back(pattern_image("variant_emission_float", 4, 2, 1, TexelStorage::Float, ColorSpace::Linear));
    m.material.type = MaterialType::Pbr;
    m.material.metallic = 0.5;
    m.material.roughness = 0.6;
    m.material.emission = {0.1, 0.1, 0.1};
    t.metallic.image = t.roughness.image = first + 2;
    t.metallic.wrap_u = t.roughness.wrap_u = TextureWrap::Clamp;
    t.metallic.channel = 1;
    t.emission.image = first + 3;
    t.emission.wrap_u = t.emission.wrap_v = TextureWrap::Mirror;
    t.emission.filter = TextureFilter::Nearest;
  }
  scene.meshes.push_back(m);
}

// Textured spheres (docs/textures.md, the spherical mapping): the left ball's colour from an 8-bit
// sRGB RGB image (repeat, bilinear) and the light's emission from a float one-channel one (clamp,
// nearest: next-event estimation reads it at the sampled cap points); with `pbr` the glTF ball's
// metallic and roughness from a half two-channel image (mirror).
void add_textured_spheres(Scene& scene, bool pbr) {
  const int first = int(scene.images.size());
  scene.images.push_back(pattern_image("variant_sphere_rgb8", 8, 4, 3, TexelStorage::U8, ColorSpace::Srgb));
  scene.images.push_back(pattern_image("variant_sphere_emission_float", 4, 2, 1, TexelStorage::Float, ColorSpace::Linear));
  if (pbr) scene.images.push_back(pattern_image("variant_sphere_mr_half", 4, 4, 2, TexelStorage::Half, ColorSpace::Linear));
  for (Sphere& s : scene.spheres) {
    MaterialTextures& t = s.material.textures;
    if (s.name == "left_ball") t.base_color.image = first;
    if (s.name == "light") {
      t.emission.image = first + 1;
      t.emission.wrap_u = t.emission.wrap_v = TextureWrap::Clamp;
      t.emission.filter = TextureFilter::Nearest;
    }
    if (s.name == "variant_pbr_ball" && pbr) {
      t.metallic.image = t.roughness.image = first + 2;
      t.metallic.wrap_u = t.roughness.wrap_v = TextureWrap::Mirror;
      t.roughness.channel = 1;
    }
  }
}

}  // namespace

const std::vector<VariantDimension>& kernel_variant_dimensions() {
  static const std::vector<VariantDimension> dims = {
      {"form", {"megakernel-path", "megakernel-lockstep", "wavefront"}},
      {"precision", {"robust", "fast", "double"}},
      {"estimator", {"book", "nee"}},
      {"russian-roulette", {"no-rr", "rr"}},
      {"specialisation", {"specialised", "generic"}},
      {"scene-loops", {"unrolled", "rolled"}},
      {"phong", {"no-phong", "phong"}},
      {"glass", {"no-glass", "glass"}},
      {"geometry", {"spheres", "mesh"}},
      {"pbr", {"no-pbr", "pbr", "pbr-transmission", "pbr-volume"}},
      {"lights", {"no-punctual", "point", "spot", "directional"}},
      {"camera", {"perspective", "orthographic"}},
      {"environment", {"no-environment", "environment-image", "environment-constant"}},
      {"aovs", {"no-aovs", "aovs"}},
      {"textures", {"no-textures", "textures", "textures-vertex-colors", "sphere-textures"}},
  };
  static_assert(kDimCount == 15, "one entry per Dim");
  return dims;
}

ExecutionForm KernelVariant::form() const {
  return choice[kForm] == 2 ? ExecutionForm::Wavefront : ExecutionForm::Megakernel;
}
MegakernelLoop KernelVariant::megakernel_loop() const {
  return choice[kForm] == 1 ? MegakernelLoop::Lockstep : MegakernelLoop::PerPath;
}
Precision KernelVariant::precision() const {
  return choice[kPrecision] == 1 ? Precision::Fast : choice[kPrecision] == 2 ? Precision::Double : Precision::Robust;
}
Estimator KernelVariant::estimator() const { return choice[kEstimator] == 1 ? Estimator::Nee : Estimator::Book; }
bool KernelVariant::russian_roulette() const { return choice[kRussianRoulette] == 1; }
bool KernelVariant::generic() const { return choice[kSpecialisation] == 1; }
SceneLoops KernelVariant::scene_loops() const {
  return choice[kSceneLoops] == 1 ? SceneLoops::Rolled : SceneLoops::Unrolled;
}
bool KernelVariant::has_phong() const { return choice[kPhong] == 1; }
bool KernelVariant::has_glass() const { return choice[kGlass] == 1; }
bool KernelVariant::has_mesh() const { return choice[kGeometry] == 1; }
bool KernelVariant::has_pbr() const { return choice[kPbr] != 0; }
bool KernelVariant::has_pbr_transmission() const { return choice[kPbr] >= 2; }
bool KernelVariant::has_pbr_volume() const { return choice[kPbr] == 3; }
int KernelVariant::punctual_light() const { return choice[kLights]; }
bool KernelVariant::orthographic() const { return choice[kCamera] == 1; }
int KernelVariant::environment() const { return choice[kEnvironment]; }
bool KernelVariant::aovs() const { return choice[kAovs] == 1; }
int KernelVariant::textures() const { return choice[kTextures]; }

std::string KernelVariant::name() const {
  const auto& dims = kernel_variant_dimensions();
  std::string n;
  for (size_t d = 0; d < dims.size(); ++d) n += (d ? "." : "") + dims[d].values[size_t(choice[d])];
  return n;
}

std::vector<KernelVariant> covering_kernel_variants() {
  const auto& dims = kernel_variant_dimensions();
  const size_t n = dims.size();
  // The uncovered pairs as a dense table over value indices (offset[d] + value); pairs that no
  // renderable combination holds are never in it.
  std::vector<size_t> offset(n + 1, 0);
  for (size_t d = 0; d < n; ++d) offset[d + 1] = offset[d] + dims[d].values.size();
  const size_t values = offset[n];
  std::vector<uint8_t> uncovered(values * values, 0);
  size_t remaining = 0;
  for (const auto& [a, va, b, vb] : all_pairs())
    uncovered[(offset[size_t(a)] + size_t(va)) * values + offset[size_t(b)] + size_t(vb)] = 1, ++remaining;
  // Each round picks, of every full renderable combination in odometer order (the last dimension
  // fastest), the first with the most uncovered pairs. A depth-first walk in that order adds each
  // dimension's pairs with the dimensions before it as it goes, and skips a subtree whose gain so
  // far plus all the pairs still to come cannot beat the best found (so the pick is the same as a
  // plain scan's, in a fraction of the time).
  std::vector<int> choice(n, 0), best;
  size_t best_gain = 0;
  std::function<void(size_t, size_t)> visit = [&](size_t d, size_t gain) {
    if (d == n) {
      if (gain > best_gain && renderable(choice)) best = choice, best_gain = gain;
      return;
    }
    const size_t pairs_to_come = (n * (n - 1) - d * (d - 1)) / 2;
    if (gain + pairs_to_come <= best_gain) return;
    for (int v = 0; v < int(dims[d].values.size()); ++v) {
      choice[d] = v;
      const size_t column = offset[d] + size_t(v);
      size_t g = gain;
      for (size_t a = 0; a < d; ++a) g += uncovered[(offset[a] + size_t(choice[a])) * values + column];
      visit(d + 1, g);
    }
  };
  std::vector<KernelVariant> chosen;
  while (remaining > 0) {
    best_gain = 0;
    visit(0, 0);
    KernelVariant v{best};
    for (const auto& [a, va, b, vb] : pairs_of(v.choice)) {
      uint8_t& cell = uncovered[(offset[size_t(a)] + size_t(va)) * values + offset[size_t(b)] + size_t(vb)];
      remaining -= cell;
      cell = 0;
    }
    chosen.push_back(std::move(v));
  }
  // Greedy can leave an early pick redundant once later ones cover its pairs: drop such picks,
  // first to last, so every variant of the set adds a pair.
  for (size_t i = 0; i < chosen.size();) {
    std::vector<KernelVariant> fewer = chosen;
    fewer.erase(fewer.begin() + long(i));
    if (uncovered_pairs(fewer).empty())
      chosen = std::move(fewer);
    else
      ++i;
  }
  return chosen;
}

size_t value_covering_prefix(const std::vector<KernelVariant>& variants) {
  const auto& dims = kernel_variant_dimensions();
  std::vector<std::set<int>> seen(dims.size());
  for (size_t k = 0; k < variants.size(); ++k) {
    for (size_t d = 0; d < dims.size(); ++d) seen[d].insert(variants[k].choice[d]);
    bool all = true;
    for (size_t d = 0; d < dims.size(); ++d) all = all && seen[d].size() == dims[d].values.size();
    if (all) return k + 1;
  }
  return variants.size();
}

std::vector<std::string> uncovered_pairs(const std::vector<KernelVariant>& variants) {
  std::set<Pair> uncovered = all_pairs();
  for (const KernelVariant& v : variants)
    for (const Pair& p : pairs_of(v.choice)) uncovered.erase(p);
  const auto& dims = kernel_variant_dimensions();
  std::vector<std::string> out;
  for (const auto& [a, va, b, vb] : uncovered)
    out.push_back(dims[size_t(a)].name + "=" + dims[size_t(a)].values[size_t(va)] + " + " + dims[size_t(b)].name +
                  "=" + dims[size_t(b)].values[size_t(vb)]);
  return out;
}

Scene variant_scene(const Scene& diffuse, const KernelVariant& variant) {
  Scene scene = diffuse;
  bool left = false, right = false;
  for (Sphere& s : scene.spheres) {
    if (s.name == "left_ball") {
      left = true;
      if (variant.has_phong()) s.material = phong_ball();
    } else if (s.name == "right_ball") {
      right = true;
      if (variant.has_glass()) s.material = glass_ball();
    }
  }
  if (!left || !right)
    throw Error(ExitCode::Failure, "kernel variants are built from the book's diffuse scene "
                                   "(spheres named left_ball and right_ball); this scene lacks them");
  if (variant.has_mesh()) {
    scene.meshes.push_back(mirror_octahedron());
    for (const Sphere& s : pebbles()) scene.spheres.push_back(s);
  }
  if (variant.has_pbr()) scene.spheres.push_back(pbr_ball(variant.has_pbr_transmission(), variant.has_pbr_volume()));
  if (variant.punctual_light() != 0) scene.lights.push_back(punctual_light(variant.punctual_light()));
  if (variant.textures() == 1 || variant.textures() == 2) add_textured_tile(scene, variant.has_pbr(), variant.textures() == 2);
  if (variant.textures() == 3) add_textured_spheres(scene, variant.has_pbr());
  if (variant.orthographic()) {
    scene.camera.projection = Projection::Orthographic;
    scene.camera.ortho_height = 6;
  }
  if (variant.environment() != 0) scene.environment = variant_environment(variant.environment() == 1);
  scene.settings.estimator = estimator_name(variant.estimator());
  scene.settings.rr_from = variant.russian_roulette() ? 2 : -1;
  return scene;
}

void apply_variant(const KernelVariant& variant, RenderRequest& request) {
  request.scene = variant_scene(request.scene, variant);
  request.form = variant.form();
  request.megakernel_loop = variant.megakernel_loop();
  request.precision = variant.precision();
  request.generic_kernel = variant.generic();
  request.scene_loops = variant.scene_loops();
  request.aovs.albedo = request.aovs.normal = request.aovs.depth = variant.aovs();
}

VariantProgram variant_program(const Scene& scene, const KernelVariant& variant) {
  // The render plan decides, as for a render on a GPU: the variant fixes the form, the loop and
  // the scene loops explicitly, so no device property is left for the plan to choose from.
  RenderRequest request;
  request.scene = scene;
  request.form = variant.form();
  request.megakernel_loop = variant.megakernel_loop();
  request.precision = variant.precision();
  request.generic_kernel = variant.generic();
  request.scene_loops = variant.scene_loops();
  request.aovs.albedo = request.aovs.normal = request.aovs.depth = variant.aovs();
  DeviceInfo gpu;
  gpu.name = "a GPU compiler's target";
  gpu.type = "GPU";
  gpu.is_gpu = true;
  gpu.fp64 = true;
  const DevicePlan planned = plan_render(request, {gpu}).devices.front();
  return {planned.entry_file, planned.features};
}

}  // namespace clpt
