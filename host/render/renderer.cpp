#include "render/renderer.h"

#include <chrono>

#include "kernels/kernel_source.h"

namespace clpt {

ProgramHandle Renderer::build(DeviceContext& ctx, const std::string& entry_file,
                              const KernelFeatures& features) {
  build_options_ = kernel_build_options(features);
  const auto start = std::chrono::steady_clock::now();
  ProgramHandle program = ctx.build_program(assemble_kernel_source(entry_file), build_options_, entry_file);
  build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return program;
}

}  // namespace clpt
