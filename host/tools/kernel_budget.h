// `clpt kernels budget`: what a device's own OpenCL compiler makes of every kernel of the covering
// set of variants (tools/kernel_variants.h). The gpucc test tier compiles the same variants with
// upstream clang for NVIDIA and AMD targets, without a GPU; this asks the driver of the GPU at
// hand, whose compiler is the one that matters (NVIDIA's ptxas, an AMD stack's own LLVM):
//   * from OpenCL itself, on every device: each kernel's private memory per work-item (spilled
//     registers and off-chip arrays), local memory, and the work-group limits;
//   * from the build log, where the driver writes it: on NVIDIA's driver, built with
//     -cl-nv-verbose, ptxas's registers per thread, stack frame and spill bytes per kernel.
#pragma once

#include <string>
#include <vector>

#include "cl/cl_device.h"
#include "scene/scene.h"
#include "tools/kernel_variants.h"

namespace clpt {

struct KernelBudgetRow {
  std::string variant, kernel;
  double build_seconds = 0;  // the variant's program, from source (no cache)
  uint64_t private_bytes = 0, local_bytes = 0;
  size_t max_work_group = 0, preferred_multiple = 0;
  // From the driver's build log; -1 where it says nothing (every driver but NVIDIA's today).
  int registers = -1, stack_bytes = -1, spill_store_bytes = -1, spill_load_bytes = -1;
};

// What NVIDIA's ptxas reports per entry function in a build log made with -cl-nv-verbose (the
// lines as ptxas -v writes them; the figures are found by their words):
//   ptxas info    : Compiling entry function 'NAME' for 'sm_90'
//   ptxas info    : Function properties for NAME
//       S bytes stack frame, T bytes spill stores, L bytes spill loads
//   ptxas info    : Used R registers, ...
// Fills the rows' log fields by kernel name; rows the log does not name keep -1.
void parse_nvidia_build_log(const std::string& log, std::vector<KernelBudgetRow>& rows);

// Builds `variants` (the CLI: every covering variant, tools/kernel_variants.h) of `diffuse`
// (scenes/diffuse.toml) on `device` and returns a row per kernel, variant by variant. on_variant sees each variant's name before its build (progress);
// on_log sees the first variant's build log where it is parsed (NVIDIA), so that a report shows
// the lines the figures come from.
std::vector<KernelBudgetRow> measure_kernel_budget(const DeviceInfo& device, const Scene& diffuse,
                                                   const std::vector<KernelVariant>& variants,
                                                   void (*on_variant)(const std::string&) = nullptr,
                                                   void (*on_log)(const std::string&) = nullptr);

// The rows as a TAB-separated table with a header; blank where a figure is unknown.
std::string kernel_budget_tsv(const std::vector<KernelBudgetRow>& rows);

}  // namespace clpt
