// The precision presets (`--precision`): the arithmetic the kernels trace in. A word of the scene
// layer because the scene's conversion for the kernels (device_scene.h: the ray offset) and the
// safe-range model (precision_range.h) depend on it as much as the kernels' specialisation
// (kernels/kernel_options.h, which compiles it in) does.
#pragma once

#include <optional>
#include <string>

namespace clpt {

// Arithmetic of the kernels; README "Precision presets".
//   fast:   float, -cl-unsafe-math-optimizations, native maths, the centre-based intersection
//   robust: float, IEEE maths, the accurate intersection of intersect.cl (default)
//   double: fp64 arithmetic throughout the path (needs cl_khr_fp64)
enum class Precision { Fast, Robust, Double };
const char* precision_name(Precision precision);
// "fast" | "robust" | "double"; nullopt otherwise.
std::optional<Precision> parse_precision(const std::string& name);

}  // namespace clpt
