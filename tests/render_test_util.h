// Small renders for statistical tests: a scene file or an in-memory scene, a small image, fixed
// seed, on the test device.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "render/film.h"
#include "render/render_session.h"
#include "scene/scene.h"

namespace clpt::test {

// `scene` at width x height, `spp` samples a pixel, `seed` (and `sampler`, where given) as the tests
// render it: clpt's kernel cache off (the kernels under test compiled from source), on the test
// device (CLPT_TEST_DEVICE, else "cpu"). Callers set what they vary (form, precision...) on it.
RenderRequest test_request(Scene scene, int width, int height, int64_t spp, uint64_t seed,
                           std::optional<Sampler> sampler = std::nullopt);

struct TestRender {
  Film film;
  RenderReport report;
};

TestRender render_for_test(Scene scene, int width, int height, int64_t spp, uint64_t seed,
                           Sampler sampler = Sampler::Jitter, Precision precision = Precision::Robust,
                           bool adaptive = false);

Scene load_book_scene(const std::string& name);  // "diffuse", "specular", "glass"

// Mean and variance of the mean of a rectangle [x0,x1) x [y0,y1) of a mean/variance image pair
// (RGB interleaved), treating pixel means as independent.
struct RegionStats {
  double mean[3];
  double variance_of_mean[3];
};
RegionStats region_stats(const std::vector<float>& mean, const std::vector<float>& variance, int width,
                         int x0, int y0, int x1, int y1);

// A named rectangle of the book scene at 160x120 (tests/reference/book_regions.txt).
struct Region {
  std::string name;
  int x0, y0, x1, y1;
};
std::vector<Region> book_regions();

// z such that a two-sided normal test at that z, repeated `comparisons` times, has family-wise
// false-alarm probability `family_alpha` (Sidak correction).
double sidak_z(int comparisons, double family_alpha = 0.01);

// A request for scenes/NAME.toml at width x height, `seed`, `sampler`, compiled from source (clpt's
// kernel cache off), on the test device (CLPT_TEST_DEVICE, else "cpu").
RenderRequest scene_request(const std::string& scene_name, int width, int height, uint64_t seed,
                            Sampler sampler = Sampler::Jitter);

// One of the book's scenes at 48x36, 32 spp, jitter sampler, `seed`, on the test device with
// clpt's kernel cache off; `configure` sets what the test varies. Returns the mean image.
std::vector<float> render_book_variant(const std::string& scene_name, uint64_t seed,
                                       const std::function<void(RenderRequest&)>& configure);

// The same image up to float rounding (two runs of the same seed): >= 99% of values within 1e-4
// relative, and those values' sums within 1e-6 relative (a different contraction of a*b+c can
// send a rare path elsewhere, which moves its pixel by more than rounding: left out of the sums).
void expect_same_image(const std::vector<float>& a, const std::vector<float>& b);

// One value of two same-seed renders agrees: within 1e-4 relative (of the larger, or of 1e-6
// near zero). What expect_same_image and the Oclgrind tier's agreement count.
bool same_value(float a, float b);

}  // namespace clpt::test
