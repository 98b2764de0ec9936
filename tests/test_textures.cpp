// Textures (docs/textures.md): the device's lookups (kernels/texture.cl, RGBA and one channel) against
// the host's in double (scene/texture.cpp) over every storage, channel count, wrap mode and filter, at texel
// centres, texel edges and outside [0, 1]; sRGB decoding and half rounding against the standards;
// the texture-coordinate conventions of inline meshes, OBJ and PLY files and glTF (a marker image
// seen through an orthographic camera); Debian's BoxTextured glTF in its three forms; a flat
// normal map leaving the image unchanged.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "device_test_util.h"
#include "gltf_builder.h"
#include "io/image_io.h"
#include "io/exr_writer.h"
#include "io/png_writer.h"
#include "render_test_util.h"
#include "scene/device_textures.h"
#include "scene/scene_loader.h"
#include "scene/texture.h"
#include "util/half_float.h"

namespace clpt::test {
namespace {

// A scene whose meshes each carry one texture (as base colour), so that pack_texturing gives
// texture i for refs[i]: one triangle per mesh, with texture coordinates.
Scene scene_with(const std::vector<TextureImage>& images, const std::vector<TextureRef>& refs) {
  Scene scene;
  scene.images = images;
  for (const TextureRef& ref : refs) {
    TriangleMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.uvs = {{0, 0}, {1, 0}, {0, 1}};
    m.triangles = {{0, 1, 2}};
    m.material.reflectance = {1, 1, 1};
    m.material.textures.base_color = ref;
    scene.meshes.push_back(m);
  }
  return scene;
}

TextureImage random_image(int w, int h, int channels, TexelStorage storage, ColorSpace space, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0, 1);
  TextureImage image;
  image.file = "random";
  image.width = w;
  image.height = h;
  image.channels = channels;
  image.storage = storage;
  image.color_space = space;
  for (int i = 0; i < w * h * channels; ++i) image.pixels.push_back(storage == TexelStorage::Float ? 4 * u(rng) - 1 : u(rng));
  return image;
}

// The device's lookups (probe_texture.cl): RGBA by texture_lookup (kernel probe_texture), or each
// channel by texture_lookup_channel (probe_texture_channels).
std::vector<cl_float4> lookup_on_device(const Scene& scene, const std::vector<cl_float4>& queries,
                                        const char* probe = "probe_texture") {
  std::vector<uint32_t> order(scene.meshes.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = uint32_t(i);
  const std::vector<uint8_t> texturing = pack_texturing(scene, order);
  Kernel kernel(test_program("probe_texture.cl"), probe, test_device().where());
  const Buffer buffer = upload(texturing), in = upload(queries);
  Buffer out(test_device(), queries.size() * sizeof(cl_float4), CL_MEM_WRITE_ONLY, "lookups");
  kernel.set_arg(0, buffer);
  kernel.set_arg(1, in);
  kernel.set_arg(2, out);
  test_device().launch(kernel, queries.size(), 0, "probe_texture");
  return download<cl_float4>(out, queries.size());
}

TEST(TextureLookup, DeviceMatchesTheHostInDouble) {
  const TexelStorage storages[] = {TexelStorage::U8, TexelStorage::Half, TexelStorage::Float};
  std::vector<TextureImage> images;
  std::vector<TextureRef> refs;
  std::vector<std::string> names;
  unsigned seed = 1;
  for (TexelStorage storage : storages)
    for (int channels = 1; channels <= 4; ++channels)
      for (ColorSpace space : {ColorSpace::Srgb, ColorSpace::Linear}) {
        if (storage != TexelStorage::U8 && space == ColorSpace::Srgb) continue;  // linearised at load
        images.push_back(random_image(5, 3, channels, storage, space, seed++));
        for (TextureWrap wrap : {TextureWrap::Repeat, TextureWrap::Clamp, TextureWrap::Mirror})
          for (TextureFilter filter : {TextureFilter::Bilinear, TextureFilter::Nearest}) {
            TextureRef ref;
            ref.image = int(images.size() - 1);
            ref.wrap_u = wrap;
            ref.wrap_v = wrap == TextureWrap::Clamp ? TextureWrap::Mirror : wrap;  // u and v apart
            ref.filter = filter;
            ref.uv_transform = {1.5, 0.25, 0.125, -0.5, 2, 0.0625};  // a sheared, offset transform
            refs.push_back(ref);
            names.push_back(std::string(texel_storage_name(storage)) + " " + std::to_string(channels) + "ch " +
                            color_space_name(space) + " " + texture_wrap_name(wrap) + " " + texture_filter_name(filter));
          }
      }
  // Points at texel centres and edges of the transformed coordinates, and well outside [0, 1].
  std::vector<cl_float4> queries;
  std::vector<std::array<double, 2>> points;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> outside(-2.5, 3.5);
  for (int i = 0; i < 64; ++i) points.push_back({outside(rng), outside(rng)});
  // Texel edges and centres for the identity-like part: u' = 1.5 u + ... is matched by solving.
  for (int k = -3; k <= 13; ++k) {
    const double target_u = k / 10.0, target_v = k / 6.0;  // multiples of half a texel (5 x 3)
    // Solve [1.5 0.25; -0.5 2] (u, v) = (target - offset).
    const double a = 1.5, b = 0.25, c = -0.5, d = 2, det = a * d - b * c;
    const double ru = target_u - 0.125, rv = target_v - 0.0625;
    points.push_back({(d * ru - b * rv) / det, (-c * ru + a * rv) / det});
  }
  for (size_t t = 0; t < refs.size(); ++t)
    for (const auto& p : points) queries.push_back({{float(p[0]), float(p[1]), float(t), 0}});
  const Scene scene = scene_with(images, refs);
  const std::vector<cl_float4> device = lookup_on_device(scene, queries);
  // The scalar parameters' one-sample lookups give the RGBA lookup's channels, to the bit but for
  // the compiler's freedom to contract differently (sRGB, grey, alpha and a missing alpha alike).
  const std::vector<cl_float4> channels = lookup_on_device(scene, queries, "probe_texture_channels");
  for (size_t q = 0; q < queries.size(); ++q)
    for (int k = 0; k < 4; ++k)
      ASSERT_NEAR(channels[q].s[k], device[q].s[k], 1e-6f * (1 + std::fabs(device[q].s[k])))
          << names[size_t(queries[q].s[2])] << " channel " << k;
  size_t checked = 0;
  for (size_t q = 0; q < queries.size(); ++q) {
    const size_t t = size_t(queries[q].s[2]);
    const double u = queries[q].s[0], v = queries[q].s[1];
    const auto host = lookup_texture_on_host(images[size_t(refs[t].image)], refs[t], u, v);
    if (refs[t].filter == TextureFilter::Nearest) {
      // Nearest is discontinuous at texel edges, where float and double may pick neighbours:
      // compare only where the point is not within 1e-4 texels of an edge.
      const auto& tr = refs[t].uv_transform;
      const TextureImage& image = images[size_t(refs[t].image)];
      const double x = (tr[0] * u + tr[1] * v + tr[2]) * image.width, y = (tr[3] * u + tr[4] * v + tr[5]) * image.height;
      if (std::fabs(x - std::round(x)) < 1e-3 || std::fabs(y - std::round(y)) < 1e-3) continue;
    }
    for (int k = 0; k < 4; ++k)
      ASSERT_NEAR(device[q].s[k], host[size_t(k)], 2e-5 * (1 + std::fabs(host[size_t(k)])))
          << names[t] << " at (" << u << ", " << v << ") channel " << k;
    ++checked;
  }
  EXPECT_GT(checked, queries.size() * 3 / 4);
}

TEST(TextureLookup, BilinearWeightsAtTexelEdgesAndCentres) {
  // A 2 x 1 image, values 0 and 1, linear: at the left texel's centre 0, halfway 0.5, at the right
  // centre 1; clamp keeps the edges' texels beyond the centres, repeat blends across the seam.
  TextureImage image;
  image.width = 2;
  image.height = 1;
  image.channels = 1;
  image.storage = TexelStorage::Float;
  image.color_space = ColorSpace::Linear;
  image.pixels = {0, 1};
  TextureRef clamp, repeat;
  clamp.image = repeat.image = 0;
  clamp.wrap_u = clamp.wrap_v = TextureWrap::Clamp;
  const std::vector<cl_float4> queries = {{{0.25f, 0.5f, 0, 0}}, {{0.5f, 0.5f, 0, 0}}, {{0.75f, 0.5f, 0, 0}},
                                          {{0.0f, 0.5f, 0, 0}},  {{0.0f, 0.5f, 1, 0}}, {{0.375f, 0.5f, 0, 0}}};
  const auto out = lookup_on_device(scene_with({image}, {clamp, repeat}), queries);
  EXPECT_NEAR(out[0].s[0], 0.0, 1e-6);
  EXPECT_NEAR(out[1].s[0], 0.5, 1e-6);
  EXPECT_NEAR(out[2].s[0], 1.0, 1e-6);
  EXPECT_NEAR(out[3].s[0], 0.0, 1e-6);   // clamp: the left texel's value up to the image's edge
  EXPECT_NEAR(out[4].s[0], 0.5, 1e-6);   // repeat: halfway between the right and the left texel
  EXPECT_NEAR(out[5].s[0], 0.25, 1e-6);  // a quarter of the way between the centres
  EXPECT_NEAR(out[0].s[3], 1.0, 0);      // one channel: alpha 1
}

TEST(TextureLookup, SrgbDecodingIsTheStandardCurve) {
  // IEC 61966-2-1 values: 0.5 -> 0.214041, 0.04045 -> 0.0031308 (the joint), 1 -> 1.
  EXPECT_NEAR(srgb_to_linear(0.5), 0.21404114, 1e-7);
  EXPECT_NEAR(srgb_to_linear(0.04045), 0.04045 / 12.92, 1e-12);
  EXPECT_NEAR(srgb_to_linear(1.0), 1.0, 1e-12);
  // Every 8-bit value through the device (a 256 x 1 sRGB image, nearest texel centres).
  TextureImage image;
  image.width = 256;
  image.height = 1;
  image.channels = 1;
  image.storage = TexelStorage::U8;
  image.color_space = ColorSpace::Srgb;
  std::vector<cl_float4> queries;
  for (int i = 0; i < 256; ++i) {
    image.pixels.push_back(float(i) / 255.0f);
    queries.push_back({{float((i + 0.5) / 256.0), 0.5f, 0, 0}});
  }
  TextureRef ref;
  ref.image = 0;
  ref.filter = TextureFilter::Nearest;
  const auto out = lookup_on_device(scene_with({image}, {ref}), queries);
  for (int i = 0; i < 256; ++i) ASSERT_NEAR(out[size_t(i)].s[0], srgb_to_linear(i / 255.0), 2e-6 + 2e-6 * srgb_to_linear(i / 255.0)) << i;
}

TEST(TextureLookup, HalfConversionRoundsToNearestEven) {
  EXPECT_EQ(float_to_half_bits(1.0f), 0x3c00);
  EXPECT_EQ(float_to_half_bits(-2.0f), 0xc000);
  EXPECT_EQ(float_to_half_bits(65504.0f), 0x7bff);
  EXPECT_EQ(float_to_half_bits(1e6f), 0x7c00);        // overflow: infinity
  EXPECT_EQ(float_to_half_bits(0.1f), 0x2e66);        // 0.0999755859375
  EXPECT_EQ(float_to_half_bits(1.0f + 1.0f / 2048), 0x3c00);  // a tie: to even
  EXPECT_EQ(float_to_half_bits(1.0f + 3.0f / 2048), 0x3c02);  // a tie: to even, upwards
  EXPECT_EQ(float_to_half_bits(5.960464477539063e-08f), 0x0001);  // the smallest subnormal
  EXPECT_EQ(float_to_half_bits(2.0e-8f), 0x0000);
  for (uint32_t h = 0; h < 0x7c00; ++h) ASSERT_EQ(float_to_half_bits(half_bits_to_float(uint16_t(h))), h) << h;
}

// --- conventions, through whole renders -----------------------------------------------------

// A 2 x 2 marker: red top-left, green top-right, blue bottom-left, white bottom-right.
std::string write_marker(const std::string& dir) {
  const std::vector<unsigned char> rgb = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
  const std::string path = dir + "/marker.png";
  write_rgb8_image(path, 2, 2, rgb);
  return path;
}

std::string temp_dir(const std::string& name) {
  const std::string dir = (std::filesystem::temp_directory_path() / ("clpt_textures_" + name)).string();
  std::filesystem::create_directories(dir);
  return dir;
}

// Renders `scene` at 4 x 4 and returns the mean of each quadrant's top-left pixel... the four
// pixels at the image's corners, as (top-left, top-right, bottom-left, bottom-right).
std::array<std::array<double, 3>, 4> corners(Scene scene) {
  const TestRender r = render_for_test(std::move(scene), 4, 4, 16, 1);
  const std::vector<float> mean = r.film.mean_rgb();
  const int at[4] = {0, 3, 12, 15};
  std::array<std::array<double, 3>, 4> out{};
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 3; ++c) out[size_t(i)][size_t(c)] = mean[size_t(at[i]) * 3 + size_t(c)];
  return out;
}

void expect_marker(const std::array<std::array<double, 3>, 4>& seen, const std::string& what) {
  const std::array<std::array<double, 3>, 4> expected = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}}};
  const char* names[4] = {"top-left", "top-right", "bottom-left", "bottom-right"};
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(seen[size_t(i)][size_t(c)], expected[size_t(i)][size_t(c)], 1e-4) << what << " " << names[i] << " channel " << c;
}

