#include "kernels/kernel_options.h"

#include <sstream>

namespace clpt {

KernelFeatures features_for_scene(const Scene& scene) {
  KernelFeatures f;
  f.phong = false;
  f.glass = false;
  f.sphere_count = static_cast<int>(scene.spheres.size());
  for (const Sphere& s : scene.spheres) {
    f.phong |= s.material.type == MaterialType::Phong;
    f.glass |= s.material.type == MaterialType::Glass;
  }
  return f;
}

KernelFeatures generic_features() { return KernelFeatures{}; }

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
