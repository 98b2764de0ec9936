// libFuzzer harness for the scene loader: arbitrary bytes go to clpt::load_scene_string as if
// they were a scene file. Rejecting the input with clpt::Error is the normal outcome; anything
// else -- another exception type, a crash, a sanitizer report (memory error, leak, UB) -- is a
// finding. Built with CLPT_FUZZ=ON; run with scripts/fuzz.sh.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "scene/scene_loader.h"
#include "util/error.h"

namespace {

[[noreturn]] void finding(const char* what) {
  std::fprintf(stderr, "fuzz_scene_loader: load_scene_string threw %s\n", what);
  std::abort();  // libFuzzer saves the input as a crash
}

// The documented message prefix "FILE:LINE:COLUMN: " with FILE = fuzz.toml.
bool names_position(const char* message) {
  const char* p = message;
  for (const char* c = "fuzz.toml:"; *c; ++c, ++p)
    if (*p != *c) return false;
  for (int field = 0; field < 2; ++field) {
    if (*p < '1' || *p > '9') return false;
    while (*p >= '0' && *p <= '9') ++p;
    if (*p++ != ':') return false;
  }
  return *p == ' ';
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const clpt::Scene scene = clpt::load_scene_string(text, "fuzz.toml");
    // An accepted scene must be a complete one (the loader's contract).
    if (scene.spheres.empty() && scene.meshes.empty()) finding("nothing but returned a scene without geometry");
  } catch (const clpt::Error& e) {
    // Rejected: every rejection is a bad scene, and its message names the file first.
    if (e.code() != clpt::ExitCode::BadScene) finding("clpt::Error with a code other than BadScene");
    if (!names_position(e.what()))
      finding("clpt::Error whose message does not start with \"fuzz.toml:LINE:COLUMN: \"");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz_scene_loader: %s\n", e.what());
    finding("a std::exception other than clpt::Error");
  } catch (...) {
    finding("a non-standard exception");
  }
  return 0;
}
