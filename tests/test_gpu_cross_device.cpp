// The GPU against the CPU: when an OpenCL GPU is present, the book's three scenes rendered there
// must agree with the CPU device (PoCL) statistically, in each channel's image mean and in 16x16
// block means (z within the Sidak-corrected limit for all comparisons), and with the same seed
// nearly pixel for pixel (printed; a GPU's contractions and maths differ, so that is reported,
// not asserted). Without a GPU the test says it was skipped (ctest shows "Skipped").
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "cl/cl_device.h"
#include "render_test_util.h"

namespace clpt::test {
namespace {

constexpr int kWidth = 64, kHeight = 48, kBlock = 16;

Film render_on(const std::string& scene_name, const std::string& device) {
  RenderRequest request;
  request.use_kernel_cache = false;
  request.scene = load_book_scene(scene_name);
  request.scene.settings.width = kWidth;
  request.scene.settings.height = kHeight;
  request.scene.settings.spp = 256;
  request.scene.settings.seed = 5150;
  request.scene.settings.sampler = Sampler::Jitter;
  request.device = device;
  RenderReport report;
  return run_render(request, report);
}

class GpuAgainstCpu : public ::testing::TestWithParam<std::string> {};

TEST_P(GpuAgainstCpu, SameImageStatistically) {
  bool has_gpu = false;
  for (const DeviceInfo& d : list_devices()) has_gpu |= d.is_gpu;
  if (!has_gpu) GTEST_SKIP() << "no OpenCL GPU on this machine: the GPU cross-device test was skipped";
  const Film gpu = render_on(GetParam(), "gpu"), cpu = render_on(GetParam(), "cpu");
  const auto mg = gpu.mean_rgb(), vg = gpu.variance_rgb(), mc = cpu.mean_rgb(), vc = cpu.variance_rgb();
  const int blocks = (kWidth / kBlock) * (kHeight / kBlock);
  const double z = sidak_z(3 * (blocks + 1), 0.001);
  for (int by = -1; by < kHeight / kBlock; ++by)
    for (int bx = 0; bx < (by < 0 ? 1 : kWidth / kBlock); ++bx) {
      // by = -1: the whole image; otherwise block (bx, by).
      const int x0 = by < 0 ? 0 : bx * kBlock, y0 = by < 0 ? 0 : by * kBlock;
      const int x1 = by < 0 ? kWidth : x0 + kBlock, y1 = by < 0 ? kHeight : y0 + kBlock;
      const RegionStats a = region_stats(mg, vg, kWidth, x0, y0, x1, y1);
      const RegionStats b = region_stats(mc, vc, kWidth, x0, y0, x1, y1);
      for (int c = 0; c < 3; ++c) {
        const double sigma = std::sqrt(a.variance_of_mean[c] + b.variance_of_mean[c]);
        EXPECT_LE(std::abs(a.mean[c] - b.mean[c]), z * sigma + 1e-7)
            << GetParam() << " block (" << x0 << "," << y0 << ") channel " << "RGB"[c] << ": gpu " << a.mean[c]
            << " cpu " << b.mean[c];
      }
    }
  size_t equal = 0;
  for (size_t i = 0; i < mg.size(); ++i)
    equal += std::abs(mg[i] - mc[i]) <= 1e-4 * std::max({std::abs(mg[i]), std::abs(mc[i]), 1e-6f});
  std::printf("%s: %.2f%% of pixel values equal within 1e-4 relative (same seed)\n", GetParam().c_str(),
              100.0 * double(equal) / double(mg.size()));
}

INSTANTIATE_TEST_SUITE_P(BookScenes, GpuAgainstCpu, ::testing::Values("diffuse", "specular", "glass"));

}  // namespace
}  // namespace clpt::test
