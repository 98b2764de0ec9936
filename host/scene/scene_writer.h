// Scene -> TOML text in the format scene_loader reads (README "Scene format"), written with
// toml++. Numbers are written so that they read back as the same doubles, so a scene written and
// loaded again is the same scene.
#pragma once

#include <string>

#include "scene/scene.h"

namespace clpt {

// `header`: comment lines put before the tables (each line is prefixed with "# ").
std::string scene_to_toml(const Scene& scene, const std::string& header = "");

// Writes scene_to_toml() to `path` atomically; throws Error(OutputError) naming the path.
void write_scene_file(const std::string& path, const Scene& scene, const std::string& header = "");

}  // namespace clpt
