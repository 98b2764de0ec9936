// glTF scenes (issue 33, the scene layer; docs/gltf.md): files built in the test (gltf_builder.h)
// loaded through load_gltf_scene, every expectation computed here from the transform or the
// specification's rule, not from a run of clpt; Debian's assimp-testmodels glTF files against
// counts read from their own JSON; the TOML [[gltf]] table; malformed files refused with the
// element named (tests/gltf_bad_cli.sh throws a larger corpus at `clpt render`).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "gltf_builder.h"
#include "scene/environment.h"
#include "scene/gltf_error.h"
#include "scene/gltf_glb.h"
#include "scene/gltf_loader.h"
#include "scene/scene_image.h"
#include "scene/scene_loader.h"
#include "scene/scene_transform.h"
#include "scene/scene_writer.h"
#include "scene/vec3_ops.h"
#include "util/error.h"

namespace clpt {
namespace {

using nlohmann::json;
using test::GltfBuilder;

constexpr double kPi = 3.14159265358979323846;
const std::string kModels = "/usr/share/assimp/models/glTF2/";

// A triangle in the z = 0 plane, counter-clockwise seen from +z.
const std::vector<float> kTriangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};

std::string glb(const GltfBuilder& b) {
  return make_glb(b.json_text(), b.bin.empty() ? std::nullopt : std::optional<std::string_view>(b.bin));
}

Scene load(const GltfBuilder& b, const GltfView& view = {}) { return load_gltf_scene(glb(b), "mem.glb", view); }

// The message of the Error that `f` throws (with its exit code checked), or "" if none.
std::string error_of(const std::function<void()>& f, ExitCode code = ExitCode::BadScene) {
  try {
    f();
  } catch (const Error& e) {
    EXPECT_EQ(int(e.code()), int(code)) << e.what();
    return e.what();
  }
  return "";
}
std::string load_error(const GltfBuilder& b, const GltfView& view = {}) {
  return error_of([&] { load(b, view); });
}

void expect_near(const Vec3& a, const Vec3& b, double tolerance = 1e-6) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], tolerance) << "component " << i;
}

Vec3 face_normal(const TriangleMesh& m, size_t t) {
  const auto& tri = m.triangles[t];
  return normalize(cross(sub(m.positions[tri[1]], m.positions[tri[0]]), sub(m.positions[tri[2]], m.positions[tri[0]])));
}

size_t triangle_count(const std::vector<TriangleMesh>& meshes) {
  size_t n = 0;
  for (const TriangleMesh& m : meshes) n += m.triangles.size();
  return n;
}

bool has_warning(const Scene& scene, const std::string& part) {
  for (const std::string& w : scene.warnings)
    if (w.find(part) != std::string::npos) return true;
  return false;
}

// --- The container -------------------------------------------------------------------------

std::string glb_error(std::string bytes) {
  try {
    split_glb(bytes);
  } catch (const GltfError& e) {
    return e.what();
  }
  return "";
}

TEST(GltfGlb, RefusesMalformedContainers) {
  const std::string good = make_glb("{\"asset\":{\"version\":\"2.0\"}}", std::string("\1\2\3\4"));
  EXPECT_EQ(glb_error(good), "");
  std::string bad_magic = good;
  bad_magic[0] = 'x';
  EXPECT_NE(glb_error(bad_magic).find("GLB header: the magic"), std::string::npos);
  std::string version = good;
  version[4] = 1;
  EXPECT_NE(glb_error(version).find("GLB header: version 1"), std::string::npos);
  EXPECT_NE(glb_error(good.substr(0, good.size() - 4)).find("GLB header: the header gives a length"), std::string::npos);
  std::string truncated = good;
  truncated[8] = char(truncated.size() - 4);  // the header agrees with a file cut inside the BIN chunk
  EXPECT_NE(glb_error(truncated.substr(0, truncated.size() - 4)).find("GLB chunk 1: its length 4 runs past"),
            std::string::npos);
  std::string unaligned = good;
  unaligned[12] = char(unaligned[12] + 1);
  EXPECT_NE(glb_error(unaligned).find("GLB chunk 0: its length"), std::string::npos);
  std::string bin_first = good;
  std::memcpy(&bin_first[16], "BIN\0", 4);
  EXPECT_NE(glb_error(bin_first).find("GLB chunk 0: the first chunk must be JSON"), std::string::npos);
  std::string header_only = good.substr(0, 12);
  header_only[8] = 12, header_only[9] = 0;
  EXPECT_NE(glb_error(header_only).find("GLB header: the file has no chunks"), std::string::npos);
}

// --- Geometry ------------------------------------------------------------------------------

