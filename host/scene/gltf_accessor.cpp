// Accessors (gltf_accessor.h): kinds, byte ranges, sparse substitutions, values.
#include "scene/gltf_accessor.h"

#include <cmath>
#include <cstring>

#include "scene/gltf_error.h"

namespace clpt {
namespace {

struct Kind {
  int type;                   // TINYGLTF_TYPE_*
  const char* type_name;
  std::vector<int> component_types;
  bool normalized_integers;  // integer component types must be normalised (texture coordinates)
};

Kind kind_of(AccessorUse use) {
  switch (use) {
    case AccessorUse::Position:
    case AccessorUse::Normal:
      return {TINYGLTF_TYPE_VEC3, "VEC3", {TINYGLTF_COMPONENT_TYPE_FLOAT}, false};
    case AccessorUse::Texcoord:
      return {TINYGLTF_TYPE_VEC2, "VEC2",
              {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
              true};
    case AccessorUse::Tangent:
      return {TINYGLTF_TYPE_VEC4, "VEC4", {TINYGLTF_COMPONENT_TYPE_FLOAT}, false};
    case AccessorUse::Color:  // VEC4 as well (checked_accessor)
      return {TINYGLTF_TYPE_VEC3, "VEC3 or VEC4",
              {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
              true};
    case AccessorUse::Indices:
      break;
  }
  return {TINYGLTF_TYPE_SCALAR, "SCALAR",
          {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
          false};
}

const char* component_name(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE (5120)";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE (5121)";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT (5122)";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT (5123)";
    case TINYGLTF_COMPONENT_TYPE_INT: return "INT (5124)";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT (5125)";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT (5126)";
  }
  return "not a glTF component type";
}

uint64_t component_bytes(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
  }
  return 4;
}

// One component at `p` (little-endian), normalised when asked.
double decode(const unsigned char* p, int type, bool normalized) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const double c = double(int8_t(p[0]));
      return normalized ? std::max(c / 127.0, -1.0) : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? p[0] / 255.0 : double(p[0]);
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const double c = double(int16_t(uint16_t(p[0] | p[1] << 8)));
      return normalized ? std::max(c / 32767.0, -1.0) : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      const double c = double(uint16_t(p[0] | p[1] << 8));
      return normalized ? c / 65535.0 : c;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return double(uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24);
  }
  const uint32_t bits = uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
  float f;
  std::memcpy(&f, &bits, 4);
  return double(f);
}

std::string accessor_name(int index) { return "accessors[" + std::to_string(index) + "]"; }

const tinygltf::Accessor& checked_accessor(const tinygltf::Model& model, int index, AccessorUse use,
                                           const std::string& referrer) {
  if (index < 0 || size_t(index) >= model.accessors.size())
    gltf_fail(referrer, "accessor " + std::to_string(index) + " is out of range (the file has " +
                            std::to_string(model.accessors.size()) + " accessors)");
  const tinygltf::Accessor& a = model.accessors[size_t(index)];
  const Kind kind = kind_of(use);
  const std::string seen = " (" + accessor_name(index) + ")";
  const bool color4 = use == AccessorUse::Color && a.type == TINYGLTF_TYPE_VEC4;
  if (a.type != kind.type && !color4) gltf_fail(referrer, "the accessor's type must be " + std::string(kind.type_name) + seen);
  bool allowed = false;
  for (int t : kind.component_types) allowed = allowed || t == a.componentType;
  if (!allowed) gltf_fail(referrer, "component type " + std::string(component_name(a.componentType)) + " is not allowed here" + seen);
  const bool integer = a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT;
  if (a.normalized && (!integer || a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
    gltf_fail(accessor_name(index) + ".normalized", "must be false for " + std::string(component_name(a.componentType)));
  if (integer && kind.normalized_integers && !a.normalized)
    gltf_fail(referrer, "integer components must be normalized here" + seen);
  if (integer && !kind.normalized_integers && a.normalized) gltf_fail(referrer, "indices must not be normalized" + seen);
  if (a.count == 0) gltf_fail(accessor_name(index) + ".count", "must be >= 1");
  return a;
}

// bufferViews[view]'s bytes, which gltf_document.cpp has checked to lie inside their buffer.
const unsigned char* view_bytes(const tinygltf::Model& model, int view, const std::string& element, uint64_t& length,
                                uint64_t& stride) {
  if (view < 0 || size_t(view) >= model.bufferViews.size())
    gltf_fail(element, "buffer view " + std::to_string(view) + " is out of range (the file has " +
                           std::to_string(model.bufferViews.size()) + " buffer views)");
  const tinygltf::BufferView& v = model.bufferViews[size_t(view)];
  const std::vector<unsigned char>& data = model.buffers.at(size_t(v.buffer)).data;
  if (v.byteOffset > data.size() || v.byteLength > data.size() - v.byteOffset)
    gltf_fail(element, "buffer view " + std::to_string(view) + " runs past its buffer");
  length = v.byteLength;
  stride = v.byteStride;
  return data.data() + v.byteOffset;
}

// `count` elements of `element_bytes` each, `stride` apart, from byte `offset` of a view of
// `length` bytes: inside it, and aligned to the component size (glTF 2.0 section 3.6.2.4).
void check_range(uint64_t offset, uint64_t count, uint64_t stride, uint64_t element_bytes, uint64_t component,
                 uint64_t view_offset, uint64_t length, const std::string& element) {
  if (offset % component != 0 || (view_offset + offset) % component != 0)
    gltf_fail(element, "byte offset " + std::to_string(offset) + " is not a multiple of the component size " +
                           std::to_string(component));
  if (offset > length || element_bytes > length - offset || (count - 1) > (length - offset - element_bytes) / stride)
    gltf_fail(element, std::to_string(count) + " elements of " + std::to_string(element_bytes) + " bytes, " +
                           std::to_string(stride) + " apart from byte " + std::to_string(offset) +
                           ", run past the end of the buffer view (" + std::to_string(length) + " bytes)");
}

void read_elements(const unsigned char* base, uint64_t count, uint64_t stride, int components, int type, bool normalized,
                   double* out) {
  const uint64_t size = component_bytes(type);
  for (uint64_t i = 0; i < count; ++i)
    for (int c = 0; c < components; ++c) out[i * components + c] = decode(base + i * stride + c * size, type, normalized);
}

void apply_sparse(const tinygltf::Model& model, const tinygltf::Accessor& a, int index, int components,
                  std::vector<double>& values) {
  const std::string element = accessor_name(index) + ".sparse";
  const auto& s = a.sparse;
  if (s.count < 1 || uint64_t(s.count) > a.count)
    gltf_fail(element + ".count", std::to_string(s.count) + " (must be in [1, " + std::to_string(a.count) + "])");
  const int index_type = s.indices.componentType;
  if (index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    gltf_fail(element + ".indices.componentType", std::string(component_name(index_type)) + " is not an index type");
  if (s.indices.byteOffset < 0) gltf_fail(element + ".indices.byteOffset", "must be >= 0");
  if (s.values.byteOffset < 0) gltf_fail(element + ".values.byteOffset", "must be >= 0");
  uint64_t length = 0, stride = 0;
  const unsigned char* indices = view_bytes(model, s.indices.bufferView, element + ".indices.bufferView", length, stride);
  const uint64_t index_bytes = component_bytes(index_type), count = uint64_t(s.count);
  const uint64_t indices_view_offset = model.bufferViews[size_t(s.indices.bufferView)].byteOffset;
  check_range(uint64_t(s.indices.byteOffset), count, index_bytes, index_bytes, index_bytes, indices_view_offset, length,
              element + ".indices");
  const uint64_t value_bytes = component_bytes(a.componentType) * uint64_t(components);
  const unsigned char* data = view_bytes(model, s.values.bufferView, element + ".values.bufferView", length, stride);
  check_range(uint64_t(s.values.byteOffset), count, value_bytes, value_bytes, component_bytes(a.componentType),
              model.bufferViews[size_t(s.values.bufferView)].byteOffset, length, element + ".values");
  std::vector<double> at(count);
  read_elements(indices + s.indices.byteOffset, count, index_bytes, 1, index_type, false, at.data());
  std::vector<double> replacement(count * uint64_t(components));
  read_elements(data + s.values.byteOffset, count, value_bytes, components, a.componentType, a.normalized, replacement.data());
  for (uint64_t i = 0; i < count; ++i) {
    if (at[i] >= double(a.count))
      gltf_fail(element + ".indices", "index " + std::to_string(uint64_t(at[i])) + " (element " + std::to_string(i) +
                                          ") is out of range (the accessor has " + std::to_string(a.count) + " elements)");
    if (i > 0 && at[i] <= at[i - 1])
      gltf_fail(element + ".indices", "not strictly increasing at element " + std::to_string(i));
    for (int c = 0; c < components; ++c) values[uint64_t(at[i]) * components + c] = replacement[i * components + c];
  }
}

}  // namespace

size_t accessor_count(const tinygltf::Model& model, int index, AccessorUse use, const std::string& referrer) {
  return checked_accessor(model, index, use, referrer).count;
}

std::vector<double> read_accessor(const tinygltf::Model& model, int index, AccessorUse use, const std::string& referrer,
                                  uint64_t total_bytes) {
  const tinygltf::Accessor& a = checked_accessor(model, index, use, referrer);
  const std::string element = accessor_name(index);
  const int components = use == AccessorUse::Indices    ? 1
                         : use == AccessorUse::Texcoord ? 2
                         : use == AccessorUse::Tangent  ? 4
                         : use == AccessorUse::Color    ? (a.type == TINYGLTF_TYPE_VEC4 ? 4 : 3)
                                                        : 3;
  const uint64_t element_bytes = component_bytes(a.componentType) * uint64_t(components);
  std::vector<double> values;
  if (a.bufferView < 0) {
    if (a.count > total_bytes)
      gltf_fail(element + ".count", std::to_string(a.count) + " elements without a buffer view, more than the file's " +
                                        std::to_string(total_bytes) + " bytes can justify");
    values.assign(a.count * uint64_t(components), 0.0);
  } else {
    uint64_t length = 0, stride = 0;
    const unsigned char* data = view_bytes(model, a.bufferView, element + ".bufferView", length, stride);
    if (stride != 0 && stride < element_bytes)
      gltf_fail(element, "its buffer view's byteStride " + std::to_string(stride) + " is less than an element's " +
                             std::to_string(element_bytes) + " bytes");
    if (stride == 0) stride = element_bytes;
    check_range(a.byteOffset, a.count, stride, element_bytes, component_bytes(a.componentType),
                model.bufferViews[size_t(a.bufferView)].byteOffset, length, element);
    values.resize(a.count * uint64_t(components));  // a.count elements fit in the view: no more than the file holds
    read_elements(data + a.byteOffset, a.count, stride, components, a.componentType, a.normalized, values.data());
  }
  if (a.sparse.isSparse) apply_sparse(model, a, index, components, values);
  for (size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      gltf_fail(element, "element " + std::to_string(i / size_t(components)) + " is not finite (" + referrer + ")");
  return values;
}

}  // namespace clpt