// The quad spans [-1, 1]^2 at z = 0 facing +z; an orthographic camera 2 units high looks at it
// from +z. The marker is its emission (an emitter: the camera ray's radiance is the texel).
const char* kCamera = R"(
[render]
spp = 16
max_bounces = 0
[camera]
position = [0, 0, 5]
look_at = [0, 0, 0]
projection = "orthographic"
height = 2
)";

TEST(TextureConventions, InlineMeshUvsAreObjs) {
  install_scene_image_reader();
  const std::string dir = temp_dir("inline");
  write_marker(dir);
  const std::string text = std::string(kCamera) + R"(
[[mesh]]
vertices = [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]]
uvs = [[0, 0], [1, 0], [1, 1], [0, 1]]
quads = [[0, 1, 2, 3]]
material = { type = "emitter", emission = { texture = "marker.png", filter = "nearest" } }
)";
  expect_marker(corners(load_scene_string(text, dir + "/scene.toml")), "inline mesh");
}

TEST(TextureConventions, ObjFileUvsAreBottomLeft) {
  install_scene_image_reader();
  const std::string dir = temp_dir("obj");
  write_marker(dir);
  std::ofstream(dir + "/quad.obj") << "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                      "f 1/1 2/2 3/3 4/4\n";
  const std::string text = std::string(kCamera) + R"(
[[mesh]]
file = "quad.obj"
material = { type = "emitter", emission = { texture = "marker.png", filter = "nearest" } }
)";
  expect_marker(corners(load_scene_string(text, dir + "/scene.toml")), "OBJ file");
}

