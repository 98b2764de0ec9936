/* cpu_tuning.h: CLPT_KERNEL, the qualifier every kernel entry point is declared with.
 *
 * PoCL vectorises a kernel across work-items with LLVM's loop vectoriser, whose width comes from
 * the target's preferred vector width. LLVM 15 tunes Intel's AVX-512 CPUs (and PoCL names this
 * machine's "skylake-avx512" whatever its vendor) to prefer 256-bit vectors, and PoCL passes no
 * option that reaches it. The tuning of one function can be changed from the source, though:
 * target("tune=CPU") keeps the instruction set of the device and takes only the tuning (costs,
 * scheduling, preferred width) of CPU. With CLPT_TUNE_CPU set to a CPU that has no 256-bit
 * preference, the work-item loops are 512 bits wide: 16 float or 8 double lanes.
 *
 * Contract: the host sets CLPT_TUNE_CPU (an LLVM x86 CPU name, e.g. znver3) only for PoCL x86
 * CPU devices with AVX-512 and `--cpu-vector-bits 512` (kernel_options.cpp); the attribute means
 * nothing to other compilers, which never see it. */
#ifndef CLPT_CPU_TUNING_H
#define CLPT_CPU_TUNING_H

#ifdef CLPT_TUNE_CPU
#define CLPT_TUNE_QUOTE_(name) #name
#define CLPT_TUNE_QUOTE(name) CLPT_TUNE_QUOTE_(name)
#define CLPT_KERNEL __attribute__((target("tune=" CLPT_TUNE_QUOTE(CLPT_TUNE_CPU)))) __kernel
#else
#define CLPT_KERNEL __kernel
#endif

#endif
