#include "scene/scene_image.h"

#include <atomic>

#include "util/error.h"

namespace clpt {
namespace {
std::atomic<SceneImageReader> installed_reader{nullptr};
}  // namespace

void set_scene_image_reader(SceneImageReader reader) { installed_reader.store(reader); }

SceneImagePixels read_scene_image(const std::string& path, const std::string& what) {
  const SceneImageReader reader = installed_reader.load();
  if (!reader)
    throw Error(ExitCode::BadScene, what + ": " + path +
                                        ": this build of clpt reads no images (built without OpenImageIO)");
  try {
    return reader(path);
  } catch (const Error& e) {
    throw Error(e.code(), what + ": " + e.what());
  }
}

}  // namespace clpt
