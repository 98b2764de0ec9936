// GLB container (gltf_glb.h): header and chunks, little-endian 32-bit fields.
#include "scene/gltf_glb.h"

#include <cstdint>
#include <cstdio>

#include "scene/gltf_error.h"

namespace clpt {
namespace {

constexpr uint32_t kMagic = 0x46546C67;      // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr uint32_t kChunkBin = 0x004E4942;   // "BIN\0"
constexpr size_t kHeaderBytes = 12, kChunkHeaderBytes = 8;

uint32_t read_u32(std::string_view bytes, size_t at) {
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data() + at);
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

void append_u32(std::string& out, uint32_t value) {
  for (int i = 0; i < 4; ++i) out.push_back(char((value >> (8 * i)) & 0xFF));
}

std::string hex(uint32_t value) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%08X", value);
  return text;
}

void check_header(std::string_view bytes) {
  if (bytes.size() < kHeaderBytes)
    gltf_fail("GLB header", "the file is " + std::to_string(bytes.size()) + " bytes, shorter than the 12-byte header");
  if (read_u32(bytes, 0) != kMagic) gltf_fail("GLB header", "the magic is not 'glTF'");
  const uint32_t version = read_u32(bytes, 4);
  if (version != 2) gltf_fail("GLB header", "version " + std::to_string(version) + " (clpt reads glTF 2)");
  const uint32_t length = read_u32(bytes, 8);
  if (length != bytes.size())
    gltf_fail("GLB header", "the header gives a length of " + std::to_string(length) + " bytes, the file has " +
                                std::to_string(bytes.size()));
  if (length % 4 != 0) gltf_fail("GLB header", "the length " + std::to_string(length) + " is not a multiple of 4");
}

}  // namespace

bool has_glb_magic(std::string_view bytes) { return bytes.size() >= 4 && read_u32(bytes, 0) == kMagic; }

GlbChunks split_glb(std::string_view bytes) {
  check_header(bytes);
  GlbChunks out;
  bool json_seen = false;
  size_t index = 0;
  for (size_t at = kHeaderBytes; at < bytes.size(); ++index) {
    const std::string element = "GLB chunk " + std::to_string(index);
    if (bytes.size() - at < kChunkHeaderBytes)
      gltf_fail(element, "truncated: " + std::to_string(bytes.size() - at) + " bytes left for its 8-byte header");
    const uint32_t length = read_u32(bytes, at), type = read_u32(bytes, at + 4);
    at += kChunkHeaderBytes;
    if (length % 4 != 0) gltf_fail(element, "its length " + std::to_string(length) + " is not a multiple of 4");
    if (length > bytes.size() - at)
      gltf_fail(element, "its length " + std::to_string(length) + " runs past the end of the file (" +
                             std::to_string(bytes.size() - at) + " bytes left)");
    const std::string_view data = bytes.substr(at, length);
    at += length;
    if (index == 0 && type != kChunkJson) gltf_fail(element, "the first chunk must be JSON (its type is " + hex(type) + ")");
    if (type == kChunkJson) {
      if (json_seen) gltf_fail(element, "a second JSON chunk");
      if (length == 0) gltf_fail(element, "the JSON chunk is empty");
      out.json = data;
      json_seen = true;
    } else if (type == kChunkBin) {
      if (index != 1) gltf_fail(element, "a BIN chunk must be the second chunk, and there may be only one");
      out.bin = data;
    } else {
      out.warnings.push_back(element + ": unknown chunk type " + hex(type) + " skipped");
    }
  }
  if (!json_seen) gltf_fail("GLB header", "the file has no chunks (a JSON chunk must follow the header)");
  return out;
}

std::string make_glb(std::string_view json, const std::optional<std::string_view>& bin) {
  std::string json_chunk(json);
  while (json_chunk.size() % 4 != 0) json_chunk.push_back(' ');
  std::string bin_chunk(bin ? *bin : std::string_view());
  while (bin_chunk.size() % 4 != 0) bin_chunk.push_back('\0');
  std::string out;
  append_u32(out, kMagic);
  append_u32(out, 2);
  const size_t length = kHeaderBytes + kChunkHeaderBytes + json_chunk.size() +
                        (bin ? kChunkHeaderBytes + bin_chunk.size() : 0);
  append_u32(out, uint32_t(length));
  append_u32(out, uint32_t(json_chunk.size()));
  append_u32(out, kChunkJson);
  out += json_chunk;
  if (bin) {
    append_u32(out, uint32_t(bin_chunk.size()));
    append_u32(out, kChunkBin);
    out += bin_chunk;
  }
  return out;
}

}  // namespace clpt
