// Mesh loading (issue 14 part A): [[mesh]] tables with mesh files (through assimp) and inline
// meshes, their placement checked numerically, quads split, normals carried and transformed,
// degenerate triangles dropped and counted, the scene hash over mesh files, scene-transform and
// the scene writer on meshes, and the safe-range warning on far triangles. The bad-input cases
// are tests/scenes/bad/mesh_*.toml (test_scene_loader.cpp runs them all).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "scene/mesh_file.h"
#include "scene/mesh_placement.h"
#include "scene/precision_range.h"
#include "scene/scene_loader.h"
#include "scene/scene_transform.h"
#include "scene/scene_writer.h"
#include "scene/vec3_ops.h"
#include "util/error.h"
#include "util/hash.h"

namespace clpt {
namespace {

const std::string kSourceDir = CLPT_SOURCE_DIR;
const std::string kMeshDir = kSourceDir + "/tests/scenes/meshes/";

// A scene with one emitting sphere and the given [[mesh]] table body (keys, one per line).
std::string scene_with_mesh(const std::string& mesh_body) {
  return "[camera]\nposition = [0.0, 1.0, 5.0]\nlook_at = [0.0, 1.0, 0.0]\n\n"
         "[[sphere]]\ncenter = [0.0, 10.0, 0.0]\nradius = 1.0\n"
         "material = { type = \"emitter\", emission = [1.0, 1.0, 1.0] }\n\n[[mesh]]\n" +
         mesh_body + "\nmaterial = { type = \"lambertian\", reflectance = [0.5, 0.5, 0.5] }\n";
}

// Expects parse_mesh_file(bytes, extension) to refuse the file with a message containing `message`.
void expect_refused(std::string_view bytes, const std::string& extension, const std::string& message) {
  try {
    parse_mesh_file(bytes, extension);
    ADD_FAILURE() << "loaded; expected the refusal '" << message << "'";
  } catch (const MeshFileError& e) {
    EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
  }
}

// The scene loaded from memory as if it were a file in tests/scenes/meshes/ (mesh files resolve there).
Scene load_mesh_scene(const std::string& mesh_body) {
  return load_scene_string(scene_with_mesh(mesh_body), kMeshDir + "mem.toml");
}

void expect_near(const Vec3& a, const Vec3& b, double tolerance = 1e-12) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], tolerance) << "component " << i;
}

TEST(MeshFile, ObjTetrahedronLoadsAsFourTrianglesWithoutNormals) {
  const Scene scene = load_mesh_scene("name = \"tet\"\nfile = \"tetrahedron.obj\"");
  ASSERT_EQ(scene.meshes.size(), 1u);
  const TriangleMesh& m = scene.meshes[0];
  EXPECT_EQ(m.name, "tet");
  EXPECT_EQ(m.file, "tetrahedron.obj");
  EXPECT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.triangles.size(), 4u);
  EXPECT_TRUE(m.normals.empty());  // the file has none, and none are generated
  EXPECT_EQ(m.where.line, 10);  // the [[mesh]] header
  for (const auto& t : m.triangles)
    for (uint32_t i : t) EXPECT_LT(i, m.positions.size());
  EXPECT_TRUE(scene.warnings.empty());
}

TEST(MeshFile, PlyQuadIsTriangulatedAndKeepsItsNormals) {
  const Scene scene = load_mesh_scene("file = \"quad_normals.ply\"");
  const TriangleMesh& m = scene.meshes[0];
  EXPECT_EQ(m.name, "mesh[0]");
  EXPECT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.triangles.size(), 2u);
  ASSERT_EQ(m.normals.size(), m.positions.size());
  for (const Vec3& n : m.normals) expect_near(n, {0, 0, 1});
}

TEST(MeshFile, LinesAreSkippedWithAWarningNamingTheTableAndFile) {
  const Scene scene = load_mesh_scene("file = \"triangle_and_line.obj\"");
  EXPECT_EQ(scene.meshes[0].triangles.size(), 1u);
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_EQ(scene.warnings[0], kMeshDir + "mem.toml:11:8: mesh[0].file: triangle_and_line.obj: 1 point or line "
                                          "primitive(s) skipped (only triangles render)");
}

TEST(MeshFile, DegenerateTrianglesAreDroppedAndCounted) {
  const Scene scene = load_mesh_scene("name = \"two\"\nfile = \"one_degenerate.obj\"");
  EXPECT_EQ(scene.meshes[0].triangles.size(), 1u);
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_EQ(scene.warnings[0],
            kMeshDir + "mem.toml:10:1: mesh 'two': 1 of 2 triangles have zero area and were dropped");
}

