#include "render_test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "device_test_util.h"
#include "scene/scene_loader.h"

namespace clpt::test {

RenderRequest test_request(Scene scene, int width, int height, int64_t spp, uint64_t seed,
                           std::optional<Sampler> sampler) {
  scene.settings.width = width;
  scene.settings.height = height;
  scene.settings.spp = spp;
  scene.settings.seed = seed;
  if (sampler) scene.settings.sampler = *sampler;
  RenderRequest request;
  request.use_kernel_cache = false;
  request.scene = std::move(scene);
  const char* device = std::getenv("CLPT_TEST_DEVICE");
  request.device = device ? device : "cpu";
  return request;
}

TestRender render_for_test(Scene scene, int width, int height, int64_t spp, uint64_t seed, Sampler sampler,
                           Precision precision, bool adaptive) {
  RenderRequest request = test_request(std::move(scene), width, height, spp, seed, sampler);
  request.precision = precision;
  request.adaptive = adaptive;
  RenderReport report;
  Film film = run_render(request, report);
  return {std::move(film), report};
}

std::vector<Region> book_regions() {
  const std::string path = source_dir() + "/tests/reference/book_regions.txt";
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << "missing " << path;
  std::vector<Region> regions;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    Region r;
    s >> r.name >> r.x0 >> r.y0 >> r.x1 >> r.y1;
    regions.push_back(r);
  }
  return regions;
}

double sidak_z(int comparisons, double family_alpha) {
  const double alpha = 1 - std::pow(1 - family_alpha, 1.0 / std::max(1, comparisons));
  double lo = 0, hi = 20;  // bisection on the upper tail; precision is not critical here
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (std::erfc(mid / std::sqrt(2.0)) > alpha ? lo : hi) = mid;
  }
  return lo;
}

RenderRequest scene_request(const std::string& scene_name, int width, int height, uint64_t seed, Sampler sampler) {
  Scene scene = load_book_scene(scene_name);
  const int64_t spp = scene.settings.spp;
  return test_request(std::move(scene), width, height, spp, seed, sampler);
}

std::vector<float> render_book_variant(const std::string& scene_name, uint64_t seed,
                                       const std::function<void(RenderRequest&)>& configure) {
  RenderRequest request = scene_request(scene_name, 48, 36, seed);
  request.scene.settings.spp = 32;
  configure(request);
  RenderReport report;
  return run_render(request, report).mean_rgb();
}

bool same_value(float a, float b) {
  return std::abs(a - b) <= 1e-4 * std::max({std::abs(a), std::abs(b), 1e-6f});
}

// Two renders of the same seed "up to rounding": at least 99% of the values agree within 1e-4
// relative, and over those values the sums agree within 1e-6 relative, which a bias common to
// the image would break (measured over the 105 comparisons of the forms and presets tests on
// 2026-12-03: at most 1.9e-8). The other values are where rounding sent one path another way (a
// hit or a miss, the light or not); such a path moves its pixel by much more than rounding, and
// which of them it is depends on the seed, so the image's whole sum is no measure of precision
// (one such path: 1.3e-4 of a 48x36 image).
void expect_same_image(const std::vector<float>& a, const std::vector<float>& b) {
  ASSERT_EQ(a.size(), b.size());
  double close_a = 0, close_b = 0, far_a = 0, far_b = 0;
  size_t close = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    const bool same = same_value(a[i], b[i]);
    close += same;
    (same ? close_a : far_a) += a[i];
    (same ? close_b : far_b) += b[i];
  }
  EXPECT_GE(double(close), 0.99 * double(a.size())) << close << " of " << a.size();
  EXPECT_NEAR(close_a, close_b, 1e-6 * close_a)
      << "over the " << close << " values that agree; the " << a.size() - close << " others sum to " << far_a
      << " and " << far_b;
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
