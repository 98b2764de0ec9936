// glTF COLOR_0 vertex colours (issue 34; kernels/vertex_colors.cl, docs/textures.md "Vertex
// colours"): the loader's values for every allowed accessor kind and its refusals naming the
// element; the texturing buffer's colors section; on the device, a quad whose colour ramps from red
// to green across it, lit by a directional light, against the linearity of the image in the base
// colour (a black and a white quad give the two ends), in both forms and the generic kernel; white
// vertex colours render as none and a constant colour as the same baseColorFactor (same seed, same
// image); a COLOR_0 alpha below a MASK cutoff cuts the surface.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <fstream>
#include <limits>

#include "gltf_builder.h"
#include "kernels/kernel_options.h"
#include "kernels/types.h"
#include "quad_camera_scene.h"
#include "render_test_util.h"
#include "scene/device_textures.h"
#include "scene/gltf_glb.h"
#include "scene/gltf_loader.h"
#include "scene/scene_loader.h"
#include "util/error.h"

namespace clpt::test {
namespace {

using nlohmann::json;

const std::vector<float> kTriangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};

Scene load(const GltfBuilder& b) {
  return load_gltf_scene(make_glb(b.json_text(), b.bin.empty() ? std::nullopt : std::optional<std::string_view>(b.bin)),
                         "mem.glb");
}

std::string load_error(const GltfBuilder& b) {
  try {
    load(b);
  } catch (const Error& e) {
    EXPECT_EQ(int(e.code()), int(ExitCode::BadScene)) << e.what();
    return e.what();
  }
  return "";
}

// A triangle with COLOR_0 = accessor `color` (built by `make`).
GltfBuilder triangle_with(const std::function<int(GltfBuilder&)>& make) {
  GltfBuilder b;
  const int position = b.positions(kTriangle);
  const int color = make(b);
  b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", position}, {"COLOR_0", color}}}})}});
  return b;
}

TEST(GltfVertexColors, EveryComponentTypeAndBothTypesGiveLinearValues) {
  // Expected (r, g, b, a) of the three vertices; the stored forms below encode them exactly
  // (ubyte: v / 255, ushort: v / 65535).
  const double expected[3][4] = {{1, 0.2, 0, 0.6}, {0, 1, 0.4, 1}, {0.8, 0, 1, 0.2}};
  for (int components : {3, 4})
    for (int type : {5126, 5121, 5123}) {
      SCOPED_TRACE("component type " + std::to_string(type) + ", VEC" + std::to_string(components));
      const double scale = type == 5121 ? 255 : type == 5123 ? 65535 : 1;
      std::vector<double> values;
      for (const auto& v : expected)
        for (int c = 0; c < components; ++c) values.push_back(v[c] * scale);
      const std::string vec = components == 3 ? "VEC3" : "VEC4";
      const GltfBuilder b = triangle_with([&](GltfBuilder& g) {
        if (type == 5126) return g.accessor(std::vector<float>(values.begin(), values.end()), type, vec);
        if (type == 5121) {
          std::vector<uint8_t> v;
          for (double x : values) v.push_back(uint8_t(std::lround(x)));
          return g.accessor(v, type, vec, true);
        }
        std::vector<uint16_t> v;
        for (double x : values) v.push_back(uint16_t(std::lround(x)));
        return g.accessor(v, type, vec, true);
      });
      const TriangleMesh m = load(b).meshes.at(0);
      ASSERT_EQ(m.colors.size(), 3u);
      const double tolerance = type == 5126 ? 1e-7 : 1e-12;
      for (int i = 0; i < 3; ++i)
        for (int c = 0; c < 4; ++c)
          EXPECT_NEAR(m.colors[size_t(i)][size_t(c)], components == 3 && c == 3 ? 1.0 : expected[i][c], tolerance)
              << "vertex " << i << " channel " << c;
    }
  // Without COLOR_0: no colours, and no texturing buffer for a plain mesh.
  GltfBuilder plain;
  plain.node({{"mesh", plain.triangle_mesh(kTriangle)}});
  const Scene s = load(plain);
  EXPECT_TRUE(s.meshes.at(0).colors.empty());
  EXPECT_FALSE(texture_use(s).vertex_colors);
  EXPECT_TRUE(pack_texturing(s, {0}).empty());
}

TEST(GltfVertexColors, BadAccessorsNameTheElement) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::string where = "mem.glb: meshes[0].primitives[0].attributes.COLOR_0: ";
  const struct {
    std::function<int(GltfBuilder&)> make;
    std::string message;
  } cases[] = {
      {[](GltfBuilder& g) { return g.accessor(std::vector<float>{1, 1, 1, 1, 1, 1}, 5126, "VEC2"); },
       where + "the accessor's type must be VEC3 or VEC4 (accessors[1])"},
      {[](GltfBuilder& g) { return g.accessor(std::vector<int8_t>(9, 100), 5120, "VEC3", true); },
       where + "component type BYTE (5120) is not allowed here (accessors[1])"},
      {[](GltfBuilder& g) { return g.accessor(std::vector<uint32_t>(9, 1), 5125, "VEC3"); },
       where + "component type UNSIGNED_INT (5125) is not allowed here (accessors[1])"},
      {[](GltfBuilder& g) { return g.accessor(std::vector<uint8_t>(9, 255), 5121, "VEC3"); },
       where + "integer components must be normalized here (accessors[1])"},
      {[](GltfBuilder& g) { return g.accessor(std::vector<float>(8, 1.0f), 5126, "VEC4"); },
       where + "has 2 elements, POSITION has 3"},
      {[](GltfBuilder& g) { return g.accessor(std::vector<float>{1, 1, 1, 1, 1, -0.5f, 1, 1, 1}, 5126, "VEC3"); },
       where + "colour 1 has a negative component"},
      {[nan](GltfBuilder& g) { return g.accessor(std::vector<float>{1, 1, 1, 1, nan, 1, 1, 1, 1}, 5126, "VEC3"); },
       "mem.glb: accessors[1]: element 1 is not finite (meshes[0].primitives[0].attributes.COLOR_0)"},
  };
  for (const auto& k : cases) {
    const std::string error = load_error(triangle_with(k.make));
    EXPECT_EQ(error.substr(0, k.message.size()), k.message) << error;
  }
}

