// Reading scene files: TOML (through toml++; the format is described in the README), or a glTF 2.0
// file rendered whole (scene/gltf_loader.h, docs/gltf.md), told apart by the file's extension or
// the GLB magic. Every TOML error throws clpt::Error(ExitCode::BadScene) whose message starts with
// "FILE:LINE:COLUMN: KEY: " where KEY is the dotted key path (e.g. "sphere[3].radius"); a glTF
// error's with "FILE: ELEMENT: ".
#pragma once

#include <string>

#include "scene/gltf_loader.h"
#include "scene/scene.h"

namespace clpt {

// Loads, parses and validates the file; the returned scene is complete and safe to render.
// `view` applies to glTF files only (their camera and image size); a --camera for a TOML scene
// is a usage error.
Scene load_scene_file(const std::string& path, const GltfView& view = {});

// Same, from text already in memory; `name` stands for the file name in messages (tests, fuzzing).
Scene load_scene_string(const std::string& text, const std::string& name);

}  // namespace clpt
