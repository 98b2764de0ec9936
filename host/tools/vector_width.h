// How many work-items one vector instruction of a compiled kernel carries (its "vector width"),
// measured rather than assumed: PoCL's CPU device compiles each work-group function with LLVM's
// loop vectoriser, whose remarks (POCL_VECTORIZER_REMARKS=1) name the width of every work-item
// loop it vectorised. `clpt bench` (a column and a JSON field per row) and `clpt render --explain`
// report it; docs/performance.md says how it is measured and what it costs.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "cl/cl_device.h"
#include "render/render_plan.h"
#include "render/render_request.h"

namespace clpt {

struct VectorWidthReport {
  // false: the width could not be measured; `why` says why and the figures below are zero.
  bool known = false;
  std::string why;
  // Work-items per vector instruction of the kernel, the figure reported: the width most of the
  // work-group functions' vectorised loops run at (the wider of a tie); 1 when the compiler
  // vectorised none, or when a blocker (below) kept a work-item loop scalar. Not the widest loop:
  // a loop of the kernel's own source inside a work-group function (the lockstep megakernel's
  // reduction over a local array of uints) is vectorised at 8 while the double preset's work-item
  // loops run at 4, or while a blocked shading runs one work-item at a time.
  uint32_t lanes = 0;
  // The widest vectorised loop (1 when none), as measured.
  uint32_t widest = 0;
  std::map<uint32_t, int> loops_by_width;  // vectorised loops (the kernels' barrier regions, ...) per width
  int not_vectorised = 0;                  // loops the vectoriser reported leaving scalar
  // Loops of the work-group functions left scalar for a reason that stops a work-item loop as a
  // whole (a vector-typed value, a call, a switch), per reason: the blockers of docs/design.md.
  std::map<std::string, int> blockers;

  // One line, lanes first: "8 work-items (vectorised loops: 3 at 8, 2 at 4; 7 not)", or with blockers
  // "1 work-item (work-item loops kept scalar: 4 by instruction return type cannot be vectorized;
  // vectorised loops: 3 at 8; 18 not)", or "unknown (WHY)".
  std::string describe() const;
};

// A report that says the width is unknown, and why (a phrase, e.g. "the driver does not report it").
VectorWidthReport unknown_vector_width(const std::string& why);

// Reads LLVM's loop-vectoriser remarks from PoCL's diagnostic text (often many remarks on one
// line): each "vectorized loop (vectorization width: N" is one loop vectorised at width N; each
// loop left scalar is one "loop not vectorized" remark that ends there (its reasons come in
// remarks "loop not vectorized: WHY" of their own, not counted again; the WHYs that stop a
// work-item loop as a whole are kept as blockers) or one "the cost-model indicates that
// vectorization is not beneficial". A loop reported as "already vectorized" is
// counted where it was vectorised. Only the work-group functions' loops count where the text
// marks them: PoCL compiles each kernel first as written (its inliner's remarks name the kernel)
// and then its work-group functions (they name '_pocl_kernel_...'), where the work-item loops
// are; a loop of the kernel's own source (e.g. over a work-group's local array) is vectorised
// across its iterations, not work-items, and is left out. Text without such marks: every remark
// counts. Text with no vectoriser remark: unknown.
VectorWidthReport parse_vectoriser_remarks(const std::string& text);

// Whether this device's driver reports the width: PoCL's CPU device.
bool reports_vector_width(const DeviceInfo& device);

// The arguments after `clpt render` of the probe's render: the request's scene file, on the
// plan's device, with every choice that changes that device's kernel (precision, intersection,
// estimator, Russian roulette, generic, form, megakernel loop, scene loops, work-group size),
// 16x8 pixels, 1 jitter sample per pixel, quiet, compiled from source, the film to `film_path`.
std::vector<std::string> vector_width_probe_arguments(const RenderRequest& request, const DevicePlan& device,
                                                      const std::string& film_path);

// The vector width of the kernel that `device` of `request`'s plan runs: on PoCL's CPU device, a
// child process of this executable (`clpt_executable`, e.g. /proc/self/exe; it must be clpt)
// renders vector_width_probe_arguments with the vectoriser remarks on and fresh, empty PoCL and
// clpt kernel caches (temporary directories, removed afterwards), and its stderr is parsed. The
// probe costs one cold compile of the kernel at 16x8 pixels. Other devices, a child that fails or
// prints no remarks: unknown, with the reason. Never throws for the child's failures.
VectorWidthReport probe_vector_width(const RenderRequest& request, const DevicePlan& device,
                                     const std::string& clpt_executable);

// The path of this process's executable (/proc/self/exe), or "" where it cannot be read.
std::string this_executable();

}  // namespace clpt