// The colors section: one record per device triangle in the device's order, the mesh's corners
// for a mesh with COLOR_0 (which gets a textured-material record without any image), white for
// the others; the kernels compile CLPT_HAS_VERTEX_COLORS for this scene only.
TEST(GltfVertexColors, TexturingBufferHoldsEachTrianglesCorners) {
  GltfBuilder b;
  const int position = b.positions({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0});
  const int color = b.accessor(std::vector<float>{1, 0, 0, 0, 1, 0, 0, 0, 1, 0.5f, 0.5f, 0.5f}, 5126, "VEC3");
  const int indices = b.indices({0, 1, 2, 1, 3, 2});
  b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", position}, {"COLOR_0", color}}}, {"indices", indices}})}});
  b.node({{"mesh", b.triangle_mesh({0, 0, 1, 1, 0, 1, 0, 1, 1})}});
  const Scene scene = load(b);
  ASSERT_EQ(scene.meshes.size(), 2u);
  const std::vector<uint32_t> order = {2, 1, 0};  // device triangle i is scene triangle order[i]
  const std::vector<uint8_t> buffer = pack_texturing(scene, order);
  ASSERT_GE(buffer.size(), sizeof(GpuTexturing));
  GpuTexturing header;
  std::memcpy(&header, buffer.data(), sizeof header);
  ASSERT_NE(header.colors, 0u);
  ASSERT_LE(header.colors + 3 * sizeof(GpuTriangleColors), buffer.size());
  const double corners[3][3][4] = {{{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}},
                                   {{0, 1, 0, 1}, {0.5, 0.5, 0.5, 1}, {0, 0, 1, 1}},
                                   {{1, 1, 1, 1}, {1, 1, 1, 1}, {1, 1, 1, 1}}};
  for (size_t i = 0; i < 3; ++i) {
    GpuTriangleColors k;
    std::memcpy(&k, buffer.data() + header.colors + i * sizeof k, sizeof k);
    GpuTriangleTexturing t;
    std::memcpy(&t, buffer.data() + header.triangles + i * sizeof t, sizeof t);
    const float* c[3] = {k.c0, k.c1, k.c2};
    const uint32_t scene_triangle = order[i];
    for (int corner = 0; corner < 3; ++corner)
      for (int ch = 0; ch < 4; ++ch)
        EXPECT_FLOAT_EQ(c[corner][ch], float(corners[scene_triangle][corner][ch]))
            << "device triangle " << i << " corner " << corner << " channel " << ch;
    EXPECT_EQ(t.material != CLPT_TEXTURE_NONE, scene_triangle < 2) << "device triangle " << i;
  }
  const KernelFeatures f = features_for_scene(scene);
  EXPECT_TRUE(f.vertex_colors);
  EXPECT_TRUE(f.textures);
  EXPECT_EQ(f.texel_storages, 0u);
  EXPECT_NE(kernel_build_options(f).find(" -DCLPT_HAS_VERTEX_COLORS=1"), std::string::npos);
  GltfBuilder plain;
  plain.node({{"mesh", plain.triangle_mesh(kTriangle)}});
  const KernelFeatures g = features_for_scene(load(plain));
  EXPECT_FALSE(g.vertex_colors);
  EXPECT_EQ(kernel_build_options(g).find("VERTEX_COLORS"), std::string::npos);
}

