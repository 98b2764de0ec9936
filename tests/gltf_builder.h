// A small glTF 2.0 file builder for tests (test_gltf_loader.cpp, the fuzz seeds): the JSON as
// nlohmann-json, one binary buffer that accessors append to, and the file written as GLB or as
// .gltf with the buffer in a data: URI or an external .bin. Each test case is then a few lines.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace clpt::test {

class GltfBuilder {
 public:
  nlohmann::json doc = {{"asset", {{"version", "2.0"}}}};
  std::string bin;  // buffers[0]

  // `bytes` appended to the buffer (4-byte aligned) as a new buffer view; its index.
  int view(const std::string& bytes, int stride = 0) {
    while (bin.size() % 4 != 0) bin.push_back('\0');
    nlohmann::json v = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes.size()}};
    if (stride > 0) v["byteStride"] = stride;
    bin += bytes;
    return push("bufferViews", v);
  }

  // An accessor over `values` stored as `component` (5121 ubyte, 5123 ushort, 5125 uint, 5126
  // float), `count` elements of `type` ("SCALAR", "VEC2", "VEC3", "VEC4").
  template <typename T>
  int accessor(const std::vector<T>& values, int component, const std::string& type, bool normalized = false) {
    std::string bytes(values.size() * sizeof(T), '\0');
    std::memcpy(bytes.data(), values.data(), bytes.size());
    const size_t components = type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC4" ? 4 : 3;
    nlohmann::json a = {{"bufferView", view(bytes)}, {"componentType", component},
                        {"count", values.size() / components}, {"type", type}};
    if (normalized) a["normalized"] = true;
    return push("accessors", a);
  }
  int positions(const std::vector<float>& xyz) { return accessor(xyz, 5126, "VEC3"); }
  int indices(const std::vector<uint32_t>& i) { return accessor(i, 5125, "SCALAR"); }

  // A mesh of one primitive; its index.
  int mesh(const nlohmann::json& primitive) { return push("meshes", {{"primitives", {primitive}}}); }
  int triangle_mesh(const std::vector<float>& xyz, int mode = 4) {
    return mesh({{"attributes", {{"POSITION", positions(xyz)}}}, {"mode", mode}});
  }
  // A node, listed among scenes[0]'s nodes when `root`.
  int node(const nlohmann::json& n, bool root = true) {
    const int index = push("nodes", n);
    if (root) {
      if (!doc.contains("scenes")) doc["scenes"] = {{{"nodes", nlohmann::json::array()}}};
      doc["scenes"][0]["nodes"].push_back(index);
    }
    return index;
  }
  int push(const std::string& array, const nlohmann::json& value) {
    doc[array].push_back(value);
    return int(doc[array].size()) - 1;
  }

  // The JSON with buffers[0] as given (no uri: a GLB's BIN chunk).
  std::string json_text(const std::string& uri = "") const {
    nlohmann::json d = doc;
    if (!bin.empty()) {
      d["buffers"] = {{{"byteLength", bin.size()}}};
      if (!uri.empty()) d["buffers"][0]["uri"] = uri;
    }
    return d.dump();
  }
  std::string gltf_embedded() const { return json_text("data:application/octet-stream;base64," + base64(bin)); }

  static std::string base64(const std::string& bytes) {
    static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
      uint32_t n = uint32_t(uint8_t(bytes[i])) << 16;
      if (i + 1 < bytes.size()) n |= uint32_t(uint8_t(bytes[i + 1])) << 8;
      if (i + 2 < bytes.size()) n |= uint32_t(uint8_t(bytes[i + 2]));
      out += alphabet[(n >> 18) & 63];
      out += alphabet[(n >> 12) & 63];
      out += i + 1 < bytes.size() ? alphabet[(n >> 6) & 63] : '=';
      out += i + 2 < bytes.size() ? alphabet[n & 63] : '=';
    }
    return out;
  }
};

}  // namespace clpt::test
