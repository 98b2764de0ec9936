// Limits, launch sizing, partial passes and checkpoints: host code only, no device needed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "cl/cl_device.h"
#include "mesh_test_util.h"
#include "render/checkpoint.h"
#include "render/film.h"
#include "render/limits.h"
#include "render/pass_loop.h"
#include "render/work_queue.h"
#include "util/error.h"

namespace clpt {
namespace {

// The message of the clpt::Error `f` throws, with its exit code.
template <typename F>
std::pair<ExitCode, std::string> error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return {e.code(), e.what()};
  }
  return {ExitCode::Ok, ""};
}

Scene small_scene() {
  Scene s;
  s.file = "scene.toml";
  s.file_hash = "0123456789abcdef";
  s.settings.width = 4;
  s.settings.height = 3;
  s.spheres.resize(2);
  return s;
}

TEST(LaunchSizing, FirstLaunchIsSmallThenAimsAtTheTarget) {
  LaunchSizing sizing{0.075, 4096, 1u << 20};
  EXPECT_EQ(next_launch_pixels(sizing, 1000000, 16, 0, 0), 4096u);
  // 1e8 pixel-samples/s * 0.075 s / 16 samples = 468750 pixels, but at most 4x the last launch.
  EXPECT_EQ(next_launch_pixels(sizing, 1000000, 16, 1e8, 4096), 4u * 4096);
  EXPECT_EQ(next_launch_pixels(sizing, 1000000, 16, 1e8, 400000), 468750u);
  // A slow device: never below one pixel.
  EXPECT_EQ(next_launch_pixels(sizing, 1000, 4096, 1.0, 10), 1u);
}

TEST(LaunchSizing, BoundsAndTails) {
  LaunchSizing sizing{0.075, 4096, 100000};
  EXPECT_EQ(next_launch_pixels(sizing, 0, 1, 1e9, 100), 0u);
  EXPECT_EQ(next_launch_pixels(sizing, 1000000, 1, 1e12, 1000000), 100000u);  // memory bound
  EXPECT_EQ(next_launch_pixels(sizing, 3000, 1, 0, 0), 3000u);                // all that is left
  EXPECT_EQ(next_launch_pixels(sizing, 4096 + 1000, 1, 0, 0), 5096u);         // tail < 1/4 folded in
  EXPECT_EQ(next_launch_pixels(sizing, 4096 + 2000, 1, 0, 0), 4096u);
  LaunchSizing whole{0, 4096, 100000};  // target 0: one launch per pass, within the memory bound
  EXPECT_EQ(next_launch_pixels(whole, 50000, 64, 1e3, 10), 50000u);
  EXPECT_EQ(next_launch_pixels(whole, 250000, 64, 1e3, 10), 100000u);
}

TEST(LaunchSizing, JobBoundKeepsEveryLaunchUnderTheDriversWidth) {
  // PoCL's one compiled kernel (cl_device.h): pixels x samples of a launch at most max_jobs.
  LaunchSizing whole{0, 4096, 1u << 20, 64512};
  EXPECT_EQ(next_launch_pixels(whole, 1000000, 16, 1e3, 10), 64512u / 16);
  EXPECT_EQ(next_launch_pixels(whole, 4032 + 100, 16, 1e3, 10), 4032u);  // no tail folded past it
  EXPECT_EQ(next_launch_pixels(whole, 4000, 16, 1e3, 10), 4000u);
  EXPECT_EQ(next_launch_pixels(whole, 1000, 100000, 1e3, 10), 1u);  // a pixel's samples alone exceed it
  LaunchSizing timed{0.075, 4096, 1u << 20, 64512};
  EXPECT_EQ(next_launch_pixels(timed, 1000000, 1, 1e9, 1000000), 64512u);
}

TEST(Film, PartialLaunchesCountAsOnePass) {
  Film film(3, 2);
  GpuPixelPass p{};
  p.valid_samples = 4;
  film.add_pass({p, p}, 0, 4);
  EXPECT_EQ(film.samples_per_pixel(), 0u);
  EXPECT_FALSE(film.between_passes());
  film.add_pass({p, p, p, p}, 2, 4);
  EXPECT_EQ(film.samples_per_pixel(), 4u);
  EXPECT_TRUE(film.between_passes());
  EXPECT_EQ(film.total_samples(), 24u);
  film.add_pass({p}, 0, 4);
  EXPECT_THROW(film.add_pass({p}, 1, 8), std::logic_error);  // samples change inside a pass
}