// The same quad as a PLY file, its texture coordinates under each of the vertex property names
// PLY writers use (s/t: Blender; u/v; texture_u/texture_v; texture_s/texture_t), as ASCII and as
// binary little-endian floats: (0, 0) at the image's bottom-left, as in OBJ.
TEST(TextureConventions, PlyFileUvsAreBottomLeft) {
  install_scene_image_reader();
  const std::string dir = temp_dir("ply");
  write_marker(dir);
  const float vertices[4][5] = {{-1, -1, 0, 0, 0}, {1, -1, 0, 1, 0}, {1, 1, 0, 1, 1}, {-1, 1, 0, 0, 1}};
  const std::pair<const char*, const char*> names[] = {{"s", "t"}, {"u", "v"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}};
  for (const auto& [u, v] : names)
    for (const bool binary : {false, true}) {
      const std::string what = std::string("PLY ") + (binary ? "binary" : "ASCII") + ", " + u + "/" + v;
      std::ofstream ply(dir + "/quad.ply", std::ios::binary);
      ply << "ply\nformat " << (binary ? "binary_little_endian" : "ascii") << " 1.0\nelement vertex 4\n"
          << "property float x\nproperty float y\nproperty float z\nproperty float " << u << "\nproperty float " << v
          << "\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
      if (binary) {
        ply.write(reinterpret_cast<const char*>(vertices), sizeof vertices);  // x86 and every OpenCL host: little-endian
        const unsigned char count = 4;
        const int32_t face[4] = {0, 1, 2, 3};
        ply.write(reinterpret_cast<const char*>(&count), 1);
        ply.write(reinterpret_cast<const char*>(face), sizeof face);
      } else {
        for (const auto& vertex : vertices) ply << vertex[0] << " " << vertex[1] << " " << vertex[2] << " " << vertex[3] << " " << vertex[4] << "\n";
        ply << "4 0 1 2 3\n";
      }
      ply.close();
      const std::string text = std::string(kCamera) + R"(
[[mesh]]
file = "quad.ply"
material = { type = "emitter", emission = { texture = "marker.png", filter = "nearest" } }
)";
      expect_marker(corners(load_scene_string(text, dir + "/scene.toml")), what);
    }
  // texture_s/texture_t are read (as texture_u/texture_v) only where the vertex has no property
  // assimp reads for that coordinate itself: u/v here, which win (assimp would take the last).
  std::ofstream(dir + "/both.ply") << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                      "property float z\nproperty float u\nproperty float texture_s\nproperty float v\n"
                                      "property float texture_t\nelement face 1\nproperty list uchar int vertex_indices\n"
                                      "end_header\n0 0 0 0 0.5 0 0.5\n1 0 0 1 0.5 0 0.5\n0 1 0 0 0.5 1 0.5\n3 0 1 2\n";
  const Scene both = load_scene_string(
      std::string(kCamera) + "[[mesh]]\nfile = \"both.ply\"\nmaterial = { type = \"emitter\", emission = [1, 1, 1] }\n",
      dir + "/both.toml");
  ASSERT_EQ(both.meshes.at(0).uvs.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(both.meshes[0].uvs[i][0], both.meshes[0].positions[i][0]) << "vertex " << i;
    EXPECT_EQ(both.meshes[0].uvs[i][1], both.meshes[0].positions[i][1]) << "vertex " << i;
  }
}