// --- On the device --------------------------------------------------------------------------

std::string temp_dir(const std::string& name) {
  const std::string dir = (std::filesystem::temp_directory_path() / ("clpt_vertex_colors_" + name)).string();
  std::filesystem::create_directories(dir);
  return dir;
}

// The quad [-1, 1]^2 at z = 0 facing +z, double-sided, with `material` and, unless `colors` is
// empty, COLOR_0 = `colors` (VEC3 or VEC4 by `components`) at its corners (-1, -1), (1, -1),
// (1, 1), (-1, 1).
std::string quad_gltf(const json& material, const std::vector<float>& colors, int components = 3) {
  GltfBuilder b;
  json attributes = {{"POSITION", b.positions({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0})}};
  if (!colors.empty()) attributes["COLOR_0"] = b.accessor(colors, 5126, components == 3 ? "VEC3" : "VEC4");
  const int indices = b.indices({0, 1, 2, 0, 2, 3});
  b.push("materials", material);
  b.node({{"mesh", b.mesh({{"attributes", attributes}, {"indices", indices}, {"material", 0}})}});
  return b.gltf_embedded();
}

// A dielectric, fully rough: base colour `base`.
json dielectric(const std::vector<double>& base) {
  return {{"pbrMetallicRoughness", {{"baseColorFactor", {base[0], base[1], base[2], 1}}, {"metallicFactor", 0}}},
          {"doubleSided", true}};
}

std::vector<float> corners(const std::vector<float>& rgb) {  // one colour at all four corners
  std::vector<float> out;
  for (int i = 0; i < 4; ++i) out.insert(out.end(), rgb.begin(), rgb.end());
  return out;
}

// The lit scene: an orthographic camera on +z sees exactly the quad (quad.gltf), lit by a
// directional light from the front (next-event estimation, one bounce, nothing else in the scene:
// every sample of a pixel is the BSDF at the same two directions times the light).
Scene lit_scene(const std::string& dir, const std::string& gltf_text) {
  std::ofstream(dir + "/quad.gltf") << gltf_text;
  return load_scene_string(R"(
[render]
max_bounces = 1
estimator = "nee"
[camera]
position = [0, 0, 5]
look_at = [0, 0, 0]
projection = "orthographic"
height = 2
[[light]]
name = "sun"
type = "directional"
direction = [0.3, -0.4, -1]
lux = 683
[[gltf]]
file = "quad.gltf"
)",
                           dir + "/lit.toml");
}

struct Way {
  const char* name;
  ExecutionForm form;
  bool generic;
};
const Way kWays[] = {
    {"megakernel", ExecutionForm::Megakernel, false},
    {"wavefront", ExecutionForm::Wavefront, false},
    {"generic megakernel", ExecutionForm::Megakernel, true},
};

MeanVarianceImage render(const Scene& scene, const Way& way, int size, int64_t spp, uint64_t seed) {
  RenderRequest request = test_request(scene, size, size, spp, seed, Sampler::Jitter);
  request.form = way.form;
  request.generic_kernel = way.generic;
  RenderReport report;
  return run_render(request, report).mean_variance();
}

