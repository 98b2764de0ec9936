// The default execution form per scene and device (form_rule.h). The measurements behind the
// rule are docs/performance.md's "Forms" table; re-measure it (the command is there) when the
// traversal or either form changes, and change kWavefrontOnCpu with it.
#include "render/form_rule.h"

namespace clpt {
namespace {

// Which scene geometries run faster as a wavefront on a CPU (PoCL), by that table: only scenes
// that are all triangles. There every segment's work is the hierarchy traversal, which the
// lockstep megakernel runs scalar in a region of its own and holds the whole group for the
// longest path, while the wavefront compacts the paths that left (the Cornell box's open front).
// Not where the meshes of large triangles are in the loop beside the hierarchy: most segments end
// on them, in the lockstep megakernel's vectorised region.
bool wavefront_on_cpu(SceneGeometry g) { return g == SceneGeometry::MeshesOnly; }

}  // namespace

const char* scene_geometry_name(SceneGeometry g) {
  switch (g) {
    case SceneGeometry::SphereHierarchy: return "spheres in a hierarchy";
    case SceneGeometry::MeshesAndSpheres: return "meshes and loop spheres";
    case SceneGeometry::MeshesOnly: return "meshes only";
    case SceneGeometry::LoopMeshesAndHierarchy: return "meshes of large triangles in the loop beside a hierarchy";
    case SceneGeometry::LoopSpheres: break;
  }
  return "loop spheres";
}

SceneGeometry scene_geometry(const KernelFeatures& f) {
  if (f.triangles && (f.sphere_count > 0 || f.spheres_in_bvh)) return SceneGeometry::MeshesAndSpheres;
  if (f.triangles)
    return f.loop_triangles > 0 && f.hierarchy_triangles ? SceneGeometry::LoopMeshesAndHierarchy : SceneGeometry::MeshesOnly;
  return f.spheres_in_bvh ? SceneGeometry::SphereHierarchy : SceneGeometry::LoopSpheres;
}

FormChoice default_form_for(const DeviceInfo& device, const KernelFeatures& scene_features) {
  const SceneGeometry g = scene_geometry(scene_features);
  FormChoice c;
  const std::string scene = std::string("a scene of ") + scene_geometry_name(g);
  if (!device.is_cpu) {
    c.form = ExecutionForm::Megakernel;
    c.reason = "the default on a non-CPU device for " + scene + "; no GPU measured: docs/performance.md \"Forms\"";
    return c;
  }
  c.form = wavefront_on_cpu(g) ? ExecutionForm::Wavefront : ExecutionForm::Megakernel;
  c.reason = std::string("the default on a CPU for ") + scene + "; docs/performance.md \"Forms\"";
  return c;
}

}  // namespace clpt