TEST(MeshFile, ParsesFromMemoryWhatTheFileHolds) {
  const std::string obj = "v 0 0 0\nv 2 0 0\nv 0 2 0\nvn 0 0 1\nf 1//1 2//1 3//1\n";
  const MeshFileContents c = parse_mesh_file(obj, "obj");
  ASSERT_EQ(c.mesh.triangles.size(), 1u);
  ASSERT_EQ(c.mesh.normals.size(), c.mesh.positions.size());
  EXPECT_THROW(parse_mesh_file("", "obj"), MeshFileError);
  EXPECT_THROW(parse_mesh_file("v 0 0 0\nv 1 0 0\nv 0 inf 0\nf 1 2 3\n", "obj"), MeshFileError);
  EXPECT_THROW(parse_mesh_file("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 0\nf 1//1 2//1 3//1\n", "obj"), MeshFileError);
  // assimp 5.2 hangs on a PLY header without an end_header line; clpt refuses it first, also
  // when the word only appears inside a comment.
  EXPECT_THROW(parse_mesh_file("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n0\n", "ply"), MeshFileError);
  EXPECT_THROW(parse_mesh_file("ply\ncomment no end_header here\nelement vertex 1\nproperty float x\n0\n", "ply"),
               MeshFileError);
  // Nor does assimp see the word when a vertical tab follows it (it hung on this very header).
  EXPECT_THROW(parse_mesh_file("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                               "property float z\nend_header\v0 0 0\n1 0 0\n0 1 0\n", "ply"),
               MeshFileError);
  // A PLY header with bytes that are not ASCII text made assimp abort on an internal assertion.
  EXPECT_THROW(parse_mesh_file("ply\nformat ascii 1.0\nelement vertex 3\nproperty fl\xff\xffoat x\nend_header\n0\n1\n2\n", "ply"),
               MeshFileError);
  // A file is read as what its extension says: a PLY body under another extension is refused,
  // never handed to the PLY reader past the PLY checks (a headerless one named .glb corrupted
  // assimp's heap).
  const std::string headerless_ply = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nelement face ement vertex 4\npro\n0 1 0 0 0 1\n4 0 1 2 3\n";
  for (const char* other : {"glb", "gltf", "obj", "stl"}) EXPECT_THROW(parse_mesh_file(headerless_ply, other), MeshFileError) << other;
  const std::string square_ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_EQ(parse_mesh_file(square_ply, "ply").mesh.triangles.size(), 1u);
  EXPECT_THROW(parse_mesh_file(square_ply, "glb"), MeshFileError);
  // A face with no indices: refused, naming it (assimp's triangulation aborted the process on a
  // mesh whose faces were all empty).
  const std::string empty_face_ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0\n";
  expect_refused(empty_face_ply, "ply", "face 0 of mesh 0 has no vertex indices");
  // A PLY header is checked against the format's grammar before assimp reads it (mangled lines
  // made its reader write past its buffers), naming the line; comments, obj_info, CRLF line ends
  // and blank lines are PLY.
  expect_refused("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\npropertyformat binary_big_endian 1.0blue\nend_header\n0\n1\n2\n", "ply", "line 5 of the PLY header is not a PLY header line: 'propertyformat binary_big_endian 1.0blue'");
  for (const char* bad : {"ply\nformat ascii 2.0\n", "ply\nformat ascii 1.0\nproperty float x\n", "ply\nformat ascii 1.0\nelement vertex -3\n",
                          "ply\nformat ascii 1.0\nelement vertex 3\nproperty list uchar vertex_indices\n", "ply\nformat ascii 1.0\nelement vertex 3\nprope\n"})
    EXPECT_THROW(parse_mesh_file(std::string(bad) + "end_header\n0 0 0\n", "ply"), MeshFileError) << bad;
  const std::string crlf_ply = "ply\r\nformat ascii 1.0\r\ncomment made by hand\r\nobj_info none\r\n\r\nelement vertex 3\r\nproperty float32 x\r\nproperty float32 y\r\nproperty float32 z\r\nelement face 1\r\nproperty list uint8 int32 vertex_indices\r\nend_header\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1 2\r\n";
  EXPECT_EQ(parse_mesh_file(crlf_ply, "ply").mesh.triangles.size(), 1u);
  // NUL bytes in an OBJ made assimp's OBJ reader crash.
  EXPECT_THROW(parse_mesh_file(std::string_view("v 0 0 0\nv 1 0 0\0\nv 0 1 0\nf 1 2 3\n", 33), "obj"), MeshFileError);
  // mtllib lines are not given to assimp (one followed by "map_K" crashed it); the mesh loads.
  EXPECT_EQ(parse_mesh_file("mtllib 8\nmap_Kne\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "obj").mesh.triangles.size(), 1u);
  EXPECT_THROW(mesh_file_extension("a.fbx"), MeshFileError);
  EXPECT_EQ(mesh_file_extension("dir.x/A.OBJ"), "obj");
}

// assimp allocates what a PLY header declares before it reads the body (a 2 kB file declaring
// 33,333,324 vertices ran the fuzzer out of memory), so clpt refuses a header whose elements
// cannot fit in the bytes after it, counting each value's least size, and names the element.
// The bound is the least size, so a file holding exactly what it declares loads, in either format.
TEST(MeshFile, RefusesAPlyHeaderDeclaringMoreThanItsBodyHolds) {
  const std::string ascii_header = "ply\nformat ascii 1.0\nelement vertex 33333324\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  expect_refused(ascii_header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "ply", "line 3 of the PLY header declares 33333324 'vertex' elements, more than the 27 bytes");
  // ASCII written as tightly as it can be: one-digit values, single separators, no newline at the end.
  const std::string tight = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2";
  EXPECT_EQ(parse_mesh_file(tight, "ply").mesh.triangles.size(), 1u);
  // Binary: 3 vertices of 3 floats and one face (a uchar count, 3 ints) is 49 bytes after the header.
  auto binary_ply = [](int vertex_count) {
    std::string out = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(vertex_count) +
                      "\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    auto put = [&out](const void* bytes, size_t size) { out.append(static_cast<const char*>(bytes), size); };
    const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const unsigned char count = 3;
    const int32_t indices[3] = {0, 1, 2};  // little-endian on every machine clpt is built for
    put(xyz, sizeof xyz);
    put(&count, 1);
    put(indices, sizeof indices);
    return out;
  };
  EXPECT_EQ(parse_mesh_file(binary_ply(3), "ply").mesh.triangles.size(), 1u);
  expect_refused(binary_ply(5), "ply", "line 3 of the PLY header declares 5 'vertex' elements");
  // An element with a count and no properties would need no bytes at all; it is refused.
  expect_refused("ply\nformat ascii 1.0\nelement vertex 33333324\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n", "ply", "line 3 of the PLY header declares element 'vertex' without properties");
}

TEST(MeshFile, RefusesWhatIsNotARegularFile) {
  EXPECT_THROW(read_mesh_file(kMeshDir), MeshFileError);
  EXPECT_THROW(read_mesh_file(kMeshDir + "no_such.obj"), MeshFileError);
  EXPECT_EQ(read_mesh_file(kMeshDir + "tetrahedron.obj").size(), std::filesystem::file_size(kMeshDir + "tetrahedron.obj"));
}

// ---- Placement ---------------------------------------------------------------------------------

// scale, then x, y, z rotations, then translate, checked on the tetrahedron's unit vertices:
// scale [2, 3, 4] then 90 degrees about z maps (1,0,0) -> (0,2,0), (0,1,0) -> (-3,0,0).
TEST(MeshPlacement, ScaleThenRotateThenTranslate) {
  const Scene scene = load_mesh_scene(
      "file = \"tetrahedron.obj\"\nscale = [2.0, 3.0, 4.0]\nrotate_deg = [0.0, 0.0, 90.0]\ntranslate = [10.0, 20.0, 30.0]");
  const TriangleMesh& m = scene.meshes[0];
  ASSERT_EQ(m.positions.size(), 4u);
  // assimp numbers joined vertices in the order faces first use them: find each by value.
  for (const Vec3& expected : {Vec3{10, 20, 30}, Vec3{10, 22, 30}, Vec3{7, 20, 30}, Vec3{10, 20, 34}}) {
    double closest = 1e300;
    for (const Vec3& p : m.positions) closest = std::min(closest, length(sub(p, expected)));
    EXPECT_LT(closest, 1e-12) << expected[0] << " " << expected[1] << " " << expected[2];
  }
}

// x first, then y: (0,1,0) -> 90 about x -> (0,0,1) -> 90 about y -> (1,0,0). In the other
// order it would go to (0,0,1)... so the order is observable.
TEST(MeshPlacement, RotatesAboutXThenYThenZ) {
  MeshPlacement p;
  p.rotate_deg = {90, 90, 0};
  expect_near(place_point(p, {0, 1, 0}), {1, 0, 0});
  p.rotate_deg = {0, 90, 90};  // y then z: (1,0,0) -> (0,0,-1) -> (0,0,-1)
  expect_near(place_point(p, {1, 0, 0}), {0, 0, -1});
  p.rotate_deg = {0, 0, 90};
  expect_near(place_point(p, {1, 0, 0}), {0, 1, 0});
}

// A normal follows the inverse transpose: the plane x + y = 1 scaled by [2, 1, 1] becomes
// x / 2 + y = 1, whose normal is (1/2, 1, 0) normalised, not the scaled (2, 1, 0).
TEST(MeshPlacement, NormalsFollowTheInverseTranspose) {
  MeshPlacement p;
  p.scale = {2, 1, 1};
  expect_near(place_normal(p, {1, 1, 0}), normalize(Vec3{0.5, 1, 0}));
  p.rotate_deg = {0, 0, 90};
  expect_near(place_normal(p, {1, 1, 0}), normalize(Vec3{-1, 0.5, 0}));
}

TEST(MeshPlacement, UniformNumberScaleEqualsTheArray) {
  const Scene a = load_mesh_scene("file = \"tetrahedron.obj\"\nscale = 2.5");
  const Scene b = load_mesh_scene("file = \"tetrahedron.obj\"\nscale = [2.5, 2.5, 2.5]");
  EXPECT_EQ(a.meshes[0].positions, b.meshes[0].positions);
  EXPECT_EQ(a.meshes[0].placement.scale, (Vec3{2.5, 2.5, 2.5}));
}

// ---- Inline meshes -------------------------------------------------------------------------------

TEST(InlineMesh, QuadsSplitIntoTwoTrianglesSharingTheDiagonal) {
  const Scene scene = load_mesh_scene(
      "vertices = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1]]\nquads = [[0, 1, 2, 3]]\ntriangles = [[0, 1, 4]]");
  const TriangleMesh& m = scene.meshes[0];
  EXPECT_TRUE(m.file.empty());
  EXPECT_TRUE(m.file_hash.empty());
  ASSERT_EQ(m.triangles.size(), 3u);
  EXPECT_EQ(m.triangles[0], (std::array<uint32_t, 3>{0, 1, 4}));  // triangles first, then quads
  EXPECT_EQ(m.triangles[1], (std::array<uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(m.triangles[2], (std::array<uint32_t, 3>{0, 2, 3}));
}

TEST(InlineMesh, NormalsAreNormalisedAndRotated) {
  const Scene scene = load_mesh_scene(
      "vertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\nnormals = [[0, 0, 2], [0, 0, 2], [0, 0, 2]]\n"
      "triangles = [[0, 1, 2]]\nrotate_deg = [90.0, 0.0, 0.0]");
  const TriangleMesh& m = scene.meshes[0];
  ASSERT_EQ(m.normals.size(), 3u);
  for (const Vec3& n : m.normals) expect_near(n, {0, -1, 0});  // +z rotated 90 degrees about x
}

TEST(InlineMesh, ASceneOfOnlyMeshesWithAnEmittingMeshLoads) {
  const std::string text =
      "[camera]\nposition = [0.0, 0.0, 5.0]\nlook_at = [0.0, 0.0, 0.0]\n[[mesh]]\n"
      "vertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\ntriangles = [[0, 1, 2]]\n"
      "material = { type = \"emitter\", emission = [1.0, 2.0, 3.0] }\n";
  const Scene scene = load_scene_string(text, "mem.toml");
  EXPECT_TRUE(scene.spheres.empty());
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.meshes[0].material.type, MaterialType::Emitter);
  EXPECT_EQ(scene.file_hash, hex64(fnv1a64(text)));  // inline meshes: the TOML is all there is
}

// ---- Scene hash over mesh files --------------------------------------------------------------------

TEST(MeshHash, TheSceneHashChangesWithTheMeshFileAlone) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "clpt_mesh_hash_test";
  std::filesystem::create_directories(dir);
  const std::string scene_path = (dir / "s.toml").string();
  std::ofstream(scene_path) << scene_with_mesh("file = \"m.obj\"");
  const auto write_mesh = [&](const char* third_vertex) {
    std::ofstream(dir / "m.obj") << "v 0 0 0\nv 1 0 0\n" << third_vertex << "\nf 1 2 3\n";
  };
  write_mesh("v 0 1 0");
  const Scene a = load_scene_file(scene_path);
  write_mesh("v 0 2 0");
  const Scene b = load_scene_file(scene_path);
  std::filesystem::remove_all(dir);
  EXPECT_NE(a.meshes[0].file_hash, b.meshes[0].file_hash);
  EXPECT_NE(a.file_hash, b.file_hash);
  EXPECT_NE(a.file_hash, hex64(fnv1a64(scene_with_mesh("file = \"m.obj\""))));  // not the TOML's alone
  EXPECT_EQ(a.meshes[0].file_hash, hex64(fnv1a64("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")));
}

// ---- scene-transform and the writer ----------------------------------------------------------------

// A file mesh transformed and written is the same file with the composed placement; loaded
// back it has the transformed world positions. An inline mesh is written inline.
TEST(MeshTransform, WrittenTransformedMeshesLoadBackAtTheTransformedPositions) {
  const Scene original = load_mesh_scene(
      "file = \"tetrahedron.obj\"\nscale = [2.0, 1.0, 0.5]\nrotate_deg = [10.0, 20.0, 30.0]\ntranslate = [1.0, 2.0, 3.0]");
  const Scene moved = translate_scene(scale_scene(original, 1.5e-3), {1e4, -7, 0.25});
  const std::string out_dir = kSourceDir + "/tests";  // a different directory from the scene's
  const Scene back = load_scene_string(scene_to_toml(moved, "", out_dir + "/written.toml"), out_dir + "/written.toml");
  ASSERT_EQ(back.meshes.size(), 1u);
  EXPECT_EQ(back.meshes[0].file, "scenes/meshes/tetrahedron.obj");
  ASSERT_EQ(back.meshes[0].positions.size(), original.meshes[0].positions.size());
  for (size_t i = 0; i < original.meshes[0].positions.size(); ++i) {
    const Vec3 expected = add(scale(original.meshes[0].positions[i], 1.5e-3), Vec3{1e4, -7, 0.25});
    expect_near(back.meshes[0].positions[i], expected, 1e-11);
    expect_near(moved.meshes[0].positions[i], expected, 1e-11);
  }

  const Scene inline_mesh = load_mesh_scene(
      "vertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\nnormals = [[0, 0, 1], [0, 0, 1], [0, 0, 1]]\n"
      "triangles = [[0, 1, 2]]\ntranslate = [0.0, 0.0, 1.0]");
  const Scene doubled = scale_scene(inline_mesh, 2);
  const Scene inline_back = load_scene_string(scene_to_toml(doubled), "written.toml");
  EXPECT_TRUE(inline_back.meshes[0].file.empty());
  EXPECT_EQ(inline_back.meshes[0].positions, doubled.meshes[0].positions);
  EXPECT_EQ(inline_back.meshes[0].positions[1], (Vec3{2, 0, 2}));
  EXPECT_EQ(inline_back.meshes[0].normals, doubled.meshes[0].normals);
  EXPECT_EQ(inline_back.meshes[0].triangles, doubled.meshes[0].triangles);
}

TEST(MeshTransform, EmissionScalesOnEmittingMeshes) {
  Scene scene = load_mesh_scene("file = \"tetrahedron.obj\"");
  scene.meshes[0].material.type = MaterialType::Emitter;
  scene.meshes[0].material.emission = {1, 2, 3};
  EXPECT_EQ(scale_emission(scene, 2).meshes[0].material.emission, (Vec3{2, 4, 6}));
}

// ---- The safe-range warning ------------------------------------------------------------------------

// A unit tetrahedron 1e3 from the camera is in range for the robust preset (rho ~ 1e-4); 1e6
// away it is not (rho ~ 0.1 > 1.2e-2), and --precision double is suggested.
TEST(MeshPrecision, FarTrianglesAreWarnedAbout) {
  const Scene near = load_mesh_scene("file = \"tetrahedron.obj\"\ntranslate = [0.0, 0.0, -1000.0]");
  EXPECT_TRUE(precision_range_warnings(near, Precision::Robust).empty());
  const Scene far = load_mesh_scene("name = \"far\"\nfile = \"tetrahedron.obj\"\ntranslate = [0.0, 0.0, -1000000.0]");
  const auto estimates = estimate_mesh_precision(far, Precision::Robust);
  ASSERT_EQ(estimates.size(), 1u);
  EXPECT_GT(estimates[0].relative_error, proven_relative_error(Precision::Robust));
  const auto warnings = precision_range_warnings(far, Precision::Robust);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("mesh 'far': triangle"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("render with --precision double"), std::string::npos) << warnings[0];
}

}  // namespace
}  // namespace clpt