TEST(GltfLoader, TriangleWithTheDefaultMaterialAndFramingView) {
  GltfBuilder b;
  b.node({{"mesh", b.triangle_mesh(kTriangle)}});
  const Scene scene = load(b);
  ASSERT_EQ(scene.meshes.size(), 1u);
  const TriangleMesh& m = scene.meshes[0];
  EXPECT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.name, "meshes[0]/primitive 0");
  EXPECT_EQ(m.gltf_element, "nodes[0] meshes[0].primitives[0]");
  EXPECT_TRUE(m.normals.empty());  // flat: the geometric normal shades
  // The specification's default material.
  EXPECT_EQ(m.material.type, MaterialType::Pbr);
  expect_near(m.material.reflectance, {1, 1, 1});
  EXPECT_EQ(m.material.metallic, 1);
  EXPECT_EQ(m.material.roughness, 1);
  EXPECT_FALSE(m.material.double_sided);
  EXPECT_EQ(scene.settings.estimator, "nee");
  EXPECT_EQ(scene.settings.width, 640);
  EXPECT_EQ(scene.settings.height, 480);
  // Framing: the bounding sphere of [0,1]x[0,1]x[0,0] (centre (0.5,0.5,0), radius sqrt(2)/2) fits
  // the vertical field of view (narrower than the 4:3 horizontal one), seen from +z.
  const double radius = std::sqrt(2.0) / 2, half_fov = scene.camera.vertical_fov_deg * kPi / 360;
  expect_near(scene.camera.look_at, {0.5, 0.5, 0});
  expect_near(scene.camera.position, {0.5, 0.5, radius / std::sin(half_fov)});
  EXPECT_TRUE(has_warning(scene, "no camera"));
  // No light: `render` warns once its environment options are applied (unlit_scene_warning).
  EXPECT_FALSE(has_warning(scene, "no lights"));
  EXPECT_NE(unlit_scene_warning(scene).find("no lights"), std::string::npos);
  Scene lit = scene;
  lit.environment = Environment{};
  EXPECT_EQ(unlit_scene_warning(lit), "");
}

// A scene with no light of its own gets the default studio environment (docs/environment.md):
// an image, white, 1 at the zenith falling linearly in cos(theta) to 0.25 at the nadir, with a
// notice naming the scene; a lit scene is left alone; --environment none takes any environment away.
TEST(GltfLoader, UnlitSceneGetsTheDefaultEnvironment) {
  GltfBuilder b;
  b.node({{"mesh", b.triangle_mesh(kTriangle)}});
  Scene scene = load(b);
  const std::string hash_before = scene.file_hash;
  const std::string notice = light_unlit_scene(scene);
  EXPECT_NE(notice.find("mem.glb: the scene has no lights"), std::string::npos) << notice;
  EXPECT_NE(notice.find("default studio environment"), std::string::npos) << notice;
  ASSERT_TRUE(scene.environment);
  const Environment& e = *scene.environment;
  ASSERT_TRUE(e.is_image());
  ASSERT_EQ(e.width, kDefaultEnvironmentWidth);
  ASSERT_EQ(e.height, kDefaultEnvironmentHeight);
  for (int row = 0; row < e.height; ++row) {
    const double y = std::cos(kPi * (row + 0.5) / e.height);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR((*e.rgb)[3 * size_t(row) * e.width + c], 0.625 + 0.375 * y, 1e-6);
  }
  EXPECT_NE(scene.file_hash, hash_before);  // checkpoints see the light
  EXPECT_EQ(unlit_scene_warning(scene), "");
  Scene again = scene;
  EXPECT_EQ(light_unlit_scene(again), "");  // lit now: unchanged
  EXPECT_EQ(again.environment->hash, e.hash);
  apply_environment_overrides(again, EnvironmentOverrides{std::string("none"), std::nullopt, std::nullopt});
  EXPECT_FALSE(again.environment);
  EXPECT_NE(unlit_scene_warning(again).find("will be black"), std::string::npos);
  EXPECT_THROW(apply_environment_overrides(again, EnvironmentOverrides{std::string("none"), 2.0, std::nullopt}), Error);
}

TEST(GltfLoader, TrsAndMatrixNodesComposeDownTheHierarchy) {
  // Parent: translate (1, 2, 3); child: rotate 90 degrees about +y, scale (2, 1, 1).
  // p -> T (R (S p)): (1,0,0) -> (2,0,0) -> (0,0,-2) -> (1,2,1).
  const double s = std::sqrt(0.5);
  for (bool matrix : {false, true}) {
    GltfBuilder b;
    json child = {{"mesh", b.triangle_mesh(kTriangle)}};
    if (matrix)  // column-major R S: columns R (2,0,0), R (0,1,0), R (0,0,1)
      child["matrix"] = {0, 0, -2, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 1};
    else
      child["rotation"] = {0, s, 0, s}, child["scale"] = {2, 1, 1};
    const int c = b.node(child, false);
    b.node({{"translation", {1, 2, 3}}, {"children", {c}}});
    const Scene scene = load(b);
    ASSERT_EQ(scene.meshes.size(), 1u) << "matrix " << matrix;
    expect_near(scene.meshes[0].positions[0], {1, 2, 3});
    expect_near(scene.meshes[0].positions[1], {1, 2, 1});
    expect_near(scene.meshes[0].positions[2], {1, 3, 3});
  }
}

TEST(GltfLoader, NonUniformScaleTiltsNormalsByTheInverseTranspose) {
  GltfBuilder b;
  const float n = float(std::sqrt(0.5));
  const int normals = b.accessor(std::vector<float>{n, n, 0, n, n, 0, n, n, 0}, 5126, "VEC3");
  b.node({{"scale", {2, 1, 1}},
          {"mesh", b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}, {"NORMAL", normals}}}})}});
  const Scene scene = load(b);
  // (1, 1, 0) under diag(2, 1, 1)^-T is (1/2, 1, 0).
  expect_near(scene.meshes[0].normals[0], normalize(Vec3{0.5, 1, 0}));
}

TEST(GltfLoader, MirroringTransformKeepsFacesOutward) {
  GltfBuilder b;
  const float n[] = {0, 0, 1};
  const int normals = b.accessor(std::vector<float>{n[0], n[1], n[2], n[0], n[1], n[2], n[0], n[1], n[2]}, 5126, "VEC3");
  const int mesh = b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}, {"NORMAL", normals}}}});
  b.node({{"mesh", mesh}, {"scale", {1, 1, -1}}});  // a mirror through z = 0: the face now looks along -z
  const Scene scene = load(b);
  expect_near(face_normal(scene.meshes[0], 0), {0, 0, -1});
  expect_near(scene.meshes[0].normals[0], {0, 0, -1});
}

