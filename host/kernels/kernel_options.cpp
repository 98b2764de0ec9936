#include "kernels/kernel_options.h"

#include <sstream>

namespace clpt {

const char* precision_name(Precision precision) {
  switch (precision) {
    case Precision::Fast: return "fast";
    case Precision::Double: return "double";
    default: return "robust";
  }
}

std::optional<Precision> parse_precision(const std::string& name) {
  if (name == "fast") return Precision::Fast;
  if (name == "robust") return Precision::Robust;
  if (name == "double") return Precision::Double;
  return std::nullopt;
}

const char* estimator_name(Estimator estimator) { return estimator == Estimator::Nee ? "nee" : "book"; }

std::optional<Estimator> parse_estimator(const std::string& name) {
  if (name == "book") return Estimator::Book;
  if (name == "nee") return Estimator::Nee;
  return std::nullopt;
}

KernelFeatures features_for_scene(const Scene& scene, Precision precision) {
  KernelFeatures f;
  f.precision = precision;
  f.estimator = parse_estimator(scene.settings.estimator).value_or(Estimator::Book);
  f.phong = false;
  f.glass = false;
  f.sphere_count = static_cast<int>(scene.spheres.size());
  for (const Sphere& s : scene.spheres) {
    f.phong |= s.material.type == MaterialType::Phong;
    f.glass |= s.material.type == MaterialType::Glass;
  }
  return f;
}

KernelFeatures generic_features(Precision precision) {
  KernelFeatures f;
  f.precision = precision;
  return f;
}

std::string kernel_build_options(const KernelFeatures& features) {
  std::ostringstream o;
  // OpenCL C 1.2: what PoCL compiles and every GPU driver accepts.
  o << "-cl-std=CL1.2";
  o << " -DCLPT_HAS_PHONG=" << (features.phong ? 1 : 0);
  o << " -DCLPT_HAS_GLASS=" << (features.glass ? 1 : 0);
  if (features.sphere_count > 0) o << " -DCLPT_SPHERE_COUNT=" << features.sphere_count;
  if (features.build_nonce) o << " -DCLPT_BUILD_NONCE=" << features.build_nonce;
  return o.str();
}

std::string explain_kernel_options(const KernelFeatures& features) {
  std::ostringstream o;
  o << "kernel specialisation:\n";
  o << "  Lambertian and emitter shading: always compiled\n";
  o << "  Phong shading: " << (features.phong ? "compiled (the scene has a Phong material)"
                                              : "left out (no Phong material in the scene)")
    << "\n";
  o << "  glass shading: " << (features.glass ? "compiled (the scene has a glass material)"
                                              : "left out (no glass material in the scene)")
    << "\n";
  o << "  sphere loop: "
    << (features.sphere_count > 0 ? "unrolled for the scene's " + std::to_string(features.sphere_count) + " spheres"
                                  : std::string("run-time sphere count (generic kernel)"))
    << "\n";
  o << "  build options: " << kernel_build_options(features) << "\n";
  return o.str();
}

}  // namespace clpt
