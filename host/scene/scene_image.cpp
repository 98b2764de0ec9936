#include "scene/scene_image.h"

#include <atomic>
#include <chrono>
#include <cstdint>

#include "util/error.h"

namespace clpt {
namespace {
std::atomic<SceneImageReader> installed_reader{nullptr};
std::atomic<int64_t> reading_nanoseconds{0};

// Adds the wall time from its construction to its destruction to reading_nanoseconds.
struct ReadTimer {
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  ~ReadTimer() {
    reading_nanoseconds += std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start).count();
  }
};
}  // namespace

double scene_image_seconds() { return double(reading_nanoseconds.load()) * 1e-9; }

void set_scene_image_reader(SceneImageReader reader) { installed_reader.store(reader); }

SceneImagePixels read_scene_image(const std::string& path, const std::string& what) {
  const SceneImageReader reader = installed_reader.load();
  if (!reader)
    throw Error(ExitCode::BadScene, what + ": " + path +
                                        ": this build of clpt reads no images (built without OpenImageIO)");
  const ReadTimer timer;
  try {
    return reader(path);
  } catch (const Error& e) {
    throw Error(e.code(), what + ": " + e.what());
  }
}

}  // namespace clpt