TEST(GltfLoader, AMeshPlacedByTwoNodesIsTwoInstances) {
  GltfBuilder b;
  const int mesh = b.triangle_mesh(kTriangle);
  b.node({{"mesh", mesh}, {"translation", {5, 0, 0}}});
  b.node({{"mesh", mesh}, {"translation", {0, 0, -5}}});
  const Scene scene = load(b);
  ASSERT_EQ(scene.meshes.size(), 2u);
  expect_near(scene.meshes[0].positions[0], {5, 0, 0});
  expect_near(scene.meshes[1].positions[0], {0, 0, -5});
  EXPECT_EQ(scene.meshes[1].gltf_element, "nodes[1] meshes[0].primitives[0]");
}

TEST(GltfLoader, DegenerateTrianglesAreDroppedAndCounted) {
  GltfBuilder b;
  // The second triangle repeats a vertex: zero area.
  b.node({{"mesh", b.triangle_mesh({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0})}});
  const Scene scene = load(b);
  EXPECT_EQ(scene.meshes[0].triangles.size(), 1u);
  EXPECT_TRUE(has_warning(scene, "mem.glb: nodes[0] meshes[0].primitives[0]: mesh 'meshes[0]/primitive 0': 1 of 2 "
                                 "triangles have zero area and were dropped"));
}

TEST(GltfLoader, StripsAndFansMakeTheSpecificationsTriangles) {
  // Five vertices zig-zagging along x in the z = 0 plane.
  const std::vector<float> zigzag = {0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0, 2, 0, 0};
  GltfBuilder strip;
  strip.node({{"mesh", strip.triangle_mesh(zigzag, 5)}});
  const TriangleMesh s = load(strip).meshes[0];
  ASSERT_EQ(s.triangles.size(), 3u);
  EXPECT_EQ(s.triangles[0], (std::array<uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(s.triangles[1], (std::array<uint32_t, 3>{2, 1, 3}));  // odd: the first two swapped
  EXPECT_EQ(s.triangles[2], (std::array<uint32_t, 3>{2, 3, 4}));
  for (size_t t = 0; t < 3; ++t) EXPECT_NEAR(std::fabs(face_normal(s, t)[2]), 1, 1e-12);
  EXPECT_EQ(face_normal(s, 0)[2], face_normal(s, 1)[2]);  // one consistent winding
  // A fan around vertex 0 of a convex polygon.
  const std::vector<float> polygon = {0, 0, 0, 1, 0, 0, 2, 1, 0, 1, 2, 0, 0, 1, 0};
  GltfBuilder fan;
  fan.node({{"mesh", fan.triangle_mesh(polygon, 6)}});
  const TriangleMesh f = load(fan).meshes[0];
  ASSERT_EQ(f.triangles.size(), 3u);
  EXPECT_EQ(f.triangles[0], (std::array<uint32_t, 3>{1, 2, 0}));
  EXPECT_EQ(f.triangles[2], (std::array<uint32_t, 3>{3, 4, 0}));
  for (size_t t = 0; t < 3; ++t) expect_near(face_normal(f, t), {0, 0, 1});
}

TEST(GltfLoader, IndicesOfEveryComponentTypeAndTheirChecks) {
  const std::vector<float> quad = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  for (int type : {5121, 5123, 5125}) {
    GltfBuilder b;
    const int indices = type == 5121   ? b.accessor(std::vector<uint8_t>{0, 1, 2, 0, 2, 3}, type, "SCALAR")
                        : type == 5123 ? b.accessor(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}, type, "SCALAR")
                                       : b.indices({0, 1, 2, 0, 2, 3});
    b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", b.positions(quad)}}}, {"indices", indices}})}});
    const TriangleMesh m = load(b).meshes[0];
    ASSERT_EQ(m.triangles.size(), 2u) << type;
    EXPECT_EQ(m.triangles[1], (std::array<uint32_t, 3>{0, 2, 3}));
  }
  GltfBuilder out_of_range;
  out_of_range.node({{"mesh", out_of_range.mesh({{"attributes", {{"POSITION", out_of_range.positions(quad)}}},
                                                 {"indices", out_of_range.indices({0, 1, 4})}})}});
  EXPECT_EQ(load_error(out_of_range),
            "mem.glb: meshes[0].primitives[0].indices: index 2 is 4, out of range (the primitive has 4 vertices)");
  GltfBuilder restart;
  restart.node({{"mesh", restart.mesh({{"attributes", {{"POSITION", restart.positions(quad)}}},
                                       {"indices", restart.accessor(std::vector<uint8_t>{0, 1, 255}, 5121, "SCALAR")}})}});
  EXPECT_NE(load_error(restart).find("primitive-restart value 255"), std::string::npos);
}

TEST(GltfLoader, SparseAccessorsSubstituteIntoZerosOrData) {
  GltfBuilder b;
  // Three zero vertices (no buffer view), vertices 1 and 2 replaced.
  const int indices = b.view(std::string("\1\0\2\0", 4));
  std::vector<float> values = {1, 0, 0, 0, 1, 0};
  const int data = b.view(std::string(reinterpret_cast<const char*>(values.data()), values.size() * 4));
  const int positions = b.push("accessors", {{"componentType", 5126}, {"count", 3}, {"type", "VEC3"},
                                             {"sparse", {{"count", 2},
                                                         {"indices", {{"bufferView", indices}, {"componentType", 5123}}},
                                                         {"values", {{"bufferView", data}}}}}});
  b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", positions}}}})}});
  const TriangleMesh m = load(b).meshes[0];
  expect_near(m.positions[0], {0, 0, 0});
  expect_near(m.positions[1], {1, 0, 0});
  expect_near(m.positions[2], {0, 1, 0});
  // Sparse indices must increase.
  b.bin.replace(0, 4, std::string("\2\0\1\0", 4));
  EXPECT_NE(load_error(b).find("accessors[0].sparse.indices: not strictly increasing at element 1"), std::string::npos);
}

TEST(GltfLoader, TexcoordsOfEveryComponentTypeAreNormalised) {
  for (int type : {5126, 5121, 5123}) {
    GltfBuilder b;
    const int uv = type == 5126   ? b.accessor(std::vector<float>{0.2f, 1, 0, 0, 1, 0.5f}, type, "VEC2")
                   : type == 5121 ? b.accessor(std::vector<uint8_t>{51, 255, 0, 0, 255, 0}, type, "VEC2", true)
                                  : b.accessor(std::vector<uint16_t>{13107, 65535, 0, 0, 65535, 0}, type, "VEC2", true);
    b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}, {"TEXCOORD_0", uv}}}})}});
    const TriangleMesh m = load(b).meshes[0];
    ASSERT_EQ(m.uvs.size(), 3u) << type;
    EXPECT_NEAR(m.uvs[0][0], 0.2, 1e-6) << type;
    EXPECT_NEAR(m.uvs[0][1], 0.0, 1e-12) << type;  // glTF's v = 1 (the image's bottom) is OBJ's 0
    EXPECT_NEAR(m.uvs[1][1], 1.0, 1e-12) << type;
    EXPECT_NEAR(m.uvs[2][0], 1.0, 1e-12) << type;
  }
  GltfBuilder unnormalised;  // integer texture coordinates must be normalised
  const int uv = unnormalised.accessor(std::vector<uint8_t>{0, 0, 1, 0, 0, 1}, 5121, "VEC2");
  unnormalised.node({{"mesh", unnormalised.mesh({{"attributes", {{"POSITION", unnormalised.positions(kTriangle)},
                                                                 {"TEXCOORD_0", uv}}}})}});
  EXPECT_NE(load_error(unnormalised).find("attributes.TEXCOORD_0: integer components must be normalized here"),
            std::string::npos);
}

