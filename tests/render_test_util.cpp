#include "render_test_util.h"

#include <cstdlib>

#include "device_test_util.h"
#include "scene/scene_loader.h"

namespace clpt::test {

TestRender render_for_test(Scene scene, int width, int height, int64_t spp, uint64_t seed, Sampler sampler,
                           Precision precision) {
  scene.settings.width = width;
  scene.settings.height = height;
  scene.settings.spp = spp;
  scene.settings.seed = seed;
  scene.settings.sampler = sampler;
  RenderRequest request;
  request.use_kernel_cache = false;  // tests compile the kernels under test from source
  request.scene = scene;
  request.precision = precision;
  const char* device = std::getenv("CLPT_TEST_DEVICE");
  request.device = device ? device : "cpu";
  RenderReport report;
  Film film = run_render(request, report);
  return {std::move(film), report};
}

Scene load_book_scene(const std::string& name) {
  return load_scene_file(source_dir() + "/scenes/" + name + ".toml");
}

RegionStats region_stats(const std::vector<float>& mean, const std::vector<float>& variance, int width,
                         int x0, int y0, int x1, int y1) {
  RegionStats r{};
  const double n = double(x1 - x0) * (y1 - y0);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      for (int c = 0; c < 3; ++c) {
        const size_t i = (size_t(y) * width + x) * 3 + c;
        r.mean[c] += mean[i] / n;
        r.variance_of_mean[c] += variance[i] / (n * n);
      }
  return r;
}

}  // namespace clpt::test
