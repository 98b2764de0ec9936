// glTF 2.0 files as clpt scenes (docs/gltf.md): a .gltf/.glb file rendered whole
// (`clpt render x.glb`), or its scene placed among a TOML scene's objects by a [[gltf]] table.
// Every error is clpt::Error(ExitCode::BadScene, "FILE: ELEMENT: MESSAGE") with ELEMENT the glTF
// element at fault ("meshes[2].primitives[0].indices"); an unknown --camera is a usage error.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene.h"

namespace clpt {

// What the command line asks of a glTF scene's view (scene/gltf_camera.h applies it).
struct GltfView {
  std::optional<std::string> camera;  // --camera: an index into `cameras`, else a camera's or its node's name
  std::optional<int> width, height;   // --width, --height
};

// True when `path` ends in .gltf or .glb (any case) or `bytes` start with the GLB magic "glTF".
bool is_gltf_file(const std::string& path, std::string_view bytes);

// The file's scene (`scene`, else scenes[0]) as a Scene: meshes, lights, the camera and image
// size from `view`, RenderSettings' defaults but the `nee` estimator (punctual lights are reached
// by next-event estimation only), file_hash over the file and its buffers. `bytes` are the file's
// contents; `path` names it in messages and its folder holds the external buffers.
Scene load_gltf_scene(std::string_view bytes, const std::string& path, const GltfView& view = {});

// Where a scene (glTF, or TOML, whose loader refuses one without light), with the command line's
// environment applied, has no light at all (no punctual light, no emitting material, no
// environment): the warning `render` prints, naming the file; empty otherwise.
std::string unlit_scene_warning(const Scene& scene);

// What a TOML [[gltf]] table places: the glTF scene's meshes and lights (its cameras are
// ignored), each transformed by `placement` after the nodes' own transforms; TriangleMesh::
// placement is `placement`, TriangleMesh::file and `where` are left for the caller. Reads the
// file at `path`; throws GltfError (scene/gltf_error.h: "ELEMENT: MESSAGE", no file name).
struct GltfContents {
  std::vector<TriangleMesh> meshes;
  std::vector<PunctualLight> lights;
  std::vector<std::string> warnings;  // "ELEMENT: MESSAGE"
  std::string hash;                   // the file's and its buffers' (GltfDocument::hash)
  std::vector<TextureImage> images;   // its materials' images (their TextureRefs index these)
};
GltfContents load_gltf_contents(const std::string& path, const MeshPlacement& placement);

}  // namespace clpt
