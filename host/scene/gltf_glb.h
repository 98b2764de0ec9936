// The binary glTF container (GLB, glTF 2.0 section 4.4): a 12-byte header, a JSON chunk, an
// optional BIN chunk. Checked here, strictly and before anything is parsed or allocated, as the
// Khronos validator checks it; tinygltf's own checks of the container are weaker.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace clpt {

// True when `bytes` start with the GLB magic "glTF" (whatever the file's extension says).
bool has_glb_magic(std::string_view bytes);

struct GlbChunks {
  std::string_view json;             // the JSON chunk, padding included
  std::optional<std::string_view> bin;  // the BIN chunk's payload, padding included
  std::vector<std::string> warnings;  // chunks of unknown types, which the format says to skip
};

// Splits a GLB file into its chunks (views into `bytes`). Throws GltfError naming "GLB header"
// or "GLB chunk N" when the magic, the version (2), the total length (the file's size, a multiple
// of 4), a chunk's length (a multiple of 4, inside the file) or the chunks' order (JSON first, at
// most one BIN, second) is wrong, or the JSON chunk is empty.
GlbChunks split_glb(std::string_view bytes);

// A well-formed GLB file holding `json` and, when given, `bin` (each padded to 4 bytes with
// spaces and zeros as the format says): what tinygltf is handed after split_glb (unknown chunks
// dropped), and what tests write.
std::string make_glb(std::string_view json, const std::optional<std::string_view>& bin);

}  // namespace clpt