// A glTF quad whose TEXCOORD_0 follows glTF's convention ((0, 0) at the image's top-left), the
// marker as its emissive texture.
GltfBuilder marker_quad(const nlohmann::json& image) {
  GltfBuilder b;
  const int position = b.positions({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0});
  const int uv = b.accessor(std::vector<float>{0, 1, 1, 1, 1, 0, 0, 0}, 5126, "VEC2");
  const int indices = b.indices({0, 1, 2, 0, 2, 3});
  b.push("images", image);
  b.push("samplers", {{"magFilter", 9728}});
  b.push("textures", {{"source", 0}, {"sampler", 0}});
  b.push("materials", {{"emissiveFactor", {1, 1, 1}}, {"emissiveTexture", {{"index", 0}}},
                       {"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 0, 1}}, {"metallicFactor", 0}}}});
  b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", position}, {"TEXCOORD_0", uv}}}, {"indices", indices}, {"material", 0}})}});
  return b;
}

TEST(TextureConventions, GltfTexcoordsAreTopLeft) {
  install_scene_image_reader();
  const std::string dir = temp_dir("gltf");
  write_marker(dir);
  std::ofstream(dir + "/quad.gltf") << marker_quad({{"uri", "marker.png"}}).gltf_embedded();
  const std::string text = std::string(kCamera) + "[[gltf]]\nfile = \"quad.gltf\"\n";
  expect_marker(corners(load_scene_string(text, dir + "/scene.toml")), "glTF, image file");
  // The same image as a data: URI.
  std::ifstream png(dir + "/marker.png", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(png)), std::istreambuf_iterator<char>());
  std::ofstream(dir + "/quad_data.gltf")
      << marker_quad({{"uri", "data:image/png;base64," + GltfBuilder::base64(bytes)}}).gltf_embedded();
  const std::string data_text = std::string(kCamera) + "[[gltf]]\nfile = \"quad_data.gltf\"\n";
  expect_marker(corners(load_scene_string(data_text, dir + "/scene2.toml")), "glTF, data: URI");
}

// A material's textures read the coordinate set their texCoord names (KHR_texture_transform's
// texCoord overriding it): the marker quad with its real coordinates in TEXCOORD_1 and a constant
// (0.5, 0.5) in TEXCOORD_0 shows the marker only through set 1. A primitive without the set its
// textured material reads is refused, naming it; textures of one material that name different
// sets all read the base colour's, with a warning naming the other.
TEST(TextureConventions, GltfTexCoordPicksTheCoordinateSet) {
  install_scene_image_reader();
  const std::string dir = temp_dir("gltf_sets");
  write_marker(dir);
  const auto quad = [](const nlohmann::json& emissive_info, bool with_set_1) {
    GltfBuilder b = marker_quad({{"uri", "marker.png"}});
    const int uv1 = b.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"];
    const int centre = b.accessor(std::vector<float>{0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f}, 5126, "VEC2");
    b.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = centre;
    if (with_set_1) b.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] = uv1;
    b.doc["materials"][0]["emissiveTexture"] = emissive_info;
    return b;
  };
  const auto render_scene = [&](const GltfBuilder& b, const std::string& name) {
    std::ofstream(dir + "/" + name + ".gltf") << b.gltf_embedded();
    return load_scene_string(std::string(kCamera) + "[[gltf]]\nfile = \"" + name + ".gltf\"\n", dir + "/" + name + ".toml");
  };
  expect_marker(corners(render_scene(quad({{"index", 0}, {"texCoord", 1}}, true), "set1")), "glTF, texCoord 1");
  const nlohmann::json transformed = {
      {"index", 0}, {"texCoord", 0}, {"extensions", {{"KHR_texture_transform", {{"texCoord", 1}}}}}};
  expect_marker(corners(render_scene(quad(transformed, true), "transform_set1")), "glTF, KHR_texture_transform texCoord 1");
  try {
    render_scene(quad({{"index", 0}, {"texCoord", 1}}, false), "missing");
    ADD_FAILURE() << "a primitive without TEXCOORD_1 was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("missing.gltf: meshes[0].primitives[0].attributes: no TEXCOORD_1, which the "
                                         "textures of its material (materials[0]) read by their texCoord"),
              std::string::npos)
        << e.what();
  }
  try {
    render_scene(quad({{"index", 0}, {"texCoord", 16}}, true), "set16");
    ADD_FAILURE() << "texCoord 16 was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("set16.gltf: materials[0].emissiveTexture.texCoord: 16 is not a coordinate "
                                         "set clpt reads (TEXCOORD_0 to TEXCOORD_15)"),
              std::string::npos)
        << e.what();
  }
  GltfBuilder mixed = quad({{"index", 0}, {"texCoord", 1}}, true);
  mixed.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
  const Scene scene = render_scene(mixed, "mixed");
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.meshes[0].material.textures.uv_set, 0);
  bool warned = false;
  for (const std::string& w : scene.warnings)
    warned = warned || w.find("materials[0].emissiveTexture.texCoord: 1, but materials[0].pbrMetallicRoughness."
                              "baseColorTexture reads TEXCOORD_0") != std::string::npos;
  EXPECT_TRUE(warned);
}

