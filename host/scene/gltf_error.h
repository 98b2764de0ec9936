// Internal to the glTF reader (host/scene/gltf_*): the one exception its parts throw. The
// message starts with the glTF element at fault ("meshes[2].primitives[0].indices: ...") but not
// the file: the caller knows how the scene names it, and turns it into
// clpt::Error(ExitCode::BadScene, "FILE: ELEMENT: MESSAGE") (gltf_loader.cpp).
#pragma once

#include <stdexcept>
#include <string>

namespace clpt {

class GltfError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws GltfError("ELEMENT: MESSAGE").
[[noreturn]] inline void gltf_fail(const std::string& element, const std::string& message) {
  throw GltfError(element + ": " + message);
}

}  // namespace clpt
