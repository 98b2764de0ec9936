// The vector-width measurement (host/tools/vector_width.h): the remarks parser on PoCL-shaped
// text, and the probe's child process against stand-in executables (shell scripts), so that
// neither needs PoCL: what the child is given, what comes back, and that failures are reported.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include "render/render_plan.h"
#include "tools/vector_width.h"
#include "util/temporary_directory.h"

namespace clpt::test {
namespace {

// One remark as PoCL prints it: no line break between remarks.
std::string remark(const std::string& text) { return "<unknown>:0:0: " + text; }
std::string vectorised(int width) {
  return remark("vectorized loop (vectorization width: " + std::to_string(width) + ", interleaved count: 1)");
}
const std::string kScalar = remark("loop not vectorized: loop control flow is not understood by vectorizer") +
                            remark("loop not vectorized");
const std::string kCostModel = remark("the cost-model indicates that vectorization is not beneficial");
const std::string kAlready = remark(
    "loop not vectorized: vectorization and interleaving are explicitly disabled, or the loop has already been "
    "vectorized");
std::string compiling_kernel(const std::string& name) {
  return remark("'_Z12get_local_idj' inlined into '" + name + "' with (cost=always): always inliner");
}
std::string compiling_work_group(const std::string& name) {
  return remark("'" + name + "' inlined into '_pocl_kernel_" + name + "_workgroup' with (cost=always)");
}

TEST(VectorWidth, CountsTheWorkGroupFunctionsLoopsOnOneLine) {
  // A kernel whose own source loop vectorises at 8 (left out), whose work-group functions hold
  // loops at 16, 8, 8 and 4, two scalar ones and a vectorised loop's remainder; then a second
  // kernel whose source loop (left out) and work-group loop are both scalar.
  const std::string text = compiling_kernel("render_paths") + vectorised(8) + compiling_work_group("render_paths") +
                           vectorised(16) + vectorised(8) + kAlready + vectorised(8) + kCostModel + vectorised(4) +
                           kScalar + compiling_kernel("film_sum_jobs") + kScalar +
                           compiling_work_group("film_sum_jobs") + kScalar + "\n";
  const VectorWidthReport r = parse_vectoriser_remarks(text);
  ASSERT_TRUE(r.known) << r.why;
  EXPECT_EQ(r.widest, 16u);
  EXPECT_EQ(r.lanes, 8u);  // most loops
  EXPECT_EQ(r.loops_by_width, (std::map<uint32_t, int>{{4, 1}, {8, 2}, {16, 1}}));
  EXPECT_EQ(r.not_vectorised, 3);
  EXPECT_EQ(r.describe(), "8 work-items (vectorised loops: 1 at 16, 2 at 8, 1 at 4; 3 not)");
}

TEST(VectorWidth, ABlockedWorkItemLoopIsOneWorkItem) {
  // As PoCL printed it for a megakernel whose shading SLP had packed (AMD EPYC Zen 4, 2026-12-02):
  // the work-group functions' only vectorised loops were the kernel's own loop over a local array,
  // and their work-item loops stopped at a vector-typed value. A blocker in the kernel as written
  // (before its work-group functions) is not the work-item loops' and is left out.
  const std::string blocked = remark("loop not vectorized: instruction return type cannot be vectorized");
  const std::string call = remark("loop not vectorized: call instruction cannot be vectorized");
  const std::string text = compiling_kernel("render_paths") + call + kScalar + vectorised(8) +
                           compiling_work_group("render_paths") + blocked + kScalar + vectorised(8) + blocked +
                           kScalar + vectorised(8) + call + remark("loop not vectorized") + "\n";
  const VectorWidthReport r = parse_vectoriser_remarks(text);
  ASSERT_TRUE(r.known) << r.why;
  EXPECT_EQ(r.lanes, 1u);
  EXPECT_EQ(r.widest, 8u);
  EXPECT_EQ(r.loops_by_width, (std::map<uint32_t, int>{{8, 2}}));
  EXPECT_EQ(r.not_vectorised, 3);
  EXPECT_EQ(r.blockers, (std::map<std::string, int>{{"call instruction cannot be vectorized", 1},
                                                    {"instruction return type cannot be vectorized", 2}}));
  EXPECT_EQ(r.describe(),
            "1 work-item (work-item loops kept scalar: 1 by call instruction cannot be vectorized, 2 by instruction "
            "return type cannot be vectorized; vectorised loops: 2 at 8; 3 not)");
}

TEST(VectorWidth, WithoutWorkGroupMarksEveryRemarkCounts) {
  const std::string text = "a.cl:3:5: remark: " + vectorised(4).substr(15) + "\n" + "a.cl:9:1: remark: " +
                           vectorised(8).substr(15) + "\n" + kScalar;
  const VectorWidthReport r = parse_vectoriser_remarks(text);
  ASSERT_TRUE(r.known) << r.why;
  EXPECT_EQ(r.widest, 8u);
  EXPECT_EQ(r.lanes, 8u);  // a tie: the wider
  EXPECT_EQ(r.describe(), "8 work-items (vectorised loops: 1 at 8, 1 at 4; 1 not)");
}

TEST(VectorWidth, OnlyScalarLoopsIsOneWorkItem) {
  const VectorWidthReport r = parse_vectoriser_remarks(compiling_work_group("k") + kScalar + kScalar + kCostModel);
  ASSERT_TRUE(r.known) << r.why;
  EXPECT_EQ(r.widest, 1u);
  EXPECT_EQ(r.lanes, 1u);
  EXPECT_TRUE(r.loops_by_width.empty());
  EXPECT_EQ(r.not_vectorised, 3);
  EXPECT_EQ(r.describe(), "1 work-item (no loop vectorised; 3 not)");
}

TEST(VectorWidth, NoRemarksIsUnknown) {
  for (const std::string& text : {std::string(), compiling_kernel("k") + compiling_work_group("k") + "\n",
                                  std::string("clpt: error: something else\n")}) {
    const VectorWidthReport r = parse_vectoriser_remarks(text);
    EXPECT_FALSE(r.known) << text;
    EXPECT_EQ(r.describe(), "unknown (the compiler printed no loop-vectoriser remarks)");
  }
  // A scalable width names no number of work-items: not a loop of known width.
  EXPECT_FALSE(
      parse_vectoriser_remarks(remark("vectorized loop (vectorization width: vscale x 4, interleaved count: 1)")).known);
}

DeviceInfo device(bool pocl_cpu) {
  DeviceInfo d;
  d.index = 3;
  d.is_cpu = pocl_cpu;
  d.is_gpu = !pocl_cpu;
  d.platform_name = pocl_cpu ? "Portable Computing Language" : "NVIDIA CUDA";
  d.name = "test device";
  return d;
}

RenderRequest lockstep_request() {
  RenderRequest request;
  request.scene.file = "scenes/glass.toml";
  request.scene.settings.estimator = "nee";
  request.scene.settings.rr_from = 3;
  request.precision = Precision::Double;
  request.intersection = Intersection::Surface;
  request.megakernel_loop = MegakernelLoop::Lockstep;
  request.scene_loops = SceneLoops::Rolled;
  request.local_size = 32;
  request.cpu_vector_bits = CpuVectorBits::Bits512;
  request.sphere_reads = SphereReads::Selects;
  return request;
}

DevicePlan plan_on(const DeviceInfo& d) {
  DevicePlan plan;
  plan.device = d;
  plan.form = ExecutionForm::Megakernel;
  return plan;
}

TEST(VectorWidth, ProbeArgumentsCarryTheKernelChoices) {
  const std::vector<std::string> args =
      vector_width_probe_arguments(lockstep_request(), plan_on(device(true)), "/tmp/x.pfm");
  std::string joined;
  for (const std::string& a : args) joined += a + " ";
  for (const char* expected :
       {"scenes/glass.toml ", "--device 3 ", "--precision double ", "--form megakernel ",
        "--megakernel-loop lockstep ", "--scene-loops rolled ", "--intersection surface ", "--estimator nee ",
        "--rr-from 3 ", "--local-size 32 ", "--cpu-vector-bits 512 ", "--sphere-reads selects ", "--width 16 --height 8 --spp 1 --sampler jitter --no-cache -q -o /tmp/x.pfm "})
    EXPECT_NE(joined.find(expected), std::string::npos) << expected << " not in: " << joined;
  EXPECT_EQ(joined.find("--generic"), std::string::npos) << joined;
}

// A stand-in for clpt at `path`: a shell script with this body.
void write_script(const std::string& path, const std::string& body) {
  std::ofstream(path) << "#!/bin/sh\n" << body;
  ASSERT_EQ(::chmod(path.c_str(), 0700), 0);
}

TEST(VectorWidth, ProbeRunsTheChildWithFreshCachesAndRemovesThem) {
  const TemporaryDirectory dir("clpt-vector-width-test");
  const std::string record = dir.file("record.txt"), fake = dir.file("fake-clpt");
  // Checks what the child is given, records its cache directory, prints remarks as PoCL does.
  write_script(fake, "[ \"$1\" = render ] || exit 11\n"
                     "[ \"$POCL_VECTORIZER_REMARKS\" = 1 ] || exit 12\n"
                     "[ -d \"$POCL_CACHE_DIR\" ] && [ -z \"$(ls -A \"$POCL_CACHE_DIR\")\" ] || exit 13\n"
                     "[ -d \"$CLPT_CACHE_DIR\" ] && [ -z \"$(ls -A \"$CLPT_CACHE_DIR\")\" ] || exit 14\n"
                     "[ -z \"$CLPT_INJECT_FAULT\" ] || exit 15\n"
                     "echo \"$POCL_CACHE_DIR\" > " + record + "\n"
                     "printf '%s' '" + compiling_work_group("k") + vectorised(16) + "' >&2\n"
                     "printf '%s\\n' '" + vectorised(8) + kScalar + "'\n");
  ASSERT_EQ(::setenv("CLPT_INJECT_FAULT", "build:0", 1), 0);
  const VectorWidthReport r = probe_vector_width(lockstep_request(), plan_on(device(true)), fake);
  ::unsetenv("CLPT_INJECT_FAULT");
  ASSERT_TRUE(r.known) << r.why;
  EXPECT_EQ(r.describe(), "16 work-items (vectorised loops: 1 at 16, 1 at 8; 1 not)");
  std::string cache;
  std::getline(std::ifstream(record), cache);
  ASSERT_FALSE(cache.empty());
  EXPECT_FALSE(std::filesystem::exists(cache)) << cache << " was not removed";
}

TEST(VectorWidth, ProbeFailuresAreUnknownWithTheReason) {
  const TemporaryDirectory dir("clpt-vector-width-test");
  const std::string fails = dir.file("failing-clpt");
  write_script(fails, "echo 'clpt: error: --device 3: no such device' >&2\nexit 2\n");
  EXPECT_EQ(probe_vector_width(lockstep_request(), plan_on(device(true)), fails).describe(),
            "unknown (the probe render exited with status 2: clpt: error: --device 3: no such device)");
  const std::string silent = dir.file("silent-clpt");
  write_script(silent, "exit 0\n");
  EXPECT_EQ(probe_vector_width(lockstep_request(), plan_on(device(true)), silent).describe(),
            "unknown (the compiler printed no loop-vectoriser remarks)");
  const VectorWidthReport missing = probe_vector_width(lockstep_request(), plan_on(device(true)), dir.file("none"));
  EXPECT_FALSE(missing.known);
  EXPECT_NE(missing.why.find("cannot start"), std::string::npos) << missing.why;
  // Not PoCL's CPU device: no child at all (the script would have said otherwise).
  EXPECT_EQ(probe_vector_width(lockstep_request(), plan_on(device(false)), fails).describe(),
            "unknown (the driver does not report it)");
}

}  // namespace
}  // namespace clpt::test
