// Similarity transforms of a whole scene, in double: the extreme scenes of the numerics tests
// (README "Numerical extremes") and `clpt scene-transform`. A uniformly scaled or translated
// scene has exactly the image of the original (a pinhole camera sees only directions, and the
// estimator has no length scale), so any difference in a render is the arithmetic's error.
#pragma once

#include "scene/scene.h"

namespace clpt {

// Every sphere centre and radius, mesh vertex, the camera position and look-at point multiplied by `factor`
// (> 0 and finite; throws std::invalid_argument otherwise). `up` and the field of view are
// directions and an angle: unchanged, and so are mesh normals. Each mesh's placement is composed
// with the transform (see TriangleMesh::placement). Punctual lights' positions and ranges, Pbr
// volumes' thickness and attenuation distance and an orthographic camera's height scale too,
// and a point or spot light's intensity by factor^2, so the image stays the same.
Scene scale_scene(const Scene& scene, double factor);

// `offset` added to every sphere centre, mesh vertex, punctual light, the camera position and look-at point (finite; throws
// std::invalid_argument otherwise).
Scene translate_scene(const Scene& scene, const Vec3& offset);

// Every emitter's and Pbr material's emission and every punctual light's intensity multiplied by
// `factor` (> 0 and finite): the image scales by it too.
Scene scale_emission(const Scene& scene, double factor);

}  // namespace clpt
