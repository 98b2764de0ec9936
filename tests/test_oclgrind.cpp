// The Oclgrind tier (label `oclgrind`; docs/oclgrind.md). ctest gives these tests a vendors
// directory (OCL_ICD_VENDORS) holding the system's ICDs and Oclgrind's, and turns on Oclgrind's
// API check (OCLGRIND_CHECK_API=1) and data-race detection (OCLGRIND_DATA_RACES=1); its
// out-of-bounds check is always on. Its uninitialised-value check (OCLGRIND_UNINITIALIZED) stays
// off: in Oclgrind 21.10 that checker does not know LLVM's `freeze` instruction, which clang 14
// emits in render_paths, and stops the kernel at the first one ("OCLGRIND FATAL ERROR ...
// Unsupported instruction: freeze"); every report after that is a consequence (film_sum_jobs
// reading results the stopped kernel never wrote), so the check cannot tell us anything here.
//
//   OclgrindChecks.*    each check, shown to report a deliberate bug (tests/kernels/probe_oclgrind.cl,
//                       and a failing API call): an empty capture below means the checks ran
//   KernelVariants/OclgrindVariant.*  every variant of covering_kernel_variants() rendered on
//                       Oclgrind: no finding at all, and the image of the same request on PoCL
//   OclgrindMixed.*     one render over PoCL and Oclgrind together
//   OclgrindAreaLights.*  the Cornell box under nee (emitting triangles as lights) in both forms
//   OclgrindAdaptive.*  adaptive sampling's slotted passes in both forms
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>
#include <ostream>
#include <utility>

#include "cl/cl_context.h"
#include "cl/cl_device.h"
#include "kernels/kernel_source.h"
#include "oclgrind_test_util.h"
#include "render_test_util.h"
#include "tools/kernel_variants.h"

namespace clpt {
// gtest prints a failing test's parameter: the variant's name rather than its bytes.
void PrintTo(const KernelVariant& variant, std::ostream* out) { *out << variant.name(); }
}  // namespace clpt

