// glTF file -> tinygltf::Model (gltf_document.h). The JSON is parsed twice: once here with
// nlohmann-json for the checks tinygltf does not make before it reads bytes (buffers, buffer
// views, images, the extensions a file requires), then by tinygltf itself, which is handed the
// external buffers this file has already read and checked (its file-system callbacks serve them
// from memory and open nothing) and an image loader that decodes nothing (textures are a later
// issue; an image's uri, bufferView and mimeType are kept).
#include "scene/gltf_document.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <system_error>

#include "scene/gltf_error.h"
#include "scene/gltf_glb.h"
#include "util/hash.h"

namespace clpt {
namespace {

using json = nlohmann::json;

// Deeper JSON than this is refused before parsing: tinygltf turns `extras` and `extensions` into
// its Value type recursively, and a file of nested brackets would exhaust the stack.
constexpr int kMaxJsonDepth = 64;
// External buffers larger than this are refused before they are read (1 GiB, as mesh files).
constexpr uint64_t kMaxBufferBytes = uint64_t(1) << 30;

std::string indexed(const std::string& array, size_t i) { return array + "[" + std::to_string(i) + "]"; }

void check_json_depth(std::string_view text) {
  int depth = 0;
  bool in_string = false, escaped = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        gltf_fail("JSON", "nested deeper than " + std::to_string(kMaxJsonDepth) + " levels at byte " + std::to_string(i));
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

json parse_json(std::string_view text) {
  check_json_depth(text);
  try {
    return json::parse(text.begin(), text.end());
  } catch (const json::exception& e) {
    std::string what = e.what();
    const size_t bracket = what.find("] ");
    if (what.rfind("[json.exception", 0) == 0 && bracket != std::string::npos) what.erase(0, bracket + 2);
    gltf_fail("JSON", "not valid JSON: " + what);
  }
}

// The value of `key` in `object` as a non-negative integer, or `fallback` when absent (nullopt:
// required).
uint64_t unsigned_member(const json& object, const char* key, const std::string& element,
                         std::optional<uint64_t> fallback = std::nullopt) {
  const auto it = object.find(key);
  if (it == object.end()) {
    if (fallback) return *fallback;
    gltf_fail(element, "the required property '" + std::string(key) + "' is missing");
  }
  if (!it->is_number_unsigned())
    gltf_fail(element + "." + key, "must be a non-negative integer (got " + it->dump().substr(0, 40) + ")");
  return it->get<uint64_t>();
}

const json* array_member(const json& root, const char* key) {
  const auto it = root.find(key);
  if (it == root.end()) return nullptr;
  if (!it->is_array()) gltf_fail(key, "must be an array");
  return &*it;
}

const json& object_at(const json& array, size_t i, const std::string& element) {
  if (!array[i].is_object()) gltf_fail(element, "must be a JSON object");
  return array[i];
}

void check_asset(const json& root) {
  if (!root.is_object()) gltf_fail("JSON", "the top level is not an object, so this is not a glTF file");
  const auto asset = root.find("asset");
  if (asset == root.end() || !asset->is_object())
    gltf_fail("asset", "missing: a glTF file must have an 'asset' object with its version");
  const auto version = asset->find("version");
  if (version == asset->end() || !version->is_string()) gltf_fail("asset.version", "missing or not a string");
  const std::string v = version->get<std::string>();
  if (v.size() < 3 || v[0] != '2' || v[1] != '.' || !std::all_of(v.begin() + 2, v.end(), ::isdigit))
    gltf_fail("asset.version", "'" + v.substr(0, 20) + "': clpt reads glTF 2.x");
  const auto min_version = asset->find("minVersion");
  if (min_version != asset->end() && !(min_version->is_string() && min_version->get<std::string>() == "2.0"))
    gltf_fail("asset.minVersion", min_version->dump().substr(0, 20) + ": clpt reads glTF 2.0");
}

std::vector<std::string> string_list(const json& root, const char* key) {
  std::vector<std::string> out;
  const json* list = array_member(root, key);
  if (!list) return out;
  for (size_t i = 0; i < list->size(); ++i) {
    if (!(*list)[i].is_string()) gltf_fail(indexed(key, i), "must be a string");
    out.push_back((*list)[i].get<std::string>());
  }
  return out;
}

// extensionsRequired: all supported, or an error naming the first that is not. extensionsUsed:
// the ones clpt ignores, in one warning.
void check_extensions(const json& root, std::vector<std::string>& warnings) {
  const auto& supported = gltf_supported_extensions();
  const auto is_supported = [&](const std::string& name) {
    return std::find(supported.begin(), supported.end(), name) != supported.end();
  };
  const std::vector<std::string> required = string_list(root, "extensionsRequired");
  for (size_t i = 0; i < required.size(); ++i)
    if (!is_supported(required[i]))
      gltf_fail(indexed("extensionsRequired", i), "the file requires " + required[i] + ", which clpt does not implement");
  std::string ignored;
  for (const std::string& name : string_list(root, "extensionsUsed"))
    if (!is_supported(name) || name == "KHR_texture_transform") ignored += (ignored.empty() ? "" : ", ") + name;
  if (!ignored.empty()) warnings.push_back("extensionsUsed: ignored: " + ignored + " (docs/gltf.md)");
}

int base64_value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

// The decoded length of the base64 text `data`, or an error naming `element`.
uint64_t base64_length(std::string_view data, const std::string& element) {
  if (data.size() % 4 != 0) gltf_fail(element, "the base64 data's length is not a multiple of 4");
  size_t padding = 0;
  while (padding < 2 && padding < data.size() && data[data.size() - 1 - padding] == '=') ++padding;
  for (size_t i = 0; i + padding < data.size(); ++i)
    if (base64_value(data[i]) < 0) gltf_fail(element, "byte " + std::to_string(i) + " of the base64 data is not base64");
  return data.size() / 4 * 3 - padding;
}

// A buffer's `data:` URI: base64, of a media type a buffer may have; its length is byteLength.
void check_data_uri(const std::string& uri, uint64_t byte_length, const std::string& element) {
  const size_t comma = uri.find(',');
  const std::string header = uri.substr(0, comma == std::string::npos ? std::min<size_t>(uri.size(), 40) : comma);
  if (comma == std::string::npos || header.size() < 12 || header.compare(header.size() - 7, 7, ";base64") != 0)
    gltf_fail(element, "a data: URI must be base64 ('data:application/octet-stream;base64,...'), got '" + header + "'");
  if (header != "data:application/octet-stream;base64" && header != "data:application/gltf-buffer;base64")
    gltf_fail(element, "a buffer's data: URI must be application/octet-stream or application/gltf-buffer, got '" + header + "'");
  const uint64_t length = base64_length(std::string_view(uri).substr(comma + 1), element);
  if (length != byte_length)
    gltf_fail(element, "the data: URI holds " + std::to_string(length) + " bytes, byteLength says " +
                           std::to_string(byte_length));
}

// %XX escapes decoded, '+' read as a space (as tinygltf decodes URIs, so that the name it asks
// for is this one).
std::string decode_uri(const std::string& uri, const std::string& element) {
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '+') {
      out += ' ';
    } else if (uri[i] == '%') {
      const auto hex = [](char c) { return std::isxdigit(static_cast<unsigned char>(c)) != 0; };
      if (i + 2 >= uri.size() || !hex(uri[i + 1]) || !hex(uri[i + 2])) gltf_fail(element, "a malformed %-escape");
      const char c = char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      if (c == '\0') gltf_fail(element, "a %00 escape");
      out += c;
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

// A URI must be a relative path inside the glTF file's folder: no scheme, no absolute path, no
// '..' component (clpt reads nothing the file's folder does not hold).
void check_relative(const std::string& path, const std::string& element) {
  if (path.empty()) gltf_fail(element, "an empty URI");
  if (path[0] == '/' || path.find('\\') != std::string::npos || path.find(':') != std::string::npos)
    gltf_fail(element, "'" + path + "' is not a relative path inside the glTF file's folder");
  for (const auto& part : std::filesystem::path(path))
    if (part == "..") gltf_fail(element, "'" + path + "' leaves the glTF file's folder ('..')");
}

std::vector<unsigned char> read_external(const std::filesystem::path& file, uint64_t byte_length,
                                         const std::string& shown, const std::string& element) {
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (ec || !std::filesystem::exists(status)) gltf_fail(element, "cannot open '" + shown + "': No such file or directory");
  if (!std::filesystem::is_regular_file(status)) gltf_fail(element, "cannot open '" + shown + "': not a regular file");
  const uint64_t size = std::filesystem::file_size(file, ec);
  if (ec) gltf_fail(element, "cannot open '" + shown + "': " + ec.message());
  if (size != byte_length)
    gltf_fail(element, "'" + shown + "' is " + std::to_string(size) + " bytes, byteLength says " + std::to_string(byte_length));
  errno = 0;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> in(std::fopen(file.c_str(), "rb"), &std::fclose);
  if (!in) gltf_fail(element, "cannot open '" + shown + "': " + std::strerror(errno));
  std::vector<unsigned char> bytes(size);
  if (size > 0 && std::fread(bytes.data(), 1, size, in.get()) != size)
    gltf_fail(element, "cannot read '" + shown + "': it changed size while being read");
  return bytes;
}

// What the buffer checks leave for tinygltf and for the scene: external buffers' bytes by the
// name tinygltf will ask for, and each buffer's byteLength.
struct Buffers {
  std::map<std::string, std::vector<unsigned char>> external;
  std::vector<uint64_t> byte_lengths;
};

Buffers check_buffers(const json& root, bool glb, const std::optional<std::string_view>& bin, const std::string& path,
                      GltfDocument& document) {
  Buffers out;
  const json* buffers = array_member(root, "buffers");
  if (!buffers) return out;
  uint64_t hash = 0;
  for (size_t i = 0; i < buffers->size(); ++i) {
    const std::string element = indexed("buffers", i);
    const json& buffer = object_at(*buffers, i, element);
    const uint64_t byte_length = unsigned_member(buffer, "byteLength", element);
    if (byte_length == 0) gltf_fail(element + ".byteLength", "must be >= 1");
    out.byte_lengths.push_back(byte_length);
    const auto uri = buffer.find("uri");
    if (uri == buffer.end()) {
      if (!glb || i != 0) gltf_fail(element, "no 'uri' (only a GLB file's first buffer may refer to its BIN chunk)");
      if (!bin) gltf_fail(element, "refers to the GLB's BIN chunk, but the file has none");
      if (byte_length > bin->size())
        gltf_fail(element + ".byteLength", std::to_string(byte_length) + " bytes, more than the BIN chunk's " +
                                                std::to_string(bin->size()));
      continue;
    }
    if (!uri->is_string()) gltf_fail(element + ".uri", "must be a string");
    const std::string text = uri->get<std::string>();
    if (text.rfind("data:", 0) == 0) {
      check_data_uri(text, byte_length, element + ".uri");
      continue;
    }
    const std::string name = decode_uri(text, element + ".uri");
    check_relative(name, element + ".uri");
    const std::filesystem::path file = std::filesystem::path(path).parent_path() / name;
    std::vector<unsigned char> bytes = read_external(file, byte_length, name, element + ".uri");
    hash = fnv1a64(name + '\0' + hex64(fnv1a64(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()))) + '\n',
                   hash == 0 ? 0xcbf29ce484222325ull : hash);
    document.total_bytes += bytes.size();
    out.external[name] = std::move(bytes);
  }
  if (hash != 0) document.hash = hex64(fnv1a64(document.hash, hash));
  return out;
}

void check_buffer_views(const json& root, const Buffers& buffers) {
  const json* views = array_member(root, "bufferViews");
  if (!views) return;
  for (size_t i = 0; i < views->size(); ++i) {
    const std::string element = indexed("bufferViews", i);
    const json& view = object_at(*views, i, element);
    const uint64_t buffer = unsigned_member(view, "buffer", element);
    if (buffer >= buffers.byte_lengths.size())
      gltf_fail(element + ".buffer", std::to_string(buffer) + " is out of range (the file has " +
                                         std::to_string(buffers.byte_lengths.size()) + " buffers)");
    const uint64_t offset = unsigned_member(view, "byteOffset", element, 0);
    const uint64_t length = unsigned_member(view, "byteLength", element);
    if (length == 0) gltf_fail(element + ".byteLength", "must be >= 1");
    const uint64_t available = buffers.byte_lengths[buffer];
    if (offset > available || length > available - offset)
      gltf_fail(element, "bytes " + std::to_string(offset) + " to " + std::to_string(offset + length) + " run past the end of buffers[" +
                             std::to_string(buffer) + "] (" + std::to_string(available) + " bytes)");
    if (view.contains("byteStride")) {
      const uint64_t stride = unsigned_member(view, "byteStride", element);
      if (stride < 4 || stride > 252 || stride % 4 != 0)
        gltf_fail(element + ".byteStride", std::to_string(stride) + " (must be a multiple of 4 in [4, 252])");
    }
  }
}

// An image in a buffer view must name one that exists; tinygltf hands its bytes to the image
// loader (which decodes nothing) without checking the range.
void check_images(const json& root) {
  const json* images = array_member(root, "images");
  if (!images) return;
  const json* views = array_member(root, "bufferViews");
  const size_t view_count = views ? views->size() : 0;
  for (size_t i = 0; i < images->size(); ++i) {
    const std::string element = indexed("images", i);
    const json& image = object_at(*images, i, element);
    const bool has_view = image.contains("bufferView"), has_uri = image.contains("uri");
    if (has_view == has_uri) gltf_fail(element, "must have exactly one of 'uri' and 'bufferView'");
    if (has_uri && !image["uri"].is_string()) gltf_fail(element + ".uri", "must be a string");
    if (has_view && unsigned_member(image, "bufferView", element) >= view_count)
      gltf_fail(element + ".bufferView", "out of range (the file has " + std::to_string(view_count) + " buffer views)");
  }
}

// A material's alpha properties, which tinygltf reads with defaults (OPAQUE, 0.5) where one has
// the wrong type: alphaMode must be a string and alphaCutoff a number (its range and alphaMode's
// words: gltf_material.cpp).
void check_material_alpha(const json& root) {
  const json* materials = array_member(root, "materials");
  if (!materials) return;
  for (size_t i = 0; i < materials->size(); ++i) {
    const std::string element = indexed("materials", i);
    const json& material = object_at(*materials, i, element);
    if (material.contains("alphaMode") && !material["alphaMode"].is_string())
      gltf_fail(element + ".alphaMode", "must be a string (got " + material["alphaMode"].dump().substr(0, 40) + ")");
    if (material.contains("alphaCutoff") && !material["alphaCutoff"].is_number())
      gltf_fail(element + ".alphaCutoff", "must be a number (got " + material["alphaCutoff"].dump().substr(0, 40) + ")");
  }
}

// The index and offset properties tinygltf reads with defaults: where one has the wrong type or
// a negative value tinygltf keeps its default (-1 or 0) silently, and it narrows indices to int,
// so each present index must be an integer in [0, 2^31 - 1] and each offset a non-negative
// integer. (array, property; "[]": each element)
void check_indices(const json& root) {
  static const std::vector<std::pair<const char*, std::vector<const char*>>> kRules = {
      {"accessors", {"bufferView", "byteOffset"}},
      {"nodes", {"mesh", "camera", "skin", "children[]"}},
      {"scenes", {"nodes[]"}},
      {"textures", {"source", "sampler"}},
  };
  const auto check = [](const json& value, const std::string& element) {
    const bool offset = element.size() >= 10 && element.compare(element.size() - 10, 10, "byteOffset") == 0;
    const uint64_t max = offset ? UINT64_MAX : 0x7FFFFFFF;
    if (!value.is_number_unsigned() || value.get<uint64_t>() > max)
      gltf_fail(element, std::string("must be ") + (offset ? "a non-negative integer" : "an integer in [0, 2^31 - 1]") +
                             " (got " + value.dump().substr(0, 40) + ")");
  };
  if (root.contains("scene")) check(root["scene"], "scene");
  for (const auto& [array, properties] : kRules) {
    const json* items = array_member(root, array);
    for (size_t i = 0; items && i < items->size(); ++i) {
      const std::string element = indexed(array, i);
      const json& item = object_at(*items, i, element);
      for (const std::string property : properties) {
        const bool list = property.size() > 2 && property.compare(property.size() - 2, 2, "[]") == 0;
        const std::string key = list ? property.substr(0, property.size() - 2) : property;
        const auto it = item.find(key);
        if (it == item.end()) continue;
        if (!list) {
          check(*it, element + "." + key);
          continue;
        }
        if (!it->is_array()) gltf_fail(element + "." + key, "must be an array");
        for (size_t k = 0; k < it->size(); ++k) check((*it)[k], element + "." + key + "[" + std::to_string(k) + "]");
      }
    }
  }
  const json* meshes = array_member(root, "meshes");
  for (size_t m = 0; meshes && m < meshes->size(); ++m) {
    const json& mesh = object_at(*meshes, m, indexed("meshes", m));
    const auto primitives = mesh.find("primitives");
    if (primitives == mesh.end() || !primitives->is_array()) continue;  // tinygltf refuses it
    for (size_t p = 0; p < primitives->size(); ++p) {
      const std::string element = indexed("meshes", m) + indexed(".primitives", p);
      const json& primitive = object_at(*primitives, p, element);
      for (const char* key : {"indices", "material", "mode"})
        if (primitive.contains(key)) check(primitive[key], element + "." + key);
      const auto attributes = primitive.find("attributes");
      if (attributes != primitive.end() && attributes->is_object())
        for (const auto& [name, value] : attributes->items()) check(value, element + ".attributes." + name);
    }
  }
}

// tinygltf's file-system callbacks: the external buffers check_buffers read, and nothing else.
bool serve_exists(const std::string& path, void* buffers) {
  const auto& external = static_cast<Buffers*>(buffers)->external;
  return external.count(path) > 0 || (path.rfind("./", 0) == 0 && external.count(path.substr(2)) > 0);
}
std::string serve_expand(const std::string& path, void*) { return path; }
bool serve_read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* buffers) {
  auto& external = static_cast<Buffers*>(buffers)->external;
  auto it = external.find(path);
  if (it == external.end() && path.rfind("./", 0) == 0) it = external.find(path.substr(2));
  if (it == external.end()) {
    if (err) *err = "not among the buffers clpt has checked";
    return false;
  }
  *out = std::move(it->second);  // each buffer is asked for once
  external.erase(it);
  return true;
}
bool refuse_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err = "clpt writes no glTF files";
  return false;
}
// Images are not decoded here: their encoded bytes (a buffer view's or a data: URI's; the
// checks above bound them by the file's size) are kept for gltf_material.cpp, which decodes them
// through the scene's image reader.
bool keep_image_undecoded(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                          const unsigned char* bytes, int size, void*) {
  if (bytes && size > 0) image->image.assign(bytes, bytes + size);
  return true;
}

// tinygltf's first error line, as the message of a GltfError (its checks catch what the ones here
// leave to it, e.g. a missing required property).
[[noreturn]] void fail_tinygltf(const std::string& err) {
  std::string first = err.substr(0, err.find('\n'));
  if (first.empty()) first = "tinygltf cannot read it";
  gltf_fail("glTF", first);
}

tinygltf::Model run_tinygltf(std::string_view bytes, bool glb, const GlbChunks& chunks, Buffers& buffers) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(keep_image_undecoded, nullptr);
  loader.SetFsCallbacks(tinygltf::FsCallbacks{serve_exists, serve_expand, serve_read, refuse_write, &buffers});
  tinygltf::Model model;
  std::string err, warn;
  bool ok;
  if (glb) {
    // The container as tinygltf expects it: JSON then BIN, unknown chunks left out.
    const std::string canonical = make_glb(chunks.json, chunks.bin);
    ok = loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(canonical.data()),
                                     static_cast<unsigned>(canonical.size()), "");
  } else {
    ok = loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), static_cast<unsigned>(bytes.size()), "");
  }
  if (!ok || !err.empty()) fail_tinygltf(err);
  return model;
}

}  // namespace

