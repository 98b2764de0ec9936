// The glTF quad tests' camera scene (test_alpha.cpp, test_vertex_colors.cpp): an orthographic
// camera on +z sees the quad [-1, 1]^2 at z = 0 (the file quad.gltf in the scene's folder, which
// the test writes) in front of an emitter of radiance 1 at z = -1; no bounce, so a pixel is the
// quad's emission or the emitter's, exactly.
#pragma once

#include <string>

#include "scene/scene.h"

namespace clpt::test {

// The scene as if read from DIR/NAME (the folder quad.gltf is read from).
Scene quad_camera_scene(const std::string& dir, const std::string& name = "camera.toml");

}  // namespace clpt::test