// Debian's BoxTextured (the Khronos sample) as a separate PNG, in the GLB's buffer and as a
// data: URI: the same image, the same texture coordinates.
TEST(TextureScenes, BoxTexturedLoadsInAllThreeForms) {
  install_scene_image_reader();
  const std::string root = "/usr/share/assimp/models/glTF2/";
  const std::string files[] = {root + "BoxTextured-glTF/BoxTextured.gltf", root + "BoxTextured-glTF-Binary/BoxTextured.glb",
                               root + "BoxTextured-glTF-Embedded/BoxTextured.gltf"};
  if (!std::filesystem::exists(files[0])) GTEST_SKIP() << "assimp-testmodels is not installed";
  std::vector<Scene> scenes;
  for (const std::string& f : files) scenes.push_back(load_scene_file(f));
  for (const Scene& s : scenes) {
    ASSERT_EQ(s.images.size(), 1u) << s.file;
    EXPECT_EQ(s.images[0].width, scenes[0].images[0].width);
    EXPECT_EQ(s.images[0].pixels, scenes[0].images[0].pixels) << s.file;
    EXPECT_EQ(s.images[0].storage, TexelStorage::U8);
    EXPECT_EQ(s.images[0].color_space, ColorSpace::Srgb);
    ASSERT_EQ(s.meshes.size(), 1u);
    EXPECT_EQ(s.meshes[0].uvs.size(), s.meshes[0].positions.size());
    EXPECT_TRUE(s.meshes[0].material.textures.base_color.used());
  }
}

