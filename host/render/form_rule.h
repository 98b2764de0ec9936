// The execution form a render uses when --form names none: a rule on what the plan knows of the
// scene before rendering (which geometry it has and where the kernels test it) and on the device,
// measured A/B with `clpt bench --forms megakernel,wavefront` (docs/performance.md, "Forms",
// the table of the rule). Printed by `clpt render --explain` with its reason.
#pragma once

#include <string>

#include "cl/cl_device.h"
#include "kernels/kernel_options.h"
#include "render/renderer.h"

namespace clpt {

// Where a scene's geometry is tested: the one property the rule reads (from features_for_scene).
enum class SceneGeometry {
  LoopSpheres,       // spheres only, all in the kernels' unrolled loop (the book's scenes)
  SphereHierarchy,   // more than a few spheres: the small ones are hierarchy primitives
  MeshesAndSpheres,  // triangles in the hierarchy beside spheres in the loop (a mesh in the book's room)
  MeshesOnly,        // triangles and no sphere at all, in the hierarchy or all in the loop (the Cornell box)
  // No sphere; the meshes of large triangles in the loop beside a hierarchy of the others
  // (scene/loop_spheres.h, loop_meshes: a detailed model in a room of quads, on a ground plane).
  LoopMeshesAndHierarchy,
};
const char* scene_geometry_name(SceneGeometry g);  // "loop spheres", ...
SceneGeometry scene_geometry(const KernelFeatures& scene_features);

struct FormChoice {
  ExecutionForm form = ExecutionForm::Megakernel;
  std::string reason;  // for --explain: the rule's row
};

// The rule. On CPU devices: the wavefront for MeshesOnly scenes, the megakernel (its lockstep
// loop) for the others, LoopMeshesAndHierarchy too; on other devices (no GPU measured yet) the
// megakernel everywhere.
// `scene_features` is features_for_scene(scene) (what the scene has, not a generic kernel's).
FormChoice default_form_for(const DeviceInfo& device, const KernelFeatures& scene_features);

}  // namespace clpt
