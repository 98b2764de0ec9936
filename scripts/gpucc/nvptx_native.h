/* nvptx_native.h: force-included (-include) into the nvptx64 compilations of scripts/gpu_compile.sh
 * only, never into a kernel that runs.
 *
 * libclc-14 implements native_powr as exp2(y * log2(x)) on LLVM's exp2/log2 intrinsics, which
 * LLVM 14's NVPTX backend cannot select (it emits a call to an undefined exp2f and stops). NVIDIA's
 * own OpenCL compiler turns native_powr into the PTX approximations lg2.approx and ex2.approx:
 * this header does the same with inline PTX, so that the fast preset (the one user of native_powr,
 * maths.cl pow_unit) compiles with about the instructions and registers the vendor's would give. */
#ifndef CLPT_GPUCC_NVPTX_NATIVE_H
#define CLPT_GPUCC_NVPTX_NATIVE_H

/* x^y for x >= 0 (native_powr's domain), to PTX's approximate accuracy. */
inline float clpt_gpucc_native_powr(float x, float y) {
  float log2_x, r;
  __asm__("lg2.approx.f32 %0, %1;" : "=f"(log2_x) : "f"(x));
  __asm__("ex2.approx.f32 %0, %1;" : "=f"(r) : "f"(y * log2_x));
  return r;
}
#define native_powr clpt_gpucc_native_powr

#endif
