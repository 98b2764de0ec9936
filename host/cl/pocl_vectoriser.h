// How many work-items PoCL's CPU device packs into one iteration of a kernel's vectorised
// work-item loop, set on the LLVM that PoCL compiles with, in this process.
//
// PoCL turns a work-group into loops over its work-items and lets LLVM's loop vectoriser pick
// their width from its cost model. For clpt's kernels that model picks 8 float lanes on AVX-512
// CPUs (whatever the tuning: docs/performance.md, "Width"), and 16 lanes run 1.4-2.3x faster on a
// CPU with full 512-bit units. PoCL passes no build option that reaches the vectoriser, but it
// compiles in-process with a shared LLVM whose command-line options are process-wide:
// LLVM's `-force-vector-width` sets the width of every loop it vectorises from then on.
//
// Contract: PoCL compiles a kernel's work-group function at the kernel's first launch with the
// options its LLVM holds then, and caches the result under the program's build options, not
// LLVM's. So the width is set before every launch on PoCL's CPU device (DeviceContext::enqueue,
// from the kernel's own lanes), and a program built for a forced width carries it in its build
// options (kernel_options.cpp), which keys both PoCL's cache and clpt's. Kernels asking for
// different widths must not be in flight together on PoCL in one process; clpt renders one plan
// at a time.
#pragma once

#include <cstdint>
#include <string>

namespace clpt {

// Whether the width can be set here: PoCL is loaded, its LLVM is a shared library clpt can find
// (through libpocl's own dependencies), and it is LLVM 15 or later, whose options may be given
// more than once. Otherwise why not, in `why_not` when given.
bool pocl_vectoriser_reachable(std::string* why_not = nullptr);

// Sets the lanes of every work-item loop PoCL vectorises from now on in this process (0: LLVM's
// cost model decides, LLVM's own default). A no-op when the value is the one last set (0 before
// the first call). Throws std::logic_error when lanes != 0 and the vectoriser is not reachable:
// the plan must not ask for a width it cannot have (kernel_options.cpp checks first).
void set_pocl_vectoriser_lanes(uint32_t lanes);

// Whether LLVM's SLP vectoriser may pair values in the kernels PoCL compiles from now on in this
// process (true, LLVM's default), or is held off by an unreachable threshold (`-slp-threshold`).
// PoCL runs SLP on each work-item's code before it builds the work-item loops, and a pair it
// forms (<2 x float>) stops the loop vectoriser for the whole region (docs/design.md). The
// triangle loop's kernels (CLPT_TRIANGLE_COUNT, kernel_options.cpp) turn it off: their
// triangle shading and light code, in one region with everything else, invites pairs at a dozen
// places. Same contract as the lanes: set before every launch on PoCL's CPU device, from the
// kernel's own value, which its build options carry. A no-op when unchanged; throws
// std::logic_error when turning it off is asked for and the vectoriser is not reachable.
void set_pocl_slp(bool on);

}  // namespace clpt
