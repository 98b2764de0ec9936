// Will this scene render correctly in the chosen precision preset? An a-priori estimate of the
// relative floating-point error of each sphere's and triangle's intersections, from the scene's geometry alone,
// compared with the largest error the extreme-scene tests proved harmless (README "Numerical
// extremes"). `clpt render` prints a warning for every sphere and mesh outside that range. The derivation
// is in precision_range.cpp.
#pragma once

#include <string>
#include <vector>

#include "scene/precision_preset.h"
#include "scene/scene.h"

namespace clpt {

// Unit roundoff of the device arithmetic of a preset: 2^-24 (fast, robust) or 2^-53 (double).
double device_unit_roundoff(Precision precision);

// The largest estimated relative error at which the extreme-scene matrix still passed for this
// preset (tests/extremes_*.cpp); beyond it renders are not proven right.
double proven_relative_error(Precision precision);

// Emission (per channel, non-zero) inside which the film's float sums stay finite and normal.
constexpr double kEmissionSafeMin = 1e-15;
constexpr double kEmissionSafeMax = 1e17;

// A camera closer than this many ray epsilons (device_scene.h) to a sphere's surface may see
// through it: hits closer than the epsilon are ignored.
constexpr double kNearClipMargin = 2;

struct SpherePrecision {
  int sphere = -1;                 // index into Scene::spheres
  double relative_error = 0;       // estimated hit-point error / the sphere's feature size
  double distance_from_camera = 0; // to the surface point the device stores (world units)
  double feature_size = 0;         // min(radius, camera-to-look-at distance), world units
};

// One estimate per sphere, in scene order.
std::vector<SpherePrecision> estimate_sphere_precision(const Scene& scene, Precision precision);

// The worst estimate over the scene's spheres (relative_error 0 when there are none).
SpherePrecision worst_sphere_precision(const Scene& scene, Precision precision);

// The same model for triangles (precision_range.cpp, item 8): each triangle's worst estimate.
struct TrianglePrecision {
  int mesh = -1;                    // index into Scene::meshes
  size_t triangle = 0;              // index into that mesh's triangles
  double relative_error = 0;        // estimated hit-point error / the triangle's feature size
  double distance_from_camera = 0;  // to its farthest vertex (world units)
  double feature_size = 0;          // min(longest edge, camera-to-look-at distance), world units
};

// The worst triangle of each mesh, in scene order (none for a scene without meshes).
std::vector<TrianglePrecision> estimate_mesh_precision(const Scene& scene, Precision precision);

// One line per problem: a sphere or a mesh (its worst triangle) whose estimate exceeds
// proven_relative_error(precision), a
// sphere whose surface is within kNearClipMargin ray epsilons of the camera, or an emitter (sphere
// or mesh) whose
// emission leaves [kEmissionSafeMin, kEmissionSafeMax]. Each names the sphere and
// its file position and suggests --precision double where that preset would be in range.
// Empty when the scene is inside the proven range.
std::vector<std::string> precision_range_warnings(const Scene& scene, Precision precision);

}  // namespace clpt