namespace clpt::test {
namespace {

#define REQUIRE_OCLGRIND()                     \
  do {                                         \
    std::string why;                           \
    if (!oclgrind_present(why)) FAIL() << why; \
  } while (0)

// The Oclgrind device, for the probes.
DeviceInfo oclgrind_device() { return select_device(list_devices(), "oclgrind"); }

// A kernel of tests/kernels/probe_oclgrind.cl built on `ctx` (a kernel keeps its program alive).
Kernel probe_kernel(DeviceContext& ctx, const char* name) {
  const ProgramHandle program =
      ctx.build_program(assemble_kernel_source("probe_oclgrind.cl"), "-cl-std=CL1.2", "probe_oclgrind.cl");
  return Kernel(program.get(), name, ctx.where());
}

TEST(OclgrindChecks, OutOfBoundsWriteIsReported) {
  REQUIRE_OCLGRIND();
  StderrCapture capture("probe");
  {
    DeviceContext ctx(oclgrind_device());
    Kernel kernel = probe_kernel(ctx, "probe_out_of_bounds");
    Buffer out(ctx, 16 * sizeof(cl_uint), CL_MEM_READ_WRITE, "probe");
    kernel.set_arg(0, out);
    ctx.launch(kernel, 16, 16, "probe_out_of_bounds");
    ctx.finish();
  }
  const OclgrindFindings f = capture.finish();
  EXPECT_EQ(f.invalid_access, 1) << f.summary();
  EXPECT_NE(f.text.find("Invalid write of size 4"), std::string::npos) << f.summary();
}

TEST(OclgrindChecks, DataRaceIsReported) {
  REQUIRE_OCLGRIND();
  StderrCapture capture("probe");
  {
    DeviceContext ctx(oclgrind_device());
    Kernel kernel = probe_kernel(ctx, "probe_data_race");
    Buffer out(ctx, sizeof(cl_uint), CL_MEM_READ_WRITE, "probe");
    kernel.set_arg(0, out);
    ctx.launch(kernel, 8, 8, "probe_data_race");
    ctx.finish();
  }
  const OclgrindFindings f = capture.finish();
  EXPECT_GE(f.data_race, 1) << f.summary() << "\n(is OCLGRIND_DATA_RACES=1 in the test's environment?)";
}

TEST(OclgrindChecks, FailedApiCallIsReported) {
  REQUIRE_OCLGRIND();
  StderrCapture capture("probe");
  cl_int err = CL_SUCCESS;
  {
    DeviceContext ctx(oclgrind_device());
    Kernel kernel = probe_kernel(ctx, "probe_data_race");
    const cl_uint wrong = 0;  // the argument is a buffer: a 4-byte value is the wrong size
    err = clSetKernelArg(kernel.get(), 0, sizeof wrong, &wrong);
  }
  const OclgrindFindings f = capture.finish();
  EXPECT_EQ(err, CL_INVALID_ARG_SIZE);
  EXPECT_EQ(f.api_error, 1) << f.summary() << "\n(is OCLGRIND_CHECK_API=1 in the test's environment?)";
}

// The variants render the book's diffuse scene (apply_variant) at 15x11 with 16 jittered samples
// per pixel (one pixel is 0.61% of the image; 2640 paths, which Oclgrind traces in seconds). 165
// pixels, odd, so no pass of fewer than 64 samples fills whole 64-path lockstep work-groups: the
// last group of every launch runs dead copies, which must neither read nor write out of bounds.
constexpr int kWidth = 15, kHeight = 11;
constexpr int64_t kSpp = 16;
constexpr uint64_t kSeed = 2718;

// The variants' seed: kSeed, or CLPT_OCLGRIND_SEED where set, which only measures the same-seed
// bounds below at other seeds (docs/oclgrind.md); the tier runs without it.
uint64_t variant_seed() {
  const char* seed = std::getenv("CLPT_OCLGRIND_SEED");
  return seed && *seed ? std::strtoull(seed, nullptr, 10) : kSeed;
}

RenderRequest variant_request(const KernelVariant& variant, const std::string& device) {
  RenderRequest request;
  request.use_kernel_cache = false;  // tests compile the kernels under test from source
  request.scene = load_book_scene("diffuse");
  request.scene.settings.width = kWidth;
  request.scene.settings.height = kHeight;
  request.scene.settings.spp = kSpp;
  request.scene.settings.seed = variant_seed();
  request.scene.settings.sampler = Sampler::Jitter;
  apply_variant(variant, request);
  request.device = device;
  // One launch per pass rather than watchdog-sized ones: each launch costs Oclgrind 0.1-0.3 s
  // whatever its size, and a lockstep launch smaller than its 64-path work-group is mostly dead
  // copies, so the measured rate sizes the next launch as small again. At 75 ms, 1454 launches
  // took 147 s for one variant; launches over part of a pass are covered by OclgrindMixed.
  request.launch_target_s = 0;
  // The wavefront's smallest pool: every pass refills its slots many times, and Oclgrind's race
  // detector, whose cost follows the size of the buffers, runs 3x faster than with the default
  // 65536 slots it gives a "GPU" (10.7 s against 3.2 s at 4 spp).
  request.paths_in_flight = 64;
  return request;
}

// Same-seed bounds per variant, from the measured agreement of Oclgrind and PoCL (Oclgrind 21.10,
// PoCL 3.1; measured with CLPT_OCLGRIND_SEED at this test's seed and others): the smallest
// fraction of the 495 values within 1e-4 relative and the largest relative difference of a
// channel's image mean.
// Both devices run the variant's own form and loop; they differ in compilers (Oclgrind
// interprets clang 14's IR, PoCL compiles with LLVM 15 for this CPU), so in contractions and in
// what fast maths makes of powr/sin/cos, which can send a rare path elsewhere: only `fast`
// variants ever differed; the Pbr ball's thin transmission under a punctual light, fast, moves
// about a tenth of the values (every lobe's direction goes through native sin/cos), its means
// 3e-4 to 6e-4. A bound allows one pixel (3 values, 0.61%) more than the worst measured; the
// means' bound is 1e-6 where no path moved (at most 1.5e-8 measured; 1e-5 for the fast variants),
// 1e-2 where one did (a path carried elsewhere moves an image this small by up to a few 1e-3).
// The 12-dimension set's table (2026-12-04: 17 variants at two seeds, all 100% but the fast
// transmission ones, 89.09% and 98.38% the worst) lost its names when the environment, textures
// and first-hit layers joined the dimensions; a variant not listed gets the loosest bound of the
// table until it is measured again (docs/oclgrind.md).
struct SameSeedBound {
  double close_fraction;  // at least this fraction of values within 1e-4 relative
  double mean_relative;   // every channel's image mean within this, relative
};
const std::map<std::string, SameSeedBound>& same_seed_bounds() {
  // measured at this seed, 2026-12-06, Intel Xeon (skylake-avx512) VM: fraction, means
  static const std::map<std::string, SameSeedBound> bounds = {
      // 100.00%, 1.2e-08
      {"megakernel-lockstep.robust.nee.no-rr.generic.rolled.phong.no-glass.spheres.pbr-transmission.spot.perspective."
       "environment-image.no-aovs.no-textures",
       {0.9939, 1e-6}},
      // 88.28%, 5.5e-04
      {"megakernel-path.fast.nee.rr.specialised.unrolled.no-phong.glass.spheres.pbr-transmission.spot.perspective."
       "no-environment.no-aovs.no-textures",
       {0.8767, 1e-2}},
  };
  return bounds;
}
SameSeedBound bound_for(const KernelVariant& variant) {
  const auto& bounds = same_seed_bounds();
  if (auto it = bounds.find(variant.name()); it != bounds.end()) return it->second;
  std::printf("%s: no measured same-seed bound yet; the table's loosest applies\n", variant.name().c_str());
  SameSeedBound loosest{1, 0};
  for (const auto& [name, b] : bounds) {
    loosest.close_fraction = std::min(loosest.close_fraction, b.close_fraction);
    loosest.mean_relative = std::max(loosest.mean_relative, b.mean_relative);
  }
  return loosest;
}

class OclgrindVariant : public ::testing::TestWithParam<KernelVariant> {};

TEST_P(OclgrindVariant, NoFindingsAndThePoclImage) {
  REQUIRE_OCLGRIND();
  const KernelVariant& variant = GetParam();
  RenderReport oclgrind_report, pocl_report;
  StderrCapture capture("render");
  const Film on_oclgrind = run_render(variant_request(variant, "oclgrind"), oclgrind_report);
  const OclgrindFindings findings = capture.finish();
  EXPECT_TRUE(findings.clean()) << variant.name() << ": Oclgrind reported (" << capture.path() << "): "
                                << findings.summary();
  ASSERT_EQ(oclgrind_report.devices.size(), 1u);
  EXPECT_NE(oclgrind_report.device.find("simulator"), std::string::npos) << oclgrind_report.device;
  EXPECT_EQ(oclgrind_report.paths, uint64_t(kWidth) * kHeight * kSpp);

  const Film on_pocl = run_render(variant_request(variant, "cpu"), pocl_report);
  EXPECT_EQ(pocl_report.device.find("simulator"), std::string::npos) << pocl_report.device;
  const SameSeedAgreement a = same_seed_agreement(on_oclgrind.mean_rgb(), on_pocl.mean_rgb());
  const SameSeedBound bound = bound_for(variant);
  std::printf("%s: Oclgrind against PoCL, same seed: %s (%d launches on Oclgrind, %.1f s)\n",
              variant.name().c_str(), a.describe().c_str(), int(oclgrind_report.launches),
              oclgrind_report.render_seconds);
  EXPECT_GE(a.close_fraction, bound.close_fraction) << variant.name() << ": " << a.describe();
  EXPECT_LE(a.worst_mean_difference(), bound.mean_relative) << variant.name() << ": " << a.describe();
  // The first-hit layers (--aovs variants): the same on both, up to a path that moved (the same
  // fraction of values as the image's bound; a value within 1e-4 of the larger, or 1e-4 absolute).
  ASSERT_EQ(on_oclgrind.has_aovs(), variant.aovs());
  if (!variant.aovs()) return;
  const std::vector<float> la = on_oclgrind.aov_means(), lb = on_pocl.aov_means();
  ASSERT_EQ(la.size(), lb.size());
  size_t close = 0;
  for (size_t i = 0; i < la.size(); ++i)
    close += std::abs(la[i] - lb[i]) <= 1e-4f * std::max(1.0f, std::max(std::abs(la[i]), std::abs(lb[i]))) ? 1 : 0;
  std::printf("%s: first-hit layers, Oclgrind against PoCL: %.2f%% of values within 1e-4\n", variant.name().c_str(),
              100.0 * double(close) / double(la.size()));
  EXPECT_GE(double(close) / double(la.size()), bound.close_fraction) << variant.name() << ": first-hit layers";
}

// A render of scenes/NAME.toml at w x h, spp samples of `sampler`, this file's seed, on `device`.
RenderRequest small_request(const std::string& scene, int w, int h, int64_t spp, Sampler sampler,
                            const std::string& device) {
  RenderRequest request = scene_request(scene, w, h, kSeed, sampler);
  request.scene.settings.spp = spp;
  request.device = device;
  return request;
}

// One render over two implementations at once, PoCL's CPU device and Oclgrind (`--device
// cpu,oclgrind`: one film, each device with its own context and program): no Oclgrind finding,
// both devices traced pixels, and the film is the PoCL-only film of the same request up to the
// same-seed bound.
// Why Oclgrind gets work although it is about 1000x slower: the pool hands every device its first
// range of a pass before the device threads start (DevicePool::run_pass), and before any
// throughput is measured that range is image_pixels / 64 pixels (later passes would give it at
// least as much again, beside its tiny share of the throughput). The render is one pass, which
// keeps the test to one Oclgrind range: the grid sampler's period is 16 samples and the first
// pass is one period. Oclgrind then traces 1/64 of the pixels (12 of 768, all 16 samples, from
// pixel 12 on: a range that starts mid-image, which the single-device variants' whole-pass
// launches do not exercise). Were those pixels wrong, at most 98.4% of the values could agree:
// the 99% bound would fail.
TEST(OclgrindMixed, PoclAndOclgrindShareOneFilm) {
  REQUIRE_OCLGRIND();
  auto request_on = [](const std::string& device) {
    return small_request("diffuse", 32, 24, 16, Sampler::Grid, device);
  };
  RenderReport mixed_report, pocl_report;
  StderrCapture capture("render");
  const Film mixed = run_render(request_on("cpu,oclgrind"), mixed_report);
  const OclgrindFindings findings = capture.finish();
  EXPECT_TRUE(findings.clean()) << "Oclgrind reported (" << capture.path() << "): " << findings.summary();
  const Film pocl = run_render(request_on("cpu"), pocl_report);
  ASSERT_EQ(mixed_report.devices.size(), 2u);
  uint64_t paths = 0;
  for (const DeviceShare& d : mixed_report.devices) {
    EXPECT_GT(d.paths, 0u) << d.device << " traced nothing";
    EXPECT_TRUE(d.failure.empty()) << d.device << ": " << d.failure;
    std::printf("  %s: %llu paths in %llu ranges\n", d.device.c_str(), (unsigned long long)d.paths,
                (unsigned long long)d.launches);
    paths += d.paths;
  }
  EXPECT_NE(mixed_report.devices[1].device.find("simulator"), std::string::npos) << mixed_report.devices[1].device;
  EXPECT_EQ(paths, 32u * 24u * 16u);
  EXPECT_EQ(mixed_report.passes, 1);
  const SameSeedAgreement a = same_seed_agreement(mixed.mean_rgb(), pocl.mean_rgb());
  std::printf("PoCL + Oclgrind against PoCL alone, same seed: %s\n", a.describe().c_str());
  EXPECT_GE(a.close_fraction, 0.99) << a.describe();
  EXPECT_LE(a.worst_mean_difference(), 1e-4) << a.describe();
}

// Renders make("oclgrind") and make("cpu"): no Oclgrind finding, `paths` paths traced on the
// simulator, and PoCL's image within the specialised robust variants' same-seed bound (float
// rounding only). Returns the two films, Oclgrind's first.
std::pair<Film, Film> expect_clean_and_the_pocl_image(const std::function<RenderRequest(const std::string&)>& make,
                                                      const std::string& label, uint64_t paths) {
  RenderReport oclgrind_report, pocl_report;
  StderrCapture capture("render");
  Film on_oclgrind = run_render(make("oclgrind"), oclgrind_report);
  const OclgrindFindings findings = capture.finish();
  EXPECT_TRUE(findings.clean()) << label << ": Oclgrind reported (" << capture.path() << "): " << findings.summary();
  EXPECT_NE(oclgrind_report.device.find("simulator"), std::string::npos) << oclgrind_report.device;
  EXPECT_EQ(oclgrind_report.paths, paths);
  Film on_pocl = run_render(make("cpu"), pocl_report);
  const SameSeedAgreement a = same_seed_agreement(on_oclgrind.mean_rgb(), on_pocl.mean_rgb());
  std::printf("%s: Oclgrind against PoCL, same seed: %s (%.1f s on Oclgrind)\n", label.c_str(), a.describe().c_str(),
              oclgrind_report.render_seconds);
  EXPECT_GE(a.close_fraction, 0.9939) << label << ": " << a.describe();
  EXPECT_LE(a.worst_mean_difference(), 1e-6) << label << ": " << a.describe();
  return {std::move(on_oclgrind), std::move(on_pocl)};
}

// The kernel with triangle lights (CLPT_HAS_TRIANGLE_LIGHTS: nee on a scene with an emitting
// mesh; the covering set's scene has none) on Oclgrind: the Cornell box at 11x9 (odd, as above),
// 8 jittered samples, in the per-path megakernel (what a GPU runs) and the wavefront. No finding
// at all, and the PoCL image of the same request: the same bound as the specialised robust
// variants' (float rounding only; measured 2026-12-02: see the printed agreement).
TEST(OclgrindAreaLights, CornellBoxNeeHasNoFindingsAndThePoclImage) {
  REQUIRE_OCLGRIND();
  for (ExecutionForm form : {ExecutionForm::Megakernel, ExecutionForm::Wavefront}) {
    const char* form_name = form == ExecutionForm::Megakernel ? "megakernel-path" : "wavefront";
    auto request_on = [form](const std::string& device) {
      RenderRequest request = small_request("cornell-box", 11, 9, 8, Sampler::Jitter, device);
      request.scene.settings.estimator = "nee";
      request.form = form;
      request.megakernel_loop = MegakernelLoop::PerPath;
      request.launch_target_s = 0;  // one launch per pass (variant_request says why)
      request.paths_in_flight = 64;
      return request;
    };
    expect_clean_and_the_pocl_image(request_on, std::string("Cornell box, nee, ") + form_name, 11u * 9u * 8u);
  }
}

// Adaptive sampling's slotted passes (kernels/film.cl job_pixel/job_sample: a slot buffer read by
// every job) in both forms on the simulator: no finding, and PoCL's image of the same seed. 15x11
// at 20 spp, next-event estimation: the uniform start to 16, then two rounds of slots (16 to 18
// and 18 to 20), each slot one jittered sample.
TEST(OclgrindAdaptive, SlottedPassesInBothForms) {
  REQUIRE_OCLGRIND();
  for (ExecutionForm form : {ExecutionForm::Megakernel, ExecutionForm::Wavefront}) {
    SCOPED_TRACE(execution_form_name(form));
    auto request_on = [form](const std::string& device) {
      RenderRequest request = small_request("diffuse", kWidth, kHeight, 20, Sampler::Jitter, device);
      request.scene.settings.estimator = "nee";
      request.adaptive = true;
      request.form = form;
      request.megakernel_loop = MegakernelLoop::Lockstep;
      request.launch_target_s = 0;
      request.paths_in_flight = 64;
      return request;
    };
    const auto [on_oclgrind, on_pocl] = expect_clean_and_the_pocl_image(
        request_on, std::string("adaptive, ") + execution_form_name(form), uint64_t(kWidth) * kHeight * 20);
    EXPECT_EQ(on_oclgrind.half1_samples(), on_pocl.half1_samples());  // the same allocation
  }
}

// The hit sphere read by selects (--sphere-reads selects, CLPT_NO_FAST_GATHER: what the lockstep
// megakernel runs on CPUs without fast gathers, docs/performance.md) on the simulator: the selects
// over the loop's spheres and the path state kept in local memory between segments, for each
// estimator. Oclgrind is no such CPU, so `auto` never picks this path there, and the covering
// variants above do not reach it. No finding, and the PoCL image of the same request (PoCL also
// reads by selects): the bound of the specialised robust variants.
TEST(OclgrindSphereReads, SelectsInTheLockstepMegakernel) {
  REQUIRE_OCLGRIND();
  for (const char* estimator : {"book", "nee"}) {
    auto request_on = [estimator](const std::string& device) {
      RenderRequest request = small_request("diffuse", kWidth, kHeight, kSpp, Sampler::Jitter, device);
      request.scene.settings.estimator = estimator;
      request.sphere_reads = SphereReads::Selects;
      request.form = ExecutionForm::Megakernel;
      request.megakernel_loop = MegakernelLoop::Lockstep;
      request.launch_target_s = 0;  // one launch per pass (variant_request says why)
      return request;
    };
    expect_clean_and_the_pocl_image(request_on, std::string("sphere reads by selects, ") + estimator,
                                    uint64_t(kWidth) * kHeight * kSpp);
  }
}

std::string variant_test_name(const ::testing::TestParamInfo<KernelVariant>& info) {
  std::string name = info.param.name();
  for (char& c : name)
    if (c == '.' || c == '-') c = '_';
  return name;
}

// The covering set in two parts: its first variants, which between them hold every value of every
// dimension (label oclgrind, the default run), and the rest, which complete every pair (label
// oclgrind-pairs, tests/CMakeLists.txt: each costs Oclgrind and PoCL a cold build of its kernels,
// 30-260 s on 2 cores, too much for every CI run; docs/oclgrind.md).
std::vector<KernelVariant> variants_with_every_value() {
  std::vector<KernelVariant> all = covering_kernel_variants();
  all.resize(value_covering_prefix(all));
  return all;
}
std::vector<KernelVariant> variants_completing_the_pairs() {
  std::vector<KernelVariant> all = covering_kernel_variants();
  all.erase(all.begin(), all.begin() + std::ptrdiff_t(value_covering_prefix(all)));
  return all;
}

INSTANTIATE_TEST_SUITE_P(KernelVariants, OclgrindVariant, ::testing::ValuesIn(variants_with_every_value()),
                         variant_test_name);
INSTANTIATE_TEST_SUITE_P(KernelVariantPairs, OclgrindVariant, ::testing::ValuesIn(variants_completing_the_pairs()),
                         variant_test_name);

}  // namespace
}  // namespace clpt::test