TEST(GltfLoader, ByteStrideInterleavesAttributes) {
  GltfBuilder b;
  // position, normal, position, normal ...: 24 bytes a vertex.
  std::vector<float> interleaved;
  for (int v = 0; v < 3; ++v) {
    for (int i = 0; i < 3; ++i) interleaved.push_back(kTriangle[size_t(3 * v + i)]);
    for (float c : {0.f, 0.f, 1.f}) interleaved.push_back(c);
  }
  const int view = b.view(std::string(reinterpret_cast<const char*>(interleaved.data()), interleaved.size() * 4), 24);
  const int p = b.push("accessors", {{"bufferView", view}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}});
  const int n = b.push("accessors",
                       {{"bufferView", view}, {"byteOffset", 12}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}});
  b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", p}, {"NORMAL", n}}}})}});
  const TriangleMesh m = load(b).meshes[0];
  expect_near(m.positions[1], {1, 0, 0});
  expect_near(m.positions[2], {0, 1, 0});
  expect_near(m.normals[2], {0, 0, 1});
  // One more vertex would run past the view: 3 * 24 + 12 > 72.
  b.doc["accessors"][0]["count"] = 4;
  EXPECT_NE(load_error(b).find("accessors[0]: 4 elements of 12 bytes, 24 apart from byte 0, run past the end"),
            std::string::npos);
}

// --- Cameras -------------------------------------------------------------------------------

GltfBuilder two_cameras() {
  GltfBuilder b;
  b.node({{"mesh", b.triangle_mesh(kTriangle)}});
  b.push("cameras", {{"type", "perspective"}, {"name", "wide"},
                     {"perspective", {{"yfov", 1.0}, {"znear", 0.1}, {"aspectRatio", 2.0}}}});
  b.push("cameras", {{"type", "orthographic"}, {"name", "plan"},
                     {"orthographic", {{"xmag", 3.0}, {"ymag", 1.5}, {"znear", 0.0}, {"zfar", 10.0}}}});
  // Looking down -y from above (rotation -90 degrees about x), scaled: the scale must not leak.
  const double s = std::sqrt(0.5);
  b.node({{"camera", 1}, {"name", "top"}, {"translation", {0, 10, 0}}, {"rotation", {-s, 0, 0, s}}, {"scale", {3, 3, 3}}});
  b.node({{"camera", 0}, {"translation", {1, 2, 5}}});
  return b;
}

