// The device-free parts of multi-device renders: --device lists (select_devices on made-up device
// lists), the pass's pixel queue, the balanced range size, CLPT_INJECT_FAULT parsing, and how a
// pass's pixels are split over the ranks of an MPI job (render/rank_pass.h).
#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "cl/cl_device.h"
#include "render/fault_injection.h"
#include "render/rank_pass.h"
#include "render/work_queue.h"
#include "util/error.h"

namespace clpt::test {
namespace {

DeviceInfo fake_device(int index, const std::string& name, bool gpu, cl_uint compute_units = 2) {
  DeviceInfo d;
  d.index = index;
  d.name = name;
  d.platform_name = "Fake";
  d.is_gpu = gpu;
  d.is_cpu = !gpu;
  d.type = gpu ? "GPU" : "CPU";
  d.compute_units = compute_units;
  d.clock_mhz = 1000;
  return d;
}

// 0: a CPU, 1: a small GPU, 2: a big GPU, 3: another CPU.
std::vector<DeviceInfo> fake_devices() {
  return {fake_device(0, "pthread-cpu", false), fake_device(1, "Small GPU", true, 20),
          fake_device(2, "Big GPU", true, 100), fake_device(3, "basic-cpu", false)};
}

std::vector<int> indices(const std::vector<DeviceInfo>& devices) {
  std::vector<int> out;
  for (const DeviceInfo& d : devices) out.push_back(d.index);
  return out;
}

// The message of the Usage error `spec` raises ("" when it raises none).
std::string usage_error(const std::string& spec) {
  try {
    select_devices(fake_devices(), spec);
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::Usage) << spec;
    return e.what();
  }
  return "";
}

TEST(DeviceList, SingleEntriesResolveAsSelectDevice) {
  const std::vector<DeviceInfo> all = fake_devices();
  for (const std::string spec : {"", "best", "gpu", "cpu", "0", "3", "small", "BIG"})
    EXPECT_EQ(indices(select_devices(all, spec)), std::vector<int>{select_device(all, spec).index}) << spec;
  EXPECT_EQ(select_device(all, "gpu").index, 2);  // the largest compute units x clock
}

TEST(DeviceList, NthDeviceOfAType) {
  const std::vector<DeviceInfo> all = fake_devices();
  EXPECT_EQ(select_device(all, "gpu:0").index, 1);
  EXPECT_EQ(select_device(all, "gpu:1").index, 2);
  EXPECT_EQ(select_device(all, "cpu:1").index, 3);
  EXPECT_EQ(select_device(all, "CPU:0").index, 0);
}

TEST(DeviceList, AllAndCommaLists) {
  const std::vector<DeviceInfo> all = fake_devices();
  EXPECT_EQ(indices(select_devices(all, "all")), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(indices(select_devices(all, "ALL")), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(indices(select_devices(all, "2,0")), (std::vector<int>{2, 0}));
  EXPECT_EQ(indices(select_devices(all, "gpu:0,cpu")), (std::vector<int>{1, 0}));
  EXPECT_EQ(indices(select_devices(all, "basic,gpu")), (std::vector<int>{3, 2}));
}

TEST(DeviceList, BadEntriesAreUsageErrorsNamingTheEntry) {
  EXPECT_NE(usage_error("0,0").find("--device '0,0': entry '0' names device 0 a second time"), std::string::npos);
  EXPECT_NE(usage_error("all,1").find("entry '1' names device 1 a second time"), std::string::npos);
  EXPECT_NE(usage_error("gpu,gpu:1").find("entry 'gpu:1' names device 2 a second time"), std::string::npos);
  EXPECT_NE(usage_error("7").find("--device '7': no such device"), std::string::npos);
  EXPECT_NE(usage_error("0,7").find("--device '0,7': entry '7': no such device"), std::string::npos);
  EXPECT_NE(usage_error("gpu:2").find("--device 'gpu:2': no such device"), std::string::npos);
  EXPECT_NE(usage_error("cpu:x").find("no such device"), std::string::npos);
  EXPECT_NE(usage_error("all,").find("--device 'all,': empty entry"), std::string::npos);
  EXPECT_NE(usage_error(",0").find("empty entry"), std::string::npos);
  // Every message lists the devices.
  EXPECT_NE(usage_error("0,0").find("available:\n  0: CPU device 'pthread-cpu' (Fake)"), std::string::npos);
}

// A simulator as Oclgrind reports itself: every device-type bit, 1 compute unit at 1 MHz, listed
// first (its platform came first).
DeviceInfo fake_simulator(int index) {
  DeviceInfo d = fake_device(index, "Oclgrind Simulator", true, 1);
  d.platform_name = "Oclgrind";
  d.is_cpu = true;
  d.is_simulator = true;
  return d;
}

TEST(DeviceList, SimulatorsAreNeverTheDefaultBesideRealDevices) {
  // 0: the simulator, 1: a CPU, 2: a GPU.
  const std::vector<DeviceInfo> with_gpu = {fake_simulator(0), fake_device(1, "pthread-cpu", false),
                                            fake_device(2, "Big GPU", true, 100)};
  EXPECT_EQ(best_device(with_gpu).index, 2);
  EXPECT_EQ(select_device(with_gpu, "cpu").index, 1);
  EXPECT_EQ(select_device(with_gpu, "gpu").index, 2);
  EXPECT_EQ(select_device(with_gpu, "gpu:0").index, 2);  // real devices first, then simulators
  EXPECT_EQ(select_device(with_gpu, "gpu:1").index, 0);
  EXPECT_EQ(select_device(with_gpu, "cpu:1").index, 0);
  EXPECT_EQ(select_device(with_gpu, "oclgrind").index, 0);  // by name: picked
  EXPECT_EQ(indices(select_devices(with_gpu, "all")), (std::vector<int>{1, 2}));
  EXPECT_EQ(indices(select_devices(with_gpu, "all,oclgrind")), (std::vector<int>{1, 2, 0}));
  EXPECT_EQ(indices(select_devices(with_gpu, "cpu,oclgrind")), (std::vector<int>{1, 0}));

  // Only a CPU beside it: the CPU is the default, and "gpu" finds only the simulator.
  const std::vector<DeviceInfo> cpu_only = {fake_simulator(0), fake_device(1, "pthread-cpu", false)};
  EXPECT_EQ(best_device(cpu_only).index, 1);
  EXPECT_EQ(select_device(cpu_only, "cpu").index, 1);
  EXPECT_EQ(select_device(cpu_only, "gpu").index, 0);

  // Nothing but the simulator: it is used, and its label says what it is.
  const std::vector<DeviceInfo> alone = {fake_simulator(0)};
  EXPECT_EQ(best_device(alone).index, 0);
  EXPECT_EQ(select_device(alone, "cpu").index, 0);
  EXPECT_EQ(indices(select_devices(alone, "all")), (std::vector<int>{0}));
  EXPECT_EQ(alone[0].label(), "device 'Oclgrind Simulator' (Oclgrind, a simulator)");
}

TEST(PixelRangeQueue, HandsOutEveryPixelOnceAndTakesBackFirst) {
  PixelRangeQueue q(100);
  EXPECT_EQ(q.remaining(), 100u);
  const PixelRange a = q.take(30);
  const PixelRange b = q.take(30);
  EXPECT_EQ(a.begin, 0u);
  EXPECT_EQ(a.count, 30u);
  EXPECT_EQ(b.begin, 30u);
  q.give_back(a);  // its device failed
  EXPECT_EQ(q.remaining(), 70u);
  const PixelRange a1 = q.take(20);  // a range given back goes out first, split as asked
  EXPECT_EQ(a1.begin, 0u);
  EXPECT_EQ(a1.count, 20u);
  const PixelRange a2 = q.take(50);
  EXPECT_EQ(a2.begin, 20u);
  EXPECT_EQ(a2.count, 10u);
  const PixelRange c = q.take(1000);
  EXPECT_EQ(c.begin, 60u);
  EXPECT_EQ(c.count, 40u);
  EXPECT_TRUE(q.empty());
  EXPECT_EQ(q.take(5).count, 0u);
}

TEST(BalancedRange, FollowsTheShareOfWhatIsLeft) {
  // Alone (share 1): the device's own launch size.
  EXPECT_EQ(balanced_range_pixels(5000, 100000, 1.0, 100), 5000u);
  // Plenty left: the launch size is the bound, whatever the share.
  EXPECT_EQ(balanced_range_pixels(5000, 100000, 0.25, 100), 5000u);
  // Near the end of a pass: at most the device's share of what is left...
  EXPECT_EQ(balanced_range_pixels(5000, 8000, 0.25, 100), 2000u);
  EXPECT_EQ(balanced_range_pixels(5000, 8000, 0.75, 100), 5000u);
  // ...but not below the minimum, and never more than is left.
  EXPECT_EQ(balanced_range_pixels(5000, 300, 0.1, 100), 100u);
  EXPECT_EQ(balanced_range_pixels(5000, 50, 0.1, 100), 50u);
  EXPECT_EQ(balanced_range_pixels(5000, 0, 0.5, 100), 0u);
}

TEST(FaultPlan, ParsesBuildAndLaunchFaults) {
  const FaultPlan none = FaultPlan::parse("");
  EXPECT_FALSE(none.fails_build(0));
  EXPECT_FALSE(none.fails_launch(0, 1));
  const FaultPlan plan = FaultPlan::parse("build:1,launch:0:3");
  EXPECT_TRUE(plan.fails_build(1));
  EXPECT_FALSE(plan.fails_build(0));
  EXPECT_TRUE(plan.fails_launch(0, 3));
  EXPECT_FALSE(plan.fails_launch(0, 2));
  EXPECT_FALSE(plan.fails_launch(1, 3));
}

TEST(FaultPlan, RejectsMalformedEntriesNamingTheVariable) {
  for (const std::string bad : {"bogus", "build", "build:", "build:x", "launch:1", "launch:1:0",
                                "launch:1:-2", "build:1,", "launch:1:2:3", "build:-1"}) {
    try {
      FaultPlan::parse(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ExitCode::Usage);
      EXPECT_NE(std::string(e.what()).find("CLPT_INJECT_FAULT='" + bad + "'"), std::string::npos) << e.what();
    }
  }
}

TEST(FaultPlan, ParsesPerturbFactorsPerDeviceAndChannel) {
  const FaultPlan none = FaultPlan::parse("build:0");
  EXPECT_EQ(none.channel_factors(0), (std::array<double, 3>{1, 1, 1}));
  const FaultPlan plan = FaultPlan::parse("perturb:0:G:1.02,perturb:1:R:0.5,perturb:1:R:3,launch:1:2");
  EXPECT_EQ(plan.channel_factors(0), (std::array<double, 3>{1, 1.02, 1}));
  EXPECT_EQ(plan.channel_factors(1), (std::array<double, 3>{1.5, 1, 1}));  // factors multiply
  EXPECT_EQ(plan.channel_factors(2), (std::array<double, 3>{1, 1, 1}));
  EXPECT_FALSE(plan.fails_build(0));  // a perturbation is not a failure
  EXPECT_FALSE(plan.fails_launch(0, 1));
  EXPECT_EQ(FaultPlan::parse("perturb:3:B:2e-1").channel_factors(3), (std::array<double, 3>{1, 1, 0.2}));
}

TEST(FaultPlan, ForDeviceRenumbersThatDevicesFaultsAsDeviceZero) {
  const FaultPlan plan = FaultPlan::parse("perturb:1:G:1.02,build:0,launch:1:4");
  const FaultPlan one = plan.for_device(1);
  EXPECT_EQ(one.channel_factors(0), (std::array<double, 3>{1, 1.02, 1}));
  EXPECT_TRUE(one.fails_launch(0, 4));
  EXPECT_FALSE(one.fails_build(0));  // device 0's build fault stays with device 0
  EXPECT_EQ(one.channel_factors(1), (std::array<double, 3>{1, 1, 1}));
  const FaultPlan zero = plan.for_device(0);
  EXPECT_TRUE(zero.fails_build(0));
  EXPECT_EQ(zero.channel_factors(0), (std::array<double, 3>{1, 1, 1}));
  EXPECT_TRUE(plan.for_device(2).empty());
}

TEST(FaultPlan, RejectsMalformedPerturbEntries) {
  for (const std::string bad : {"perturb", "perturb:0", "perturb:0:G", "perturb:0:G:", "perturb:0:g:1.02",
                                "perturb:0:A:1.02", "perturb:x:G:1.02", "perturb:-1:G:1", "perturb:0:G:0",
                                "perturb:0:G:-1.02", "perturb:0:G:nan", "perturb:0:G:inf", "perturb:0:G:1.02x",
                                "perturb:0:G: 1.02", "perturb:0:G:1e999", "perturb:0:G:1.02:1"}) {
    try {
      FaultPlan::parse(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ExitCode::Usage);
      EXPECT_NE(std::string(e.what()).find("CLPT_INJECT_FAULT='" + bad + "': entry '" + bad + "'"),
                std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("perturb:DEVICE:R|G|B:FACTOR"), std::string::npos) << e.what();
    }
  }
}

TEST(FaultPlan, ParsesDelayAndExitFaults) {
  const FaultPlan plan = FaultPlan::parse("delay:1:30,delay:1:5,exit:3");
  EXPECT_EQ(plan.launch_delay_ms(1), 35u);
  EXPECT_EQ(plan.launch_delay_ms(0), 0u);
  EXPECT_TRUE(plan.exits_at_pass(3));
  EXPECT_FALSE(plan.exits_at_pass(2));
  EXPECT_FALSE(FaultPlan::parse("delay:0:9").exits_at_pass(1));
  for (const char* bad : {"delay:0", "delay:x:5", "delay:0:-1", "exit:0", "exit:", "exit:1:2"})
    EXPECT_THROW(FaultPlan::parse(bad), Error) << bad;
}

// Parts are consecutive, in rank order, cover the range once, and follow the weights.
TEST(RankSplit, PartsCoverTheRangeInOrderByWeight) {
  const std::vector<PixelRange> parts = split_pixels_by_weight({100, 1000}, {1, 3, 0, 1});
  ASSERT_EQ(parts.size(), 4u);
  EXPECT_EQ(parts[0].begin, 100u);
  EXPECT_EQ(parts[0].count, 200u);
  EXPECT_EQ(parts[1].begin, 300u);
  EXPECT_EQ(parts[1].count, 600u);
  EXPECT_EQ(parts[2].count, 0u);  // a failed rank: none
  EXPECT_EQ(parts[3].begin, 900u);
  EXPECT_EQ(parts[3].count, 200u);  // the last working part ends the range
  // Rounding: awkward weights still cover every pixel once.
  const std::vector<PixelRange> odd = split_pixels_by_weight({0, 7}, {0.3, 0.3, 0.3});
  uint32_t next = 0;
  for (const PixelRange& p : odd) {
    EXPECT_EQ(p.begin, next);
    next += p.count;
  }
  EXPECT_EQ(next, 7u);
  // The last working rank need not be the last rank.
  const std::vector<PixelRange> tail = split_pixels_by_weight({0, 10}, {1, 1, 0});
  EXPECT_EQ(tail[1].begin + tail[1].count, 10u);
  EXPECT_EQ(tail[2].count, 0u);
  // No working rank: nothing handed out.
  for (const PixelRange& p : split_pixels_by_weight({0, 10}, {0, 0})) EXPECT_EQ(p.count, 0u);
}

TEST(FaultPlan, InjectedFailureReadsLikeTheClWrapper) {
  try {
    FaultPlan::throw_injected(-5, "clEnqueueNDRangeKernel", "device 'X' (P)");
    ADD_FAILURE() << "did not throw";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::DeviceError);
    EXPECT_EQ(std::string(e.what()),
              "clEnqueueNDRangeKernel failed with CL_OUT_OF_RESOURCES on device 'X' (P) [injected by CLPT_INJECT_FAULT]");
  }
}

}  // namespace
}  // namespace clpt::test
