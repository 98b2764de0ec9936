// Internal to host/scene: the seam between reading the TOML (scene_loader.cpp: structure, key
// names, value types, source positions) and judging the values (scene_validate.cpp: ranges,
// finiteness, an emitter present, a usable camera). Not for use outside host/scene.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>

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

// Shortest text that reads back as `value`: "-1", "0.7", "1e+300", "nan", "inf".
std::string format_number(double value);

// Range rule for the integer settings (image.width, image.height, render.spp, render.seed,
// render.max_bounces). Called by the loader as each is read, before it is narrowed to the
// Scene's field type: TOML integers are 64-bit and would otherwise wrap silently.
void check_integer_setting(const std::string& key, int64_t value, const SourcePosition& where);

// Every other semantic rule, on a scene whose structure and types the loader has checked.
// Throws on the first violation found (settings, camera, spheres in file order, then the
// scene-wide emitter rule).
void validate_scene(const Scene& scene, const SourceMap& sources);

}  // namespace clpt::scene_detail