TEST(GltfCamera, FirstInNodeOrderOrTheOneNamedOrIndexed) {
  GltfBuilder b = two_cameras();
  const Scene first = load(b);  // nodes[1] (camera 1) comes before nodes[2] in the scene
  EXPECT_EQ(first.camera.projection, Projection::Orthographic);
  EXPECT_NEAR(first.camera.ortho_height, 3.0, 1e-12);
  expect_near(first.camera.position, {0, 10, 0});
  expect_near(sub(first.camera.look_at, first.camera.position), {0, -1, 0});
  expect_near(first.camera.up, {0, 0, -1});
  // 640 wide, the height from xmag / ymag = 2.
  EXPECT_EQ(first.settings.width, 640);
  EXPECT_EQ(first.settings.height, 320);
  for (const char* name : {"wide", "0"}) {
    const Scene wide = load(b, GltfView{name, std::nullopt, std::nullopt});
    EXPECT_EQ(wide.camera.projection, Projection::Perspective) << name;
    EXPECT_NEAR(wide.camera.vertical_fov_deg, 180 / kPi, 1e-9) << name;
    expect_near(wide.camera.position, {1, 2, 5});
    expect_near(sub(wide.camera.look_at, wide.camera.position), {0, 0, -1});
  }
  EXPECT_EQ(load(b, GltfView{"top", std::nullopt, std::nullopt}).camera.projection, Projection::Orthographic);
  const std::string unknown = error_of([&] { load(b, GltfView{"7", std::nullopt, std::nullopt}); }, ExitCode::Usage);
  EXPECT_EQ(unknown, "--camera 7: no camera of the scene has that index or name (the file's cameras: 0 'wide' "
                     "(nodes[2]), 1 'plan' (nodes[1]))");
}

TEST(GltfCamera, ImageSizeFollowsTheAspectRatioWhenOneSideIsGiven) {
  GltfBuilder b = two_cameras();
  const GltfView wide_only_height{"wide", std::nullopt, 100};
  EXPECT_EQ(load(b, wide_only_height).settings.width, 200);
  const GltfView wide_only_width{"wide", 300, std::nullopt};
  EXPECT_EQ(load(b, wide_only_width).settings.height, 150);
  const Scene both = load(b, GltfView{"wide", 64, 48});
  EXPECT_EQ(both.settings.width, 64);
  EXPECT_EQ(both.settings.height, 48);
  b.doc["cameras"][0]["perspective"].erase("aspectRatio");
  EXPECT_EQ(load(b, GltfView{"wide", std::nullopt, std::nullopt}).settings.height, 480);
}

TEST(GltfCamera, RangesOfTheSchema) {
  for (const auto& [key, value, message] :
       {std::tuple{"yfov", 0.0, "cameras[0].perspective.yfov: must be in (0, pi)"},
        std::tuple{"yfov", kPi, "cameras[0].perspective.yfov: must be in (0, pi)"},
        std::tuple{"znear", 0.0, "cameras[0].perspective.znear: must be > 0"},
        std::tuple{"aspectRatio", -1.0, "cameras[0].perspective.aspectRatio: must be > 0"}}) {
    GltfBuilder b = two_cameras();
    b.doc["cameras"][0]["perspective"][key] = value;
    EXPECT_NE(load_error(b).find(message), std::string::npos) << load_error(b);
  }
}

// --- Lights --------------------------------------------------------------------------------

GltfBuilder lit(const json& light, const json& node_extra = json::object()) {
  GltfBuilder b;
  b.node({{"mesh", b.triangle_mesh(kTriangle)}});
  b.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  b.doc["extensions"]["KHR_lights_punctual"]["lights"] = {light};
  json node = {{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}};
  node.update(node_extra);
  b.node(node);
  return b;
}

TEST(GltfLights, UnitsPositionsDirectionsConesAndRange) {
  const Scene point = load(lit({{"type", "point"}, {"color", {1, 0.5, 0}}, {"intensity", 683}, {"range", 4}},
                               {{"translation", {1, 2, 3}}}));
  ASSERT_EQ(point.lights.size(), 1u);
  EXPECT_EQ(point.lights[0].type, LightType::Point);
  expect_near(point.lights[0].intensity, {1, 0.5, 0}, 1e-12);  // 683 cd = 1 W/sr
  expect_near(point.lights[0].position, {1, 2, 3});
  EXPECT_EQ(point.lights[0].range, 4);
  EXPECT_EQ(point.lights[0].name, "lights[0]");
  EXPECT_FALSE(has_warning(point, "no lights"));
  // A directional light rotated 90 degrees about +x: its -z turns to +y... (R e_-z = (0, 1, 0)).
  const double s = std::sqrt(0.5);
  const Scene sun = load(lit({{"type", "directional"}, {"intensity", 2 * 683.0}}, {{"rotation", {s, 0, 0, s}}}));
  expect_near(sun.lights[0].direction, {0, 1, 0});
  expect_near(sun.lights[0].intensity, {2, 2, 2}, 1e-12);  // lux / 683 = W/m^2
  EXPECT_EQ(sun.lights[0].range, 0);
  const Scene spot = load(lit({{"type", "spot"}, {"spot", {{"innerConeAngle", 0.1}, {"outerConeAngle", 0.5}}}}));
  EXPECT_EQ(spot.lights[0].inner_cone_rad, 0.1);
  EXPECT_EQ(spot.lights[0].outer_cone_rad, 0.5);
  const Scene default_cone = load(lit({{"type", "spot"}, {"spot", json::object()}}));
  EXPECT_NEAR(default_cone.lights[0].outer_cone_rad, kPi / 4, 1e-15);
  for (const auto& [light, message] :
       {std::pair{json{{"type", "spot"}, {"spot", {{"innerConeAngle", 0.5}, {"outerConeAngle", 0.5}}}},
                  "KHR_lights_punctual.lights[0].spot: the cone angles must satisfy"},
        std::pair{json{{"type", "spot"}, {"spot", {{"outerConeAngle", 2.0}}}}, "lights[0].spot: the cone angles"},
        std::pair{json{{"type", "point"}, {"intensity", -1}}, "lights[0].intensity: must be >= 0"},
        std::pair{json{{"type", "point"}, {"color", {1, -0.5, 0}}}, "lights[0].color[1]: must be in [0, 1]"},
        std::pair{json{{"type", "point"}, {"range", 0}}, "lights[0].range: must be > 0"},
        std::pair{json{{"type", "area"}}, "lights[0].type: 'area'"}})
    EXPECT_NE(load_error(lit(light)).find(message), std::string::npos) << load_error(lit(light));
}

