// Scene -> TOML text in the format scene_loader reads (README "Scene format"), written with
// toml++. Numbers are written so that they read back as the same doubles, so a scene written and
// loaded again is the same scene.
#pragma once

#include <string>

#include "scene/scene.h"

namespace clpt {

// `header`: comment lines put before the tables (each line is prefixed with "# ").
// `written_as`: the path the text is for. A mesh read from a file is written as that file (named
// relative to written_as's directory, or absolute where no relative name exists) with its
// composed placement; a mesh written inline is written inline, its world positions and normals
// as they are, with no placement.
// A scene with glTF content (a glTF file rendered whole, or a TOML scene's [[gltf]] tables) is
// refused with Error(Usage) naming the file: its meshes and lights would have to be written back
// as the [[gltf]] tables they came from, which the writer does not do yet (docs/gltf.md).
std::string scene_to_toml(const Scene& scene, const std::string& header = "", const std::string& written_as = "");

// Writes scene_to_toml() to `path` atomically; throws Error(OutputError) naming the path.
void write_scene_file(const std::string& path, const Scene& scene, const std::string& header = "");

}  // namespace clpt