TEST(TextureScenes, FlatNormalMapLeavesTheImageUnchanged) {
  install_scene_image_reader();
  const std::string dir = temp_dir("normal");
  // A float normal map of (0.5, 0.5, 1): exactly the unperturbed normal (0, 0, 1).
  const std::vector<float> flat = {0.5f, 0.5f, 1.0f, 0.5f, 0.5f, 1.0f, 0.5f, 0.5f, 1.0f, 0.5f, 0.5f, 1.0f};
  ImageToWrite exr;
  exr.width = 2;
  exr.height = 2;
  exr.channels = {"R", "G", "B"};
  exr.pixels = flat.data();
  ASSERT_EQ(write_exr(dir + "/flat.exr", exr), "");
  const auto scene = [&](bool mapped) {
    return std::string(R"(
[render]
estimator = "nee"
max_bounces = 3
[camera]
position = [0, 2, 4]
look_at = [0, 0, 0]
[[sphere]]
center = [0, 6, 0]
radius = 1
material = { type = "emitter", emission = [6, 6, 6] }
[[mesh]]
vertices = [[-2, 0, -2], [2, 0, -2], [2, 0, 2], [-2, 0, 2]]
normals = [[0.2, 1, 0], [0, 1, 0.3], [-0.1, 1, 0], [0, 1, 0]]
uvs = [[0, 0], [3, 0], [3, 3], [0, 3]]
quads = [[3, 2, 1, 0]]
material = { type = "pbr", roughness = 0.4, metallic = 0.3)") +
           (mapped ? ", normal_map = { texture = \"flat.exr\" }" : "") + " }\n";
  };
  const Scene plain = load_scene_string(scene(false), dir + "/plain.toml");
  const Scene mapped = load_scene_string(scene(true), dir + "/mapped.toml");
  ASSERT_TRUE(mapped.meshes[0].material.textures.normal.used());
  const TestRender a = render_for_test(plain, 24, 16, 32, 5);
  const TestRender b = render_for_test(mapped, 24, 16, 32, 5);
  expect_same_image(a.film.mean_rgb(), b.film.mean_rgb());
}

// A glTF primitive's TANGENT is kept, in world space: xyz as a direction, w flipped where the
// node mirrors (the bitangent w n x t must stay the mirrored one).
TEST(TextureScenes, GltfTangentsFollowTheNodeTransform) {
  const std::string dir = temp_dir("tangents");
  for (const double sx : {1.0, -1.0}) {
    GltfBuilder b;
    const int position = b.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
    const int normal = b.accessor(std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1}, 5126, "VEC3");
    const int tangent = b.accessor(std::vector<float>{1, 0, 0, 1, 1, 0, 0, -1, 0, 2, 0, 1}, 5126, "VEC4");
    b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", position}, {"NORMAL", normal}, {"TANGENT", tangent}}}})},
            {"scale", {sx, 1, 1}}});
    const std::string file = dir + "/t.gltf";
    std::ofstream(file) << b.gltf_embedded();
    const Scene scene = load_scene_file(file);
    const TriangleMesh& m = scene.meshes.at(0);
    ASSERT_EQ(m.tangents.size(), 3u);
    EXPECT_NEAR(m.tangents[0][0], sx, 1e-12);
    EXPECT_NEAR(m.tangents[0][3], sx, 1e-12);       // w = 1, flipped by the mirror
    EXPECT_NEAR(m.tangents[1][3], -sx, 1e-12);      // w = -1
    EXPECT_NEAR(m.tangents[2][1], 1, 1e-12);        // (0, 2, 0) normalised
  }
}