const std::vector<std::string>& gltf_supported_extensions() {
  static const std::vector<std::string> names = {
      "KHR_lights_punctual",   "KHR_materials_emissive_strength", "KHR_materials_ior",
      "KHR_materials_transmission", "KHR_materials_volume",       "KHR_texture_transform"};
  return names;
}

std::string gltf_decode_uri(const std::string& uri, const std::string& element) { return decode_uri(uri, element); }
void gltf_check_relative(const std::string& path, const std::string& element) { check_relative(path, element); }

GltfDocument parse_gltf_document(std::string_view bytes, const std::string& path) {
  if (bytes.size() > kMaxBufferBytes)
    gltf_fail("glTF", "the file is " + std::to_string(bytes.size()) + " bytes, over the limit of " + std::to_string(kMaxBufferBytes));
  GltfDocument document;
  document.hash = hex64(fnv1a64(bytes));
  // A .glb file is a GLB container whatever its first bytes say (a wrong magic is its first error).
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  const bool glb = has_glb_magic(bytes) || extension == ".glb";
  GlbChunks chunks;
  if (glb) {
    chunks = split_glb(bytes);
    document.warnings = chunks.warnings;
  }
  document.total_bytes = bytes.size();
  const json root = parse_json(glb ? chunks.json : bytes);
  check_asset(root);
  check_extensions(root, document.warnings);
  Buffers buffers = check_buffers(root, glb, chunks.bin, path, document);
  check_buffer_views(root, buffers);
  check_images(root);
  check_indices(root);
  check_material_alpha(root);
  document.model = run_tinygltf(bytes, glb, chunks, buffers);
  return document;
}

}  // namespace clpt
