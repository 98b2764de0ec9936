// libFuzzer harness for the glTF reader (host/scene/gltf_*.cpp, tinygltf, the GLB container):
// the first byte of the input picks the file's name (even: fuzz.glb, odd: fuzz.gltf; a .gltf
// holding the GLB magic is read as GLB all the same), the rest are the file's bytes, handed to
// clpt::load_gltf_scene. Rejecting the input with clpt::Error(BadScene) whose message starts with
// the file's name is the normal outcome; anything else -- another exception, a crash, a
// sanitizer report, a scene breaking the loader's contract -- is a finding. External buffers
// resolve against the working directory (scripts/fuzz.sh runs in tests/scenes/bad).
// Built with CLPT_FUZZ=ON; run with scripts/fuzz.sh.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "scene/gltf_loader.h"
#include "util/error.h"

namespace {

[[noreturn]] void finding(const char* what) {
  std::fprintf(stderr, "fuzz_gltf: load_gltf_scene %s\n", what);
  std::abort();  // libFuzzer saves the input as a crash
}

bool finite(const clpt::Vec3& v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

// What the loader promises of a scene it returns (gltf_loader.h, scene.h TriangleMesh).
void check_contract(const clpt::Scene& scene) {
  if (scene.meshes.empty()) finding("returned a scene without meshes");
  for (const clpt::TriangleMesh& m : scene.meshes) {
    if (m.triangles.empty()) finding("returned a mesh without triangles");
    if (!m.normals.empty() && m.normals.size() != m.positions.size()) finding("returned normals not one per vertex");
    if (!m.uvs.empty() && m.uvs.size() != m.positions.size()) finding("returned uvs not one per vertex");
    for (const clpt::Vec3& p : m.positions)
      if (!finite(p)) finding("returned a vertex that is not finite");
    for (const clpt::Vec3& n : m.normals)
      if (!finite(n) || std::fabs(n[0] * n[0] + n[1] * n[1] + n[2] * n[2] - 1) > 1e-6) finding("returned a normal that is not unit");
    for (const auto& t : m.triangles)
      for (uint32_t i : t)
        if (i >= m.positions.size()) finding("returned a triangle index out of range");
  }
  for (const clpt::PunctualLight& l : scene.lights)
    if (!finite(l.position) || !finite(l.direction) || !finite(l.intensity)) finding("returned a light that is not finite");
  if (!finite(scene.camera.position) || !finite(scene.camera.look_at) || !finite(scene.camera.up))
    finding("returned a camera that is not finite");
  if (scene.settings.width < 1 || scene.settings.height < 1) finding("returned an empty image size");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string name = data[0] % 2 == 0 ? "fuzz.glb" : "fuzz.gltf";
  const std::string bytes(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    check_contract(clpt::load_gltf_scene(bytes, name));
  } catch (const clpt::Error& e) {
    if (e.code() != clpt::ExitCode::BadScene) finding("threw clpt::Error with a code other than BadScene");
    if (std::string(e.what()).rfind(name + ": ", 0) != 0) finding("threw clpt::Error whose message does not start with the file");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz_gltf: %s\n", e.what());
    finding("threw a std::exception other than clpt::Error");
  } catch (...) {
    finding("threw a non-standard exception");
  }
  return 0;
}
