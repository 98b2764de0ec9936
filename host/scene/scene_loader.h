// Reading scene files (TOML, through toml++). The format is described in the README.
// Every error throws clpt::Error(ExitCode::BadScene) whose message starts with
// "FILE:LINE:COLUMN: KEY: " where KEY is the dotted key path (e.g. "sphere[3].radius").
#pragma once

#include <string>

#include "scene/scene.h"

namespace clpt {

// Loads, parses and validates the file; the returned scene is complete and safe to render.
Scene load_scene_file(const std::string& path);

// Same, from text already in memory; `name` stands for the file name in messages (tests, fuzzing).
Scene load_scene_string(const std::string& text, const std::string& name);

}  // namespace clpt
