// Reading a glTF 2.0 file (.gltf JSON or .glb binary) into tinygltf's Model, with the checks that
// must come before tinygltf touches the data: the GLB container (gltf_glb.h), the JSON's nesting,
// `asset`, `extensionsRequired`, and every buffer, buffer view and image byte range, so that
// tinygltf never reads a file outside the glTF file's folder or a byte outside a buffer, and
// nothing is allocated beyond what the file and its buffers hold. What the Model then describes
// (accessors, nodes, meshes, materials, cameras, lights) is checked by gltf_loader.cpp's parts.
#pragma once

#include "scene/tinygltf_config.h"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace clpt {

// The extensions clpt reads (docs/gltf.md); a file may require these and no others.
// (KHR_texture_transform among them: textures, docs/textures.md.)
const std::vector<std::string>& gltf_supported_extensions();

struct GltfDocument {
  tinygltf::Model model;
  // FNV-1a 64 of the file's bytes chained over each external buffer's URI and bytes' hash, hex:
  // Scene::file_hash for a glTF scene.
  std::string hash;
  // The file's bytes plus its external buffers' bytes: what an accessor count without a buffer
  // view behind it is measured against (gltf_accessor.cpp).
  uint64_t total_bytes = 0;
  std::vector<std::string> warnings;  // "ELEMENT: MESSAGE", without the file
};

// A URI's %XX escapes decoded ('+' a space), and the check that it names a relative path inside
// the glTF file's folder (no scheme, no absolute path, no '..'): buffers' rules, which images
// follow too. Throw GltfError naming `element`.
std::string gltf_decode_uri(const std::string& uri, const std::string& element);
void gltf_check_relative(const std::string& path, const std::string& element);

// `bytes`: the file's contents; `path`: the file, whose folder holds its external buffers.
// Throws GltfError ("ELEMENT: MESSAGE") on anything malformed.
GltfDocument parse_gltf_document(std::string_view bytes, const std::string& path);

}  // namespace clpt