// An emitting quad whose emission is the marker image lights a floor: next-event estimation
// (which samples points on the quad and must read the texture there, light.cl) and the book
// estimator (which finds the emission where a path hits the quad) converge to the same image.
// Were the light samples to see the factor alone (white), the floor under the quad's red,
// green and blue quarters would come out grey under nee.
TEST(TextureScenes, EmissionTexturesLightAlikeUnderBothEstimators) {
  install_scene_image_reader();
  const std::string dir = temp_dir("emission");
  write_marker(dir);
  const auto scene = [&](const char* estimator) {
    return std::string("[render]\nmax_bounces = 1\nestimator = \"") + estimator + R"("
[camera]
position = [0, 3, 0.001]
look_at = [0, 0, 0]
projection = "orthographic"
height = 2
[[mesh]]
vertices = [[-1, 0, 1], [1, 0, 1], [1, 0, -1], [-1, 0, -1]]
quads = [[0, 1, 2, 3]]
material = { type = "lambertian", reflectance = [0.8, 0.8, 0.8] }
[[mesh]]
vertices = [[-1, 0.5, 1], [1, 0.5, 1], [1, 0.5, -1], [-1, 0.5, -1]]
uvs = [[0, 0], [1, 0], [1, 1], [0, 1]]
quads = [[3, 2, 1, 0]]
material = { type = "emitter", emission = { texture = "marker.png", filter = "nearest", scale = 3 } }
)";
  };
  // The camera sits above the emitting quad, which hides the floor: look from below the light
  // instead, through the gap, by placing the camera between the two (y = 0.25, looking down).
  std::string nee = scene("nee"), book = scene("book");
  for (std::string* text : {&nee, &book}) {
    const size_t at = text->find("position = [0, 3, 0.001]");
    text->replace(at, 24, "position = [0, 0.25, 0.001]");
  }
  const TestRender a = render_for_test(load_scene_string(nee, dir + "/nee.toml"), 8, 8, 256, 3);
  const TestRender b = render_for_test(load_scene_string(book, dir + "/book.toml"), 8, 8, 256, 4);
  const MeanVarianceImage ia = a.film.mean_variance(), ib = b.film.mean_variance();
  const double z = sidak_z(4 * 3);
  int coloured = 0;
  for (int q = 0; q < 4; ++q) {
    const int x0 = (q % 2) * 4, y0 = (q / 2) * 4;
    const RegionStats ra = region_stats(ia.mean, ia.variance, 8, x0, y0, x0 + 4, y0 + 4);
    const RegionStats rb = region_stats(ib.mean, ib.variance, 8, x0, y0, x0 + 4, y0 + 4);
    for (int c = 0; c < 3; ++c) {
      const double diff = ra.mean[c] - rb.mean[c];
      EXPECT_LT(std::fabs(diff), z * std::sqrt(ra.variance_of_mean[c] + rb.variance_of_mean[c]) + 1e-6)
          << "quadrant " << q << " channel " << c << ": nee " << ra.mean[c] << ", book " << rb.mean[c];
    }
    // The quadrants are tinted (not grey): the texture reaches the floor.
    coloured += std::fabs(ra.mean[0] - ra.mean[1]) > 0.05 || std::fabs(ra.mean[1] - ra.mean[2]) > 0.05;
  }
  EXPECT_GE(coloured, 3);
}

}  // namespace
}  // namespace clpt::test
