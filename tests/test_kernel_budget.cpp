// `clpt kernels budget` (tools/kernel_budget.h): the parse of NVIDIA's ptxas lines in a build log,
// on a log written the way the driver writes it, and the table on PoCL, where OpenCL's own
// figures are there and the log's are blank.
#include <gtest/gtest.h>

#include <algorithm>

#include "device_test_util.h"
#include "scene/scene_loader.h"
#include "tools/kernel_budget.h"
#include "tools/kernel_variants.h"

namespace clpt {
namespace {

TEST(KernelBudget, ParsesNvidiaPtxasLinesPerKernel) {
  std::vector<KernelBudgetRow> rows(3);
  rows[0].kernel = "render_paths";
  rows[1].kernel = "film_sum_jobs";
  rows[2].kernel = "not_in_the_log";
  const std::string log =
      "ptxas info    : 0 bytes gmem\n"
      "ptxas info    : Compiling entry function 'film_sum_jobs' for 'sm_90'\n"
      "ptxas info    : Function properties for film_sum_jobs\n"
      "    0 bytes stack frame, 0 bytes spill stores, 0 bytes spill loads\n"
      "ptxas info    : Used 18 registers, 392 bytes cmem[0]\n"
      "ptxas info    : Compiling entry function 'render_paths' for 'sm_90'\n"
      "ptxas info    : Function properties for render_paths\n"
      "    96 bytes stack frame, 40 bytes spill stores, 44 bytes spill loads\n"
      "ptxas info    : Used 255 registers, 520 bytes cmem[0], 8 bytes cmem[2]\n";
  parse_nvidia_build_log(log, rows);
  EXPECT_EQ(rows[0].registers, 255);
  EXPECT_EQ(rows[0].stack_bytes, 96);
  EXPECT_EQ(rows[0].spill_store_bytes, 40);
  EXPECT_EQ(rows[0].spill_load_bytes, 44);
  EXPECT_EQ(rows[1].registers, 18);
  EXPECT_EQ(rows[1].stack_bytes, 0);
  EXPECT_EQ(rows[2].registers, -1);
  EXPECT_EQ(rows[2].stack_bytes, -1);

  // The same figures prefixed as a driver may relay them.
  std::vector<KernelBudgetRow> relayed(1);
  relayed[0].kernel = "wf_shade";
  parse_nvidia_build_log(
      "ptxas info    : Compiling entry function 'wf_shade' for 'sm_90'\n"
      "ptxas info    : Function properties for wf_shade\n"
      "ptxas         .     192 bytes stack frame, 8 bytes spill stores, 12 bytes spill loads\n"
      "ptxas info    : Used 166 registers, used 0 barriers, 192 bytes cumulative stack size\n",
      relayed);
  EXPECT_EQ(relayed[0].registers, 166);
  EXPECT_EQ(relayed[0].stack_bytes, 192);
  EXPECT_EQ(relayed[0].spill_store_bytes, 8);
  EXPECT_EQ(relayed[0].spill_load_bytes, 12);
}

// The covering set's first variants, which hold every value of every dimension between them (the
// Oclgrind tier renders the same programs on PoCL, so with PoCL's cache warm they cost little); the
// whole set is `clpt kernels budget`'s, run by scripts/gpu_compile.sh and the GPU report.
TEST(KernelBudget, TabulatesEveryKernelOfTheValueCoveringVariantsOnTheTestDevice) {
  const Scene diffuse = load_scene_file(std::string(CLPT_SOURCE_DIR) + "/scenes/diffuse.toml");
  std::vector<KernelVariant> variants = covering_kernel_variants();
  variants.resize(value_covering_prefix(variants));
  const auto rows = measure_kernel_budget(test::test_device().device(), diffuse, variants);
  ASSERT_FALSE(rows.empty());
  bool megakernel = false, wavefront_shade = false;
  for (const KernelBudgetRow& r : rows) {
    megakernel |= r.kernel == "render_paths";
    wavefront_shade |= r.kernel == "wf_shade";
    EXPECT_GT(r.max_work_group, 0u) << r.variant << " " << r.kernel;
    EXPECT_EQ(r.registers, -1) << "PoCL writes no ptxas lines";
  }
  EXPECT_TRUE(megakernel && wavefront_shade);
  const std::string tsv = kernel_budget_tsv(rows);
  EXPECT_EQ(tsv.substr(0, tsv.find('\n')),
            "variant\tkernel\tbuild_s\tregisters\tstack_bytes\tspill_store_bytes\tspill_load_bytes\t"
            "private_bytes\tlocal_bytes\tmax_work_group\tpreferred_multiple");
  EXPECT_EQ(size_t(std::count(tsv.begin(), tsv.end(), '\n')), rows.size() + 1);
}

}  // namespace
}  // namespace clpt