// --- Materials and extensions --------------------------------------------------------------

TEST(GltfMaterial, FactorsAndExtensions) {
  GltfBuilder b;
  b.push("materials", {{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.25, 1, 0.5}}, {"metallicFactor", 0.0},
                                                 {"roughnessFactor", 0.3}}},
                       {"emissiveFactor", {1, 0.5, 0}},
                       {"doubleSided", true},
                       {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4}}},
                                       {"KHR_materials_ior", {{"ior", 1.33}}},
                                       {"KHR_materials_transmission", {{"transmissionFactor", 0.75}}},
                                       {"KHR_materials_volume", {{"thicknessFactor", 0.2}, {"attenuationDistance", 3},
                                                                 {"attenuationColor", {0.9, 0.8, 0.7}}}}}}});
  b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}}, {"material", 0}})}});
  const Material m = load(b).meshes[0].material;
  expect_near(m.reflectance, {0.5, 0.25, 1}, 0);
  EXPECT_EQ(m.metallic, 0);
  EXPECT_EQ(m.roughness, 0.3);
  expect_near(m.emission, {4, 2, 0}, 0);
  EXPECT_TRUE(m.double_sided);
  EXPECT_EQ(m.ior, 1.33);
  EXPECT_EQ(m.transmission, 0.75);
  EXPECT_EQ(m.thickness, 0.2);
  EXPECT_EQ(m.attenuation_distance, 3);
  expect_near(m.attenuation_color, {0.9, 0.8, 0.7}, 0);
  b.doc["materials"][0]["pbrMetallicRoughness"]["roughnessFactor"] = 1.5;
  EXPECT_EQ(load_error(b), "mem.glb: materials[0].pbrMetallicRoughness.roughnessFactor: must be in [0, 1] (got 1.5)");
}

TEST(GltfExtensions, RequiredUnknownIsAnErrorUsedUnknownAWarning) {
  GltfBuilder b;
  b.node({{"mesh", b.triangle_mesh(kTriangle)}});
  b.doc["extensionsUsed"] = {"KHR_materials_clearcoat", "KHR_materials_ior", "KHR_texture_transform"};
  const Scene scene = load(b);
  EXPECT_TRUE(has_warning(scene, "extensionsUsed: ignored: KHR_materials_clearcoat, KHR_texture_transform"));
  b.doc["extensionsRequired"] = {"KHR_materials_ior", "KHR_draco_mesh_compression"};
  EXPECT_EQ(load_error(b),
            "mem.glb: extensionsRequired[1]: the file requires KHR_draco_mesh_compression, which clpt does not implement");
}

// --- Bad input -----------------------------------------------------------------------------