TEST(Limits, SceneLimitsNameTheValueAndTheLimit) {
  Scene s = small_scene();
  EXPECT_EQ(error_of([&] { check_scene_limits(s); }).first, ExitCode::Ok);
  s.settings.width = s.settings.height = 16384;
  EXPECT_EQ(error_of([&] { check_scene_limits(s, {true, false, false}); }),
            std::make_pair(ExitCode::Usage,
                           std::string("--width/--height: the image 16384x16384 has 268435456 pixels; "
                                       "at most 67108864 (2^26) are supported")));
  EXPECT_EQ(error_of([&] { check_scene_limits(s); }).first, ExitCode::BadScene);
  s = small_scene();
  s.spheres.resize(5000);
  EXPECT_EQ(error_of([&] { check_scene_limits(s); }),
            std::make_pair(ExitCode::BadScene,
                           std::string("scene.toml: sphere: the scene has 5000 spheres; at most 4096 are supported")));
  s = small_scene();
  s.settings.spp = int64_t(1) << 32;
  EXPECT_EQ(error_of([&] { check_scene_limits(s, {false, true, false}); }).first, ExitCode::Usage);
}

DeviceInfo fake_device(uint64_t global, uint64_t max_alloc) {
  DeviceInfo d;
  d.name = "X";
  d.is_gpu = true;
  d.compute_units = 4;
  d.global_mem_bytes = global;
  d.max_alloc_bytes = max_alloc;
  return d;
}

TEST(Limits, MemoryEstimateFollowsTheRenderers) {
  const DeviceInfo d = fake_device(8ull << 30, 2ull << 30);
  EXPECT_EQ(launch_buffer_budget(d), 256u << 20);
  EXPECT_EQ(launch_buffer_budget(fake_device(1ull << 30, 256u << 20)), 128u << 20);
  // Megakernel: spheres, one launch's pass statistics (at most budget / 32 pixels) and its job
  // results (16 B per sample: 1000 pixels x 4096 samples, the most a pass takes).
  const MemoryEstimate mk = estimate_device_memory(ExecutionForm::Megakernel, 1000, 10, 0, d);
  EXPECT_EQ(mk.total_bytes, 10u * 128 + 1000u * 32 + 1000u * 4096 * 16);
  EXPECT_EQ(estimate_device_memory(ExecutionForm::Megakernel, 1ull << 26, 1, 0, d).largest_bytes, 256u << 20);
  // Wavefront: 65536 paths x 256 B (the double preset's state, the largest), pass statistics,
  // job results bounded by the budget.
  const MemoryEstimate wf = estimate_device_memory(ExecutionForm::Wavefront, 1ull << 20, 1, 65536, d);
  EXPECT_EQ(wf.total_bytes, 128u + 65536u * 256 + (32u << 20) + (256u << 20));
  EXPECT_EQ(wf.largest_label, "job results");
}

// The first-hit layers (--aovs): 28 B more per sample of job results (44 in all), 28 B of layer
// sums per pixel of a launch, and for the wavefront 7 more state buffers per set (two sets, at the
// double preset's 8 B: 112 B more per path slot).
TEST(Limits, FirstHitLayersCountInTheMemoryEstimate) {
  const DeviceInfo d = fake_device(8ull << 30, 2ull << 30);
  EXPECT_EQ(result_bytes_per_job(false), 16u);
  EXPECT_EQ(result_bytes_per_job(true), 44u);
  EXPECT_EQ(max_samples_per_pass_for(d, 1u << 20, true), (256u << 20) / (44u << 20));
  const MemoryEstimate mk = estimate_device_memory(ExecutionForm::Megakernel, 1000, 10, 0, d, 0, 0, 0, true);
  EXPECT_EQ(mk.total_bytes, 10u * 128 + 1000u * 32 + 1000u * 28 + 1000u * 4096 * 44);
  const MemoryEstimate wf = estimate_device_memory(ExecutionForm::Wavefront, 1000, 1, 65536, d);
  const MemoryEstimate wf_aovs = estimate_device_memory(ExecutionForm::Wavefront, 1000, 1, 65536, d, 0, 0, 0, true);
  EXPECT_EQ(wf_aovs.total_bytes - wf.total_bytes, 65536u * 112 + 1000u * 28 + 1000u * 4096 * 28);
}

