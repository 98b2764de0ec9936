// Renders over several PoCL devices (ctest sets POCL_DEVICES for this process: "pthread pthread"
// for the MultiDeviceIdentical tests, "basic pthread" for MultiDeviceMixed). Random numbers are
// keyed by (seed, pixel, sample) and each pixel of a pass is traced by exactly one device, so
// which device traced a range changes no pixel: the films must be equal, not merely close.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include "cl/cl_device.h"
#include "render_test_util.h"
#include "util/error.h"

namespace clpt::test {
namespace {

// The glass scene, 64x48, grid sampler at 16 spp: exactly one pass, so the films of two renders
// can differ only through how the pass was split among devices and launches.
RenderRequest one_pass_request(const std::string& device, ExecutionForm form) {
  RenderRequest request;
  request.scene = load_book_scene("glass");
  request.scene.settings.width = 64;
  request.scene.settings.height = 48;
  request.scene.settings.spp = 16;
  request.scene.settings.seed = 11;
  request.scene.settings.sampler = Sampler::Grid;
  request.device = device;
  request.form = form;
  request.launch_target_s = 1e-3;  // megakernel: many small ranges, so both devices take some
  request.use_kernel_cache = false;  // tests compile the kernels under test from source
  return request;
}

void expect_equal_films(const Film& a, const Film& b) {
  EXPECT_EQ(a.samples_per_pixel(), b.samples_per_pixel());
  EXPECT_EQ(a.total_samples(), b.total_samples());
  EXPECT_EQ(a.total_segments(), b.total_segments());
  EXPECT_EQ(a.sums(), b.sums());
  EXPECT_EQ(a.sums_of_squares(), b.sums_of_squares());
  EXPECT_EQ(a.valid_counts(), b.valid_counts());
}

// Sets CLPT_INJECT_FAULT for one scope.
struct InjectedFaults {
  explicit InjectedFaults(const char* spec) { setenv("CLPT_INJECT_FAULT", spec, 1); }
  ~InjectedFaults() { unsetenv("CLPT_INJECT_FAULT"); }
};

void require_two_devices() {
  ASSERT_GE(list_devices().size(), 2u) << "POCL_DEVICES should expose two devices to this test";
}

TEST(MultiDeviceIdentical, TwoDevicesGiveTheImageOfOne) {
  require_two_devices();
  for (ExecutionForm form : {ExecutionForm::Megakernel, ExecutionForm::Wavefront}) {
    SCOPED_TRACE(execution_form_name(form));
    RenderReport one_report, two_report;
    const Film one = run_render(one_pass_request("0", form), one_report);
    const Film two = run_render(one_pass_request("all", form), two_report);
    ASSERT_EQ(two_report.devices.size(), 2u);
    EXPECT_EQ(two_report.passes, 1);
    for (const DeviceShare& d : two_report.devices) {
      EXPECT_GT(d.paths, 0u) << d.device << " took no range";
      EXPECT_TRUE(d.failure.empty());
    }
    EXPECT_EQ(two_report.devices[0].paths + two_report.devices[1].paths, two_report.paths);
    expect_equal_films(one, two);
  }
}

// The Sobol sampler over two devices: a pass of one sample, then a resumed pass of the next (each
// render exactly one pass, so only the split among devices and launches can differ).
TEST(MultiDeviceIdentical, SobolTwoDevicesGiveTheImageOfOne) {
  require_two_devices();
  for (ExecutionForm form : {ExecutionForm::Megakernel, ExecutionForm::Wavefront}) {
    SCOPED_TRACE(execution_form_name(form));
    auto two_passes = [&](const std::string& device, std::vector<DeviceShare>* shares) {
      RenderRequest request = one_pass_request(device, form);
      request.scene.settings.width = 128;
      request.scene.settings.height = 96;
      request.scene.settings.sampler = Sampler::Sobol;
      request.scene.settings.spp = 1;
      RenderReport first, second;
      request.resume = run_render(request, first);
      request.scene.settings.spp = 2;
      Film film = run_render(request, second);
      EXPECT_EQ(first.passes, 1);
      EXPECT_EQ(second.passes, 1);
      if (shares) *shares = second.devices;
      return film;
    };
    std::vector<DeviceShare> shares;
    const Film one = two_passes("0", nullptr);
    const Film two = two_passes("all", &shares);
    ASSERT_EQ(shares.size(), 2u);
    for (const DeviceShare& d : shares) EXPECT_GT(d.paths, 0u) << d.device << " took no range";
    EXPECT_EQ(two.samples_per_pixel(), 2u);
    expect_equal_films(one, two);
  }
}

// --target-error over two devices stops at the sample count of one device (the stopping rule
// reads only the samples, pass_schedule.h), with the same image up to the float rounding of pass
// sums (pass sizes follow each run's measured rate).
// The glass scene of one_pass_request with next-event estimation and jitter, stopped at a
// relative error of 0.1 (target) or at 96 spp, adaptive or not, on `device`.
Film render_nee(const std::string& device, bool target, bool adaptive, RenderReport& report) {
  RenderRequest request = one_pass_request(device, ExecutionForm::Megakernel);
  request.scene.settings.estimator = "nee";
  request.scene.settings.sampler = Sampler::Jitter;
  request.scene.settings.spp = 96;
  request.adaptive = adaptive;
  if (target) {
    request.target_error = 0.1;
    request.spp_given = false;
  }
  return run_render(request, report);
}

TEST(MultiDeviceIdentical, TargetErrorStopsAtTheSameSamplesOnTwoDevices) {
  require_two_devices();
  auto render = [](const std::string& device, RenderReport& report) { return render_nee(device, true, false, report); };
  RenderReport one_report, two_report;
  const Film one = render("0", one_report);
  const Film two = render("all", two_report);
  ASSERT_EQ(two_report.devices.size(), 2u);
  EXPECT_EQ(one_report.stop, StopReason::TargetError);
  EXPECT_EQ(two_report.stop, StopReason::TargetError);
  EXPECT_EQ(one.samples_per_pixel(), two.samples_per_pixel());
  EXPECT_EQ(one.half_samples_per_pixel(1), two.half_samples_per_pixel(1));
  expect_same_image(one.mean_rgb(), two.mean_rgb());
}

// Adaptive sampling sizes its passes by the image alone (render/adaptive_sampling.h): one device
// and two give the same passes and so the same film, bit for bit, slots and all; with a target
// error too (jitter: every round's slots hold one sample, the table split at any slot).
TEST(MultiDeviceIdentical, AdaptiveSamplingGivesTheFilmOfOneDevice) {
  require_two_devices();
  for (bool target : {false, true}) {
    SCOPED_TRACE(target ? "target error 0.1" : "96 spp");
    auto render = [&](const std::string& device, RenderReport& report) { return render_nee(device, target, true, report); };
    RenderReport one_report, two_report;
    const Film one = render("0", one_report);
    const Film two = render("all", two_report);
    ASSERT_EQ(two_report.devices.size(), 2u);
    EXPECT_GT(two_report.devices[0].paths, 0u);
    EXPECT_GT(two_report.devices[1].paths, 0u);
    if (target) {
      EXPECT_EQ(two_report.stop, StopReason::TargetError);
    }
    expect_equal_films(one, two);
    EXPECT_EQ(one.half1_samples(), two.half1_samples());
    EXPECT_EQ(one.half1_sums(), two.half1_sums());
  }
}

TEST(MultiDeviceIdentical, FailedLaunchGoesToTheOtherDevice) {
  require_two_devices();
  RenderReport straight_report, report;
  const Film straight = run_render(one_pass_request("0", ExecutionForm::Megakernel), straight_report);
  InjectedFaults faults("launch:1:2");  // device 1's second range fails mid-pass
  const Film film = run_render(one_pass_request("0,1", ExecutionForm::Megakernel), report);
  ASSERT_EQ(report.devices.size(), 2u);
  EXPECT_TRUE(report.devices[0].failure.empty());
  EXPECT_NE(report.devices[1].failure.find("CL_OUT_OF_RESOURCES"), std::string::npos) << report.devices[1].failure;
  EXPECT_EQ(report.devices[1].launches, 1u);  // its first range counted, the failed one retraced
  expect_equal_films(straight, film);
}

TEST(MultiDeviceIdentical, FailedBuildLeavesTheRenderToTheOthers) {
  require_two_devices();
  RenderReport straight_report, report;
  const Film straight = run_render(one_pass_request("1", ExecutionForm::Wavefront), straight_report);
  InjectedFaults faults("build:0");
  const Film film = run_render(one_pass_request("all", ExecutionForm::Wavefront), report);
  EXPECT_NE(report.devices[0].failure.find("clBuildProgram"), std::string::npos);
  EXPECT_EQ(report.devices[0].paths, 0u);
  EXPECT_EQ(report.devices[1].paths, report.paths);
  expect_equal_films(straight, film);
}

TEST(MultiDeviceIdentical, EveryDeviceFailingFailsTheRender) {
  require_two_devices();
  InjectedFaults faults("build:1,launch:0:1");
  RenderReport report;
  try {
    run_render(one_pass_request("all", ExecutionForm::Wavefront), report);
    ADD_FAILURE() << "the render did not fail";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::DeviceError);
    const std::string message = e.what();
    EXPECT_NE(message.find("every device failed"), std::string::npos) << message;
    EXPECT_NE(message.find("device 0 ("), std::string::npos) << message;
    EXPECT_NE(message.find("device 1 ("), std::string::npos) << message;
  }
}

// A single-threaded `basic` device beside the multi-threaded `pthread` one, on the same cores.
// Work is pulled by throughput, so each device's share of the samples should equal its share of
// the combined throughput. From the report: share_i = r_i b_i / sum_j r_j b_j, with r_i its
// paths/s while busy and b_i its busy time, so the two shares differ only as far as the busy
// times differ, i.e. as far as a device idled while another finished a pass; the balancing
// keeps that to the pass tails, where ranges shrink to each device's share of what is left.
// Hence two checks. (1) The busy times are within 20% of each other (the shorter at least 0.8 of
// the longer): the balancing leaves only the pass tails and the first launches (PoCL compiles
// each kernel of each device at its first launch; a warm-up render first makes that a load from
// PoCL's cache) to one device alone. A split fixed in advance, tried by changing the scheduler,
// gave 0.70-0.73 here (measured), the faster device waiting at every pass end. Idle time common
// to both devices (the host between passes, a loaded machine) does not enter this ratio, nor the
// shares. (2) Each device's share is within 0.1 of its throughput share (measured differences
// 0.002-0.04); with busy times within 20%, share_i / throughput share_i lies in [0.8, 1.25].
TEST(MultiDeviceMixed, SharesFollowThroughput) {
  require_two_devices();
  RenderRequest request;
  request.scene = load_book_scene("diffuse");
  request.scene.settings.width = 32;
  request.scene.settings.height = 24;
  request.scene.settings.spp = 16;
  request.scene.settings.seed = 3;
  request.scene.settings.sampler = Sampler::Jitter;
  request.device = "all";
  request.use_kernel_cache = false;
  RenderReport warm_up;
  run_render(request, warm_up);

  request.scene.settings.width = 128;
  request.scene.settings.height = 96;
  request.scene.settings.spp = 128;
  RenderReport report;
  const Film film = run_render(request, report);
  ASSERT_EQ(film.samples_per_pixel(), 128u);
  ASSERT_EQ(report.devices.size(), 2u);
  double rate_sum = 0, busy_min = 1e300, busy_max = 0;
  for (const DeviceShare& d : report.devices) {
    ASSERT_GT(d.busy_seconds, 0) << d.device << " did no work";
    rate_sum += double(d.paths) / d.busy_seconds;
    busy_min = std::min(busy_min, d.busy_seconds);
    busy_max = std::max(busy_max, d.busy_seconds);
  }
  EXPECT_GE(busy_min, 0.8 * busy_max) << "one device idled while the other worked";
  for (const DeviceShare& d : report.devices) {
    const double share = double(d.paths) / double(report.paths);
    const double throughput_share = double(d.paths) / d.busy_seconds / rate_sum;
    std::printf("%s: share %.3f, throughput share %.3f, busy %.2f of %.2f s\n", d.device.c_str(), share,
                throughput_share, d.busy_seconds, report.render_seconds);
    EXPECT_GT(share, 0.05) << d.device << " got (almost) no work";
    EXPECT_NEAR(share, throughput_share, 0.1) << d.device;
  }
}

}  // namespace
}  // namespace clpt::test
