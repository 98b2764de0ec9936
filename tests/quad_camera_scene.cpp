#include "quad_camera_scene.h"

#include "scene/scene_loader.h"

namespace clpt::test {

Scene quad_camera_scene(const std::string& dir, const std::string& name) {
  const std::string text = R"(
[render]
max_bounces = 0
estimator = "book"
[camera]
position = [0, 0, 5]
look_at = [0, 0, 0]
projection = "orthographic"
height = 2
[[mesh]]
vertices = [[-2, -2, -1], [2, -2, -1], [2, 2, -1], [-2, 2, -1]]
quads = [[0, 1, 2, 3]]
material = { type = "emitter", emission = [1, 1, 1] }
[[gltf]]
file = "quad.gltf"
)";
  return load_scene_string(text, dir + "/" + name);
}

}  // namespace clpt::test