// Triangles add 48 + 112 B each, a 160-byte leaf block each at most and at most (2n + 2) / 3
// 128-byte 4-wide nodes for n primitives (spheres included); a device
// whose largest allocation cannot hold the shading records refuses before upload, naming them.
TEST(Limits, TrianglesCountInTheMemoryEstimate) {
  const DeviceInfo d = fake_device(8ull << 30, 2ull << 30);
  const MemoryEstimate plain = estimate_device_memory(ExecutionForm::Megakernel, 1000, 10, 0, d);
  const MemoryEstimate mesh = estimate_device_memory(ExecutionForm::Megakernel, 1000, 10, 0, d, 100000);
  EXPECT_EQ(mesh.total_bytes - plain.total_bytes, 100000u * (48 + 112 + 160) + (2u * 100010 + 2) / 3 * 128);
  EXPECT_EQ(kDeviceBytesPerTriangle, 406u);
  // An emitting mesh's triangles are light entries too (80 B each), counted from the scene.
  const MemoryEstimate lit = estimate_device_memory(ExecutionForm::Megakernel, 1000, 10, 0, d, 100000, 100001);
  EXPECT_EQ(lit.total_bytes - mesh.total_bytes, 100001u * 80);
  Scene scene;
  scene.meshes.push_back(test::closed_box({0, 0, 0}, {1, 1, 1}, test::emitter(1)));
  scene.meshes.push_back(test::closed_box({2, 0, 0}, {3, 1, 1}, test::lambertian(0.5)));
  Sphere light;
  light.material = test::emitter(2);
  scene.spheres = {light, Sphere{}};
  EXPECT_EQ(light_entry_bound(scene), 13u);
  const DeviceInfo small = fake_device(8ull << 30, 64ull << 20);
  const MemoryEstimate big = estimate_device_memory(ExecutionForm::Megakernel, 100, 1, 0, small, 1000000);
  EXPECT_EQ(big.largest_label, "hierarchy nodes and leaf triangles");
  const auto [code, message] = error_of([&] { check_device_memory(big, small); });
  EXPECT_EQ(code, ExitCode::DeviceError);
  EXPECT_NE(message.find("buffer 'hierarchy nodes and leaf triangles' would be 234.0 MiB"), std::string::npos) << message;
}

TEST(Limits, MemoryErrorsNameTheDeviceAndSizes) {
  MemoryEstimate need{3435973837ull, 1u << 20, "pass statistics"};  // 3.2 GiB in all
  EXPECT_EQ(error_of([&] { check_device_memory(need, fake_device(2ull << 30, 1ull << 30)); }).second,
            "render needs 3.2 GiB on device 'X' but it has 2.0 GiB (use a smaller image, fewer "
            "--paths-in-flight, or another --device)");
  need = {5ull << 30, 5ull << 30, "job results"};
  const auto e = error_of([&] { check_device_memory(need, fake_device(8ull << 30, 2ull << 30)); });
  EXPECT_EQ(e.first, ExitCode::DeviceError);
  const std::string expected =
      "buffer 'job results' would be 5.0 GiB but device 'X' allows at most 2.0 GiB per allocation";
  EXPECT_EQ(e.second.substr(0, expected.size()), expected);
  EXPECT_EQ(format_bytes(100), "100 B");
  EXPECT_EQ(format_bytes(1536), "1.5 KiB");
}

class Checkpoint : public ::testing::Test {
 protected:
  // One file per process and test: ctest runs the tests in parallel processes (gtest's random
  // seed, used here before, comes from the clock and two processes drew the same one).
  std::string path_ = (std::filesystem::temp_directory_path() /
                       ("clpt_test_checkpoint_" + std::to_string(::getpid()) + "_" +
                        ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".ckpt"))
                          .string();
  void TearDown() override { std::remove(path_.c_str()); }
};

TEST_F(Checkpoint, RoundTripsTheFilmExactly) {
  const Scene scene = small_scene();
  Film film(4, 3);
  GpuPixelPass p{};
  p.sum[0] = 0.1f, p.sum_sq[0] = 0.01f, p.valid_samples = 2, p.segments = 7;
  film.add_pass(std::vector<GpuPixelPass>(12, p), 0, 3);
  p.sum[1] = 0.5f;
  film.add_pass(std::vector<GpuPixelPass>(12, p), 0, 3);  // half 1
  save_checkpoint(path_, scene, film);
  const Film back = load_checkpoint(path_, scene);
  EXPECT_EQ(back.samples_per_pixel(), 6u);
  EXPECT_EQ(back.half_samples_per_pixel(1), 3u);
  EXPECT_EQ(back.half1_sums(), film.half1_sums());
  EXPECT_EQ(back.half1_valid_counts(), film.half1_valid_counts());
  EXPECT_EQ(back.sums(), film.sums());
  EXPECT_EQ(back.sums_of_squares(), film.sums_of_squares());
  EXPECT_EQ(back.valid_counts(), film.valid_counts());
  EXPECT_EQ(back.total_segments(), 168u);
  EXPECT_EQ(back.dropped_samples(), 24u);
}

// A 4x3 film of two uniform passes of 3 samples (the second in half 1).
Film two_pass_film() {
  Film film(4, 3);
  GpuPixelPass p{};
  p.sum[0] = 0.1f, p.sum_sq[0] = 0.01f, p.valid_samples = 3;
  film.add_pass(std::vector<GpuPixelPass>(12, p), 0, 3);
  film.add_pass(std::vector<GpuPixelPass>(12, p), 0, 3);
  return film;
}

