// The one place that decides how a kernel is specialised for a scene: which features are
// compiled in and the exact build options. `clpt render --explain` prints its answer.
#pragma once

#include <cstdint>
#include <string>

#include "scene/scene.h"

namespace clpt {

struct KernelFeatures {
  bool phong = true;     // CLPT_HAS_PHONG
  bool glass = true;     // CLPT_HAS_GLASS
  int sphere_count = 0;  // CLPT_SPHERE_COUNT when > 0 (loop unrolled); 0: read at run time
  // When non-zero, -DCLPT_BUILD_NONCE=n: a source no driver has cached (cold-build timing).
  uint64_t build_nonce = 0;
};

// Only what the scene uses. (Lambertian and emitters are always present.)
KernelFeatures features_for_scene(const Scene& scene);

// Every feature compiled in: the generic kernel.
KernelFeatures generic_features();

// OpenCL build options for these features.
std::string kernel_build_options(const KernelFeatures& features);

// Human-readable: one line per decision, then the options.
std::string explain_kernel_options(const KernelFeatures& features);

}  // namespace clpt
