// Internal to host/scene: the seam between reading the TOML (scene_loader.cpp: structure, key
// names, value types, source positions) and judging the values (scene_validate.cpp: ranges,
// finiteness, an emitter present, a usable camera). Not for use outside host/scene.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "scene/mesh_placement.h"
#include "scene/scene.h"

namespace clpt::scene_detail {

// Where each value present in the file sits, keyed by dotted path: "image.width",
// "sphere[2].material.ior", and the tables themselves ("camera", "sphere[2]"). The loader
// records; the validator looks up, so that its messages point at the offending value.
class SourceMap {
 public:
  explicit SourceMap(std::string file) : file_(std::move(file)) {}

  const std::string& file() const { return file_; }
  void record(const std::string& key, const SourcePosition& where);

  // The position of `key`. A value left at its default has none, so the position of its nearest
  // recorded enclosing table stands in ("camera.up" -> "camera"), and failing that file:1:1.
  SourcePosition find(const std::string& key) const;

 private:
  std::string file_;
  std::map<std::string, std::pair<int, int>> positions_;  // key -> (line, column)
};

// Throws clpt::Error(ExitCode::BadScene, "FILE:LINE:COLUMN: KEY: MESSAGE").
[[noreturn]] void fail(const SourcePosition& where, const std::string& key,
                       const std::string& message);

// An angle in degrees, rounded to 1e-9 degrees: what the file wrote (30, not 29.999999999999996)
// for an angle the loader converted to radians. For messages and the scene writer.
double degrees_of(double radians);

// Shortest text that reads back as `value`: "-1", "0.7", "1e+300", "nan", "inf".
std::string format_number(double value);

// Range rule for the integer settings (image.width, image.height, render.spp, render.seed,
// render.max_bounces). Called by the loader as each is read, before it is narrowed to the
// Scene's field type: TOML integers are 64-bit and would otherwise wrap silently.
void check_integer_setting(const std::string& key, int64_t value, const SourcePosition& where);

// An inline mesh as the [[mesh]] table writes it, before its values are judged: rows of the
// `vertices`, `normals`, `triangles` and `quads` arrays (the loader has checked that each row has
// 3, 3, 3 and 4 numbers, integers for the index lists, and recorded each row's position as
// "KEY.vertices[i]" etc.).
struct InlineMeshRows {
  std::vector<Vec3> vertices;
  std::vector<Vec3> normals;
  std::vector<std::array<double, 2>> uvs;  // texture coordinates, OBJ's convention ((0, 0) bottom-left)
  std::vector<std::array<int64_t, 3>> triangles;
  std::vector<std::array<int64_t, 4>> quads;
};

// Scale > 0 and finite per axis, rotation and translation finite. `key` is "mesh[i]".
void check_mesh_placement(const MeshPlacement& placement, const std::string& key, const SourceMap& sources);

// The rows' values judged (finite vertices, normals non-zero and one per vertex, indices in
// range, at least one triangle or quad) and turned into a LocalMesh, each quad (i, j, k, l) split
// into the triangles (i, j, k) and (i, k, l).
LocalMesh inline_local_mesh(const InlineMeshRows& rows, const std::string& key, const SourceMap& sources);

// After placement (mesh_placement.h): every position still finite (a huge scale can overflow)
// and at least one triangle left after `dropped` degenerate ones were removed.
void check_placed_mesh(const TriangleMesh& mesh, size_t dropped, const std::string& key, const SourceMap& sources);

// Every other semantic rule, on a scene whose structure and types the loader has checked.
// Throws on the first violation found (settings, camera, spheres in file order, mesh materials,
// then the scene-wide emitter rule: a sphere or a mesh must emit).
void validate_scene(const Scene& scene, const SourceMap& sources);

}  // namespace clpt::scene_detail