// Makes the checkpoint at `path` an older version's file: its last `newer_bytes` cut, the
// version field rewritten.
void downgrade_checkpoint(const std::string& path, size_t newer_bytes, uint32_t version) {
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - newer_bytes);
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(8);
  f.write(reinterpret_cast<const char*>(&version), sizeof version);
}

// What version 3 added for 12 pixels: the adaptive flag, half-1 sums of squares and sample counts.
constexpr size_t kVersion3Bytes = 1 + 12 * 3 * sizeof(double) + 12 * sizeof(uint32_t);

// A version-1 file (before the half-films: the same bytes without the trailing half-film) is
// still read, with every sample in half 0, so that the resumed passes fill half 1 first.
TEST_F(Checkpoint, ReadsVersion1FilesWithEverythingInHalf0) {
  const Scene scene = small_scene();
  const Film film = two_pass_film();
  save_checkpoint(path_, scene, film);
  downgrade_checkpoint(path_, 8 + 12 * 4 * sizeof(double) + kVersion3Bytes, 1);
  const Film back = load_checkpoint(path_, scene);
  EXPECT_EQ(back.samples_per_pixel(), 6u);
  EXPECT_EQ(back.sums(), film.sums());
  EXPECT_EQ(back.half_samples_per_pixel(0), 6u);
  EXPECT_EQ(back.half_samples_per_pixel(1), 0u);
  EXPECT_EQ(back.next_half(), 1);
}

// A version-2 file (before adaptive sampling) is read as a non-adaptive render with uniform halves.
TEST_F(Checkpoint, ReadsVersion2FilesAsNonAdaptive) {
  const Scene scene = small_scene();
  const Film film = two_pass_film();
  save_checkpoint(path_, scene, film);
  downgrade_checkpoint(path_, kVersion3Bytes, 2);
  const Film back = load_checkpoint(path_, scene);
  EXPECT_EQ(back.half_samples_per_pixel(1), 3u);
  EXPECT_EQ(back.half1_samples(), LargeVector<uint32_t>(12, 3u));
  EXPECT_EQ(back.half1_sums(), film.half1_sums());
  EXPECT_NE(error_of([&] { load_checkpoint(path_, scene, true); }).second.find("adaptively"), std::string::npos);
}

TEST_F(Checkpoint, AdaptiveFilmsKeepEveryPixelsHalfOneSamples) {
  const Scene scene = small_scene();
  Film film(4, 3);
  GpuPixelPass p{};
  p.sum[0] = 0.1f, p.sum_sq[0] = 0.01f, p.valid_samples = 2;
  film.add_pass(std::vector<GpuPixelPass>(12, p), 0, 2);
  film.add_pass(std::vector<GpuPixelPass>(12, p), 0, 2);
  // An adaptive pass: pixel 5 takes 10 of the 12 slots, pixels 0 and 11 one each.
  std::vector<GpuSampleSlot> slots(12, GpuSampleSlot{5, 0});
  slots[0].pixel = 0, slots[11].pixel = 11;
  film.add_pass(std::vector<GpuPixelPass>(12, p), 0, 2, &slots);
  save_checkpoint(path_, scene, film, true);
  const Film back = load_checkpoint(path_, scene, true);
  EXPECT_EQ(back.half1_samples(), film.half1_samples());
  EXPECT_EQ(back.half1_samples()[5], 2u + 20u);
  EXPECT_EQ(back.half1_sums_of_squares(), film.half1_sums_of_squares());
  EXPECT_EQ(back.half_samples_per_pixel(1), 4u);
  EXPECT_EQ(back.samples_per_pixel(), film.samples_per_pixel());
  EXPECT_NE(error_of([&] { load_checkpoint(path_, scene, false); }).second.find("--adaptive"), std::string::npos);
}

TEST_F(Checkpoint, MismatchesNameTheField) {
  const Scene scene = small_scene();
  save_checkpoint(path_, scene, Film(4, 3));
  Scene other = scene;
  other.settings.seed = 2;
  EXPECT_NE(error_of([&] { load_checkpoint(path_, other); }).second.find("seed 1 does not match"), std::string::npos);
  other = scene;
  other.settings.max_bounces = 3;
  EXPECT_NE(error_of([&] { load_checkpoint(path_, other); }).second.find("max_bounces"), std::string::npos);
  other = scene;
  other.file_hash = "fedcba9876543210";
  EXPECT_NE(error_of([&] { load_checkpoint(path_, other); }).second.find("scene"), std::string::npos);
  std::filesystem::resize_file(path_, std::filesystem::file_size(path_) - 8);
  const auto e = error_of([&] { load_checkpoint(path_, scene); });
  EXPECT_EQ(e.first, ExitCode::Usage);
  EXPECT_NE(e.second.find("truncated"), std::string::npos);
}

}  // namespace
}  // namespace clpt
