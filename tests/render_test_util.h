// Small renders for statistical tests: a scene file or an in-memory scene, a small image, fixed
// seed, on the test device.
#pragma once

#include <string>

#include "render/film.h"
#include "render/render_session.h"
#include "scene/scene.h"

namespace clpt::test {

struct TestRender {
  Film film;
  RenderReport report;
};

TestRender render_for_test(Scene scene, int width, int height, int64_t spp, uint64_t seed,
                           Sampler sampler = Sampler::Jitter, Precision precision = Precision::Robust);

Scene load_book_scene(const std::string& name);  // "diffuse", "specular", "glass"

// Mean and variance of the mean of a rectangle [x0,x1) x [y0,y1) of a mean/variance image pair
// (RGB interleaved), treating pixel means as independent.
struct RegionStats {
  double mean[3];
  double variance_of_mean[3];
};
RegionStats region_stats(const std::vector<float>& mean, const std::vector<float>& variance, int width,
                         int x0, int y0, int x1, int y1);

}  // namespace clpt::test