TEST(GltfBadInput, EachNamesTheElement) {
  const std::vector<std::pair<std::function<void(GltfBuilder&)>, std::string>> cases = {
      {[](GltfBuilder& b) { b.doc.erase("asset"); }, "mem.glb: asset: missing"},
      {[](GltfBuilder& b) { b.doc["asset"]["version"] = "1.0"; }, "mem.glb: asset.version: '1.0': clpt reads glTF 2.x"},
      {[](GltfBuilder& b) { b.doc["nodes"][0]["children"] = {0}; }, "mem.glb: nodes[0]: the node is its own ancestor"},
      {[](GltfBuilder& b) {
         b.push("nodes", {{"children", {2}}});
         b.push("nodes", {{"children", {1}}});
       },
       "mem.glb: nodes[2]: the node is its own ancestor"},
      {[](GltfBuilder& b) {
         b.push("nodes", {{"children", {0}}});
         b.push("nodes", {{"children", {0}}});
       },
       "mem.glb: nodes[2].children[0]: nodes[0] has two parents, nodes[1] and nodes[2]"},
      {[](GltfBuilder& b) { b.doc["nodes"][0]["rotation"] = {0, 0, 0, 0}; },
       "mem.glb: nodes[0].rotation: a rotation quaternion must have length 1"},
      {[](GltfBuilder& b) { b.doc["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1}; },
       "mem.glb: nodes[0].matrix: the matrix is singular"},
      {[](GltfBuilder& b) { b.doc["nodes"][0]["scale"] = {1, 0, 1}; }, "mem.glb: nodes[0].scale: a zero scale"},
      {[](GltfBuilder& b) { b.doc["accessors"][0]["count"] = 4; }, "mem.glb: accessors[0]: 4 elements of 12 bytes"},
      {[](GltfBuilder& b) { b.doc["accessors"][0]["type"] = "VEC2"; },
       "mem.glb: meshes[0].primitives[0].attributes.POSITION: the accessor's type must be VEC3 (accessors[0])"},
      {[](GltfBuilder& b) { b.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 9; },
       "mem.glb: meshes[0].primitives[0].attributes.POSITION: accessor 9 is out of range"},
      {[](GltfBuilder& b) { b.doc["bufferViews"][0]["byteLength"] = 400; }, "mem.glb: bufferViews[0]: bytes 0 to 400"},
      {[](GltfBuilder& b) {
         b.doc["accessors"][0].erase("bufferView");
         b.doc["accessors"][0]["count"] = 1000000000;
       },
       "mem.glb: accessors[0].count: 1000000000 elements without a buffer view, more than the file's"},
      {[](GltfBuilder& b) { b.bin.replace(0, 4, std::string("\0\0\xc0\x7f", 4)); },
       "mem.glb: accessors[0]: element 0 is not finite"},
      {[](GltfBuilder& b) { b.doc["scene"] = 3; }, "mem.glb: scene: 3 is out of range"},
      {[](GltfBuilder& b) { b.doc["accessors"][0]["byteOffset"] = -4; },
       "mem.glb: accessors[0].byteOffset: must be a non-negative integer (got -4)"},
      {[](GltfBuilder& b) { b.doc["nodes"][0]["mesh"] = 4294967296; },
       "mem.glb: nodes[0].mesh: must be an integer in [0, 2^31 - 1] (got 4294967296)"},
      {[](GltfBuilder& b) { b.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = "0"; },
       "mem.glb: meshes[0].primitives[0].attributes.POSITION: must be an integer"},
      {[](GltfBuilder& b) { b.doc["meshes"][0]["primitives"][0]["mode"] = 9; },
       "mem.glb: meshes[0].primitives[0].mode: 9 is not a glTF primitive mode"},
  };
  for (const auto& [mutate, message] : cases) {
    GltfBuilder b;
    b.node({{"mesh", b.triangle_mesh(kTriangle)}});
    mutate(b);
    const std::string error = load_error(b);
    EXPECT_EQ(error.substr(0, message.size()), message) << error;
  }
}

// --- Files: external buffers, URIs, hashes, [[gltf]] tables --------------------------------

struct TempDir {
  std::filesystem::path path;
  explicit TempDir(const std::string& name) : path(std::filesystem::temp_directory_path() / ("clpt_gltf_" + name)) {
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~TempDir() { std::filesystem::remove_all(path); }
  std::string write(const std::string& name, const std::string& bytes) const {
    std::ofstream(path / name, std::ios::binary) << bytes;
    return (path / name).string();
  }
};

TEST(GltfFiles, ExternalBuffersUrisAndTheHash) {
  TempDir dir("external");
  GltfBuilder b;
  b.node({{"mesh", b.triangle_mesh(kTriangle)}});
  dir.write("tri.bin", b.bin);
  const std::string file = dir.write("tri.gltf", b.json_text("tri.bin"));
  const Scene a = load_scene_file(file);
  EXPECT_EQ(triangle_count(a.meshes), 1u);
  std::string changed = b.bin;
  changed[0] = 1;  // the same size, other bytes: the hash must see it
  dir.write("tri.bin", changed);
  EXPECT_NE(load_scene_file(file).file_hash, a.file_hash);
  for (const auto& [uri, message] :
       {std::pair{"missing.bin", "buffers[0].uri: cannot open 'missing.bin': No such file or directory"},
        std::pair{"../tri.bin", "buffers[0].uri: '../tri.bin' leaves the glTF file's folder"},
        std::pair{"/etc/passwd", "buffers[0].uri: '/etc/passwd' is not a relative path"},
        std::pair{"data:application/octet-stream,abc", "buffers[0].uri: a data: URI must be base64"},
        std::pair{"data:application/octet-stream;base64,A!==", "buffers[0].uri: byte 1 of the base64 data is not base64"}}) {
    const std::string bad = dir.write("bad.gltf", b.json_text(uri));
    const std::string error = error_of([&] { load_scene_file(bad); });
    EXPECT_EQ(error.substr(0, bad.size() + 2 + std::string(message).size()), bad + ": " + message);
  }
  const Scene embedded = load_gltf_scene(b.gltf_embedded(), "embedded.gltf");
  expect_near(embedded.meshes[0].positions[2], {0, 1, 0});
}

TEST(GltfFiles, TomlGltfTablePlacesMeshesAndLights) {
  TempDir dir("table");
  GltfBuilder b = lit({{"type", "point"}, {"intensity", 683}}, {{"translation", {0, 1, 0}}});
  dir.write("model.glb", glb(b));
  const std::string toml = dir.write(
      "room.toml",
      "[camera]\nposition = [0, 0, 10]\nlook_at = [0, 0, 0]\n\n"
      "[[gltf]]\nfile = \"model.glb\"\nscale = 2\nrotate_deg = [0, 0, 90]\ntranslate = [10, 0, 0]\n");
  const Scene scene = load_scene_file(toml);
  ASSERT_EQ(scene.meshes.size(), 1u);
  // (1, 0, 0) scaled by 2, turned 90 degrees about z, moved by (10, 0, 0).
  expect_near(scene.meshes[0].positions[1], {10, 2, 0});
  EXPECT_EQ(scene.meshes[0].file, "model.glb");
  EXPECT_EQ(scene.meshes[0].placement.translate, (Vec3{10, 0, 0}));
  ASSERT_EQ(scene.lights.size(), 1u);
  expect_near(scene.lights[0].position, {8, 0, 0});  // (0, 1, 0) -> (0, 2, 0) -> (-2, 0, 0) -> (8, 0, 0)
  // Scene-transform cannot write glTF content back yet, and says so.
  EXPECT_NE(error_of([&] { scene_to_toml(scale_scene(scene, 2)); }, ExitCode::Usage).find("holds glTF content"),
            std::string::npos);
  // Errors carry the table's position, the key and the file.
  b.doc["nodes"][1]["rotation"] = {0, 0, 0, 2};
  dir.write("model.glb", glb(b));
  EXPECT_EQ(error_of([&] { load_scene_file(toml); }),
            toml + ":6:8: gltf[0].file: model.glb: nodes[1].rotation: a rotation quaternion must have length 1 (got 2.000000)");
}

TEST(GltfFiles, CameraOptionIsForGltfScenesOnly) {
  TempDir dir("toml_camera");
  const std::string toml = dir.write("s.toml", "[camera]\nposition = [0, 0, 1]\nlook_at = [0, 0, 0]\n");
  EXPECT_NE(error_of([&] { load_scene_file(toml, GltfView{"0", std::nullopt, std::nullopt}); }, ExitCode::Usage)
                .find("is a TOML scene"),
            std::string::npos);
}

// --- Debian's assimp-testmodels ------------------------------------------------------------

// Triangles a primitive makes, from the JSON alone (the specification's rule per mode).
size_t expected_triangles(const json& doc, const json& primitive) {
  const int mode = primitive.value("mode", 4);
  const size_t n = primitive.contains("indices") ? doc["accessors"][primitive["indices"].get<size_t>()]["count"].get<size_t>()
                                                 : doc["accessors"][primitive["attributes"]["POSITION"].get<size_t>()]["count"].get<size_t>();
  return mode == 4 ? n / 3 : mode == 5 || mode == 6 ? n - 2 : 0;
}

json read_json(const std::string& path) {
  std::ifstream in(path);
  return json::parse(in);
}

TEST(GltfDebianModels, PrimitiveModeSetLoadsWithTheExpectedTriangleCounts) {
  const std::string dir = kModels + "glTF-Asset-Generator/Mesh_PrimitiveMode/";
  if (!std::filesystem::exists(dir)) GTEST_SKIP() << "assimp-testmodels not installed";
  int files = 0;
  for (int i = 0; i <= 15; ++i) {
    const std::string file = dir + "Mesh_PrimitiveMode_" + (i < 10 ? "0" : "") + std::to_string(i) + ".gltf";
    const json doc = read_json(file);
    size_t expected = 0;
    for (const json& node : doc["nodes"])  // each file places each mesh once
      if (node.contains("mesh"))
        for (const json& p : doc["meshes"][node["mesh"].get<size_t>()]["primitives"]) expected += expected_triangles(doc, p);
    const GltfContents contents = load_gltf_contents(file, MeshPlacement{});
    EXPECT_EQ(triangle_count(contents.meshes), expected) << file;
    const bool skipped = expected == 0;
    bool warned = false;
    for (const std::string& w : contents.warnings) warned = warned || w.find("skipped (clpt renders triangles)") != std::string::npos;
    EXPECT_EQ(warned, skipped) << file;
    ++files;
  }
  EXPECT_EQ(files, 16);
}

TEST(GltfDebianModels, CamerasFileGivesItsFirstCameraAndTheOrthographicByIndex) {
  const std::string file = kModels + "cameras/Cameras.gltf";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "assimp-testmodels not installed";
  const json doc = read_json(file);
  const json& perspective = doc["cameras"][0]["perspective"];
  const json& translation = doc["nodes"][1]["translation"];
  const Scene scene = load_scene_file(file);
  EXPECT_NEAR(scene.camera.vertical_fov_deg, perspective["yfov"].get<double>() * 180 / kPi, 1e-9);
  expect_near(scene.camera.position, {translation[0], translation[1], translation[2]}, 1e-12);
  expect_near(sub(scene.camera.look_at, scene.camera.position), {0, 0, -1});
  EXPECT_EQ(scene.settings.width, 640);
  EXPECT_EQ(scene.settings.height, int(std::lround(640 / perspective["aspectRatio"].get<double>())));
  const Scene ortho = load_scene_file(file, GltfView{"1", std::nullopt, std::nullopt});
  EXPECT_EQ(ortho.camera.projection, Projection::Orthographic);
  EXPECT_NEAR(ortho.camera.ortho_height, 2 * doc["cameras"][1]["orthographic"]["ymag"].get<double>(), 1e-12);
}

// The image reader the loader decodes textures through, for tests about geometry: a grey 1 x 1
// image whatever the file (OpenImageIO's reader is tests/test_textures.cpp's).
SceneImagePixels grey_pixel(const std::string&) {
  SceneImagePixels p;
  p.width = p.height = 1;
  p.channels = 1;
  p.pixel_type = "uint8";
  p.pixels = {0.5f};
  return p;
}

TEST(GltfDebianModels, BinaryFilesLoadWithTheirAccessorsTriangleCounts) {
  set_scene_image_reader(&grey_pixel);  // BoxTextured's image; this test counts triangles
  for (const char* name : {"BoxTextured-glTF-Binary/BoxTextured.glb", "2CylinderEngine-glTF-Binary/2CylinderEngine.glb"}) {
    const std::string file = kModels + name;
    if (!std::filesystem::exists(file)) GTEST_SKIP() << "assimp-testmodels not installed";
    std::ifstream in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    uint32_t json_length = 0;
    std::memcpy(&json_length, bytes.data() + 12, 4);
    const json doc = json::parse(bytes.substr(20, json_length));
    // Every node placing a mesh, once each (neither file instances a node twice).
    size_t expected = 0;
    for (const json& node : doc["nodes"])
      if (node.contains("mesh"))
        for (const json& p : doc["meshes"][node["mesh"].get<size_t>()]["primitives"]) expected += expected_triangles(doc, p);
    const Scene scene = load_scene_file(file);
    size_t dropped = 0;  // degenerate triangles a warning reports ("N of M triangles have zero area")
    for (const std::string& w : scene.warnings)
      if (const size_t at = w.find("': "); at != std::string::npos && w.find("zero area and were dropped") != std::string::npos)
        dropped += std::stoul(w.substr(at + 3));
    EXPECT_EQ(triangle_count(scene.meshes) + dropped, expected) << name;
    EXPECT_GT(triangle_count(scene.meshes), 0u);
  }
  set_scene_image_reader(nullptr);
}

}  // namespace
}  // namespace clpt
