// glTF accessors (glTF 2.0 section 3.6) read as doubles, every byte range checked before anything
// is read or allocated: the accessor inside its buffer view (offset, stride, alignment), sparse
// substitutions (indices strictly increasing and in range), floats finite, and the kinds of data
// each use allows (no KHR_mesh_quantization).
#pragma once

#include "scene/tinygltf_config.h"

#include <cstdint>
#include <string>
#include <vector>

namespace clpt {

// What a use of an accessor allows (the specification's table of mesh attributes, and indices).
// Color: COLOR_0, VEC3 or VEC4 (read_accessor gives the accessor's own 3 or 4 components).
enum class AccessorUse { Position, Normal, Texcoord, Indices, Tangent, Color };

// The elements of accessors[index], `components` doubles each (3 for VEC3 ...), one after the
// other. Normalised integers are mapped as the specification says (unsigned: c / max; signed:
// max(c / max, -1)); others keep their integer values. An accessor without a buffer view is all
// zeros before its sparse substitutions; its count may not exceed `total_bytes` (the file and its
// buffers), the budget that keeps a 1 kB file from asking for gigabytes. `referrer` names what
// uses it ("meshes[0].primitives[1].attributes.POSITION") in messages about the kind of data;
// faults of the accessor itself name "accessors[index]".
std::vector<double> read_accessor(const tinygltf::Model& model, int index, AccessorUse use,
                                  const std::string& referrer, uint64_t total_bytes);

// The number of elements accessors[index] has, after the same checks of index and kind.
size_t accessor_count(const tinygltf::Model& model, int index, AccessorUse use, const std::string& referrer);

}  // namespace clpt