// The image is linear in the base colour: with COLOR_0 red at the quad's left edge and green at its
// right, column x (centre at a fraction t = (x + 0.5) / size across) is black + c (white - black)
// per channel, c = (1 - t, t, 0), where black and white are the same quad with COLOR_0 0 and 1.
TEST(GltfVertexColors, RampIsTheInterpolatedBaseColourInEveryForm) {
  const std::string dir = temp_dir("ramp");
  const json white_base = dielectric({1, 1, 1});
  const std::vector<float> ramp = {1, 0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0};
  const int size = 8, spp = 16;
  const Scene black = lit_scene(dir, quad_gltf(white_base, corners({0, 0, 0})));
  const Scene white = lit_scene(dir, quad_gltf(white_base, corners({1, 1, 1})));
  const Scene ramped = lit_scene(dir, quad_gltf(white_base, ramp));
  ASSERT_TRUE(features_for_scene(ramped).vertex_colors);
  const double z = sidak_z(int(std::size(kWays)) * size * 3);
  uint64_t seed = 41;
  for (const Way& way : kWays) {
    const MeanVarianceImage b = render(black, way, size, spp, seed++);
    const MeanVarianceImage w = render(white, way, size, spp, seed++);
    const MeanVarianceImage r = render(ramped, way, size, spp, seed++);
    const RegionStats sb = region_stats(b.mean, b.variance, size, 0, 0, size, size);
    const RegionStats sw = region_stats(w.mean, w.variance, size, 0, 0, size, size);
    EXPECT_GT(sw.mean[0], 2 * sb.mean[0] + 1e-3) << way.name << ": the base colour must matter";
    for (int x = 0; x < size; ++x) {
      const RegionStats column = region_stats(r.mean, r.variance, size, x, 0, x + 1, size);
      const double t = (x + 0.5) / size;
      const double c[3] = {1 - t, t, 0};
      for (int ch = 0; ch < 3; ++ch) {
        const double expected = sb.mean[ch] + c[ch] * (sw.mean[ch] - sb.mean[ch]);
        const double variance = column.variance_of_mean[ch] + (1 - c[ch]) * (1 - c[ch]) * sb.variance_of_mean[ch] +
                                c[ch] * c[ch] * sw.variance_of_mean[ch];
        EXPECT_NEAR(column.mean[ch], expected, z * std::sqrt(variance) + 1e-5 * sw.mean[ch])
            << way.name << ": column " << x << " channel " << ch;
      }
    }
  }
}

// Same seed, same image: white COLOR_0 is no COLOR_0 (the textured path multiplies by 1), and a
// constant COLOR_0 c under baseColorFactor 1 is baseColorFactor c without COLOR_0.
TEST(GltfVertexColors, WhiteIsNoneAndConstantIsTheFactorAtTheSameSeed) {
  const std::string dir = temp_dir("same_seed");
  const std::vector<float> c = {0.8f, 0.5f, 0.2f};
  const Scene none = lit_scene(dir, quad_gltf(dielectric({1, 1, 1}), {}));
  const Scene white = lit_scene(dir, quad_gltf(dielectric({1, 1, 1}), corners({1, 1, 1})));
  const Scene factor = lit_scene(dir, quad_gltf(dielectric({c[0], c[1], c[2]}), {}));
  const Scene colored = lit_scene(dir, quad_gltf(dielectric({1, 1, 1}), corners(c)));
  EXPECT_FALSE(features_for_scene(none).vertex_colors);
  EXPECT_TRUE(features_for_scene(white).vertex_colors);
  for (const Way& way : {kWays[0], kWays[1]}) {
    SCOPED_TRACE(way.name);
    expect_same_image(render(none, way, 8, 4, 7).mean, render(white, way, 8, 4, 7).mean);
    expect_same_image(render(factor, way, 8, 4, 8).mean, render(colored, way, 8, 4, 8).mean);
  }
}

// COLOR_0's alpha multiplies the base colour's: 0.3 under a MASK cutoff of 0.5 cuts the quad (the
// emitter behind it shows, exactly 1), 0.7 keeps it (its emission, which COLOR_0 does not tint).
TEST(GltfVertexColors, AlphaBelowTheMaskCutoffCutsTheSurface) {
  const std::string dir = temp_dir("alpha");
  const double emission[3] = {0.2, 0.4, 0.6};
  for (const float alpha : {0.3f, 0.7f}) {
    const json material = {{"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 0, 1}}, {"metallicFactor", 0}}},
                           {"emissiveFactor", {emission[0], emission[1], emission[2]}},
                           {"alphaMode", "MASK"},
                           {"alphaCutoff", 0.5},
                           {"doubleSided", true}};
    std::vector<float> rgba;
    for (int i = 0; i < 4; ++i) rgba.insert(rgba.end(), {0.5f, 0.5f, 0.5f, alpha});
    std::ofstream(dir + "/quad.gltf") << quad_gltf(material, rgba, 4);
    const Scene scene = quad_camera_scene(dir, "alpha.toml");
    const bool cut = alpha < 0.5f;
    EXPECT_EQ(features_for_scene(scene).alpha, cut) << "alpha " << alpha;
    for (const Way& way : {kWays[0], kWays[1]}) {
      const MeanVarianceImage image = render(scene, way, 4, 2, 3);
      for (size_t i = 0; i < image.mean.size(); ++i)
        EXPECT_NEAR(image.mean[i], cut ? 1.0 : emission[i % 3], 1e-4) << way.name << ": alpha " << alpha << " value " << i;
    }
  }
}

}  // namespace
}  // namespace clpt::test
