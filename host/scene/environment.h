// The environment light as the scene layer reads it (docs/environment.md): its image decoded
// through scene/scene_image.h and checked, and the command line's --environment,
// --environment-strength and --environment-rotation applied to any scene, TOML or glTF. What the
// kernels read is made from it by scene/environment_map.h.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "scene/scene.h"
#include "util/error.h"

namespace clpt {

// At most 2^26 texels (an 8192 x 8192 image; 1.5 GiB of device data at 24 bytes a texel): more
// is refused before anything is uploaded, naming the file and the key.
constexpr uint64_t kMaxEnvironmentTexels = uint64_t(1) << 26;

// Reads the image `path` into env (width, height, rgb, hash): 1 channel is grey, 2 grey with
// alpha, 3 or 4 RGB(A); alpha is dropped. 8- and 16-bit integer files (PNG, JPEG, ...) are sRGB
// and decoded to linear; float and half files (EXR, HDR) are linear radiance as stored. Throws Error(`code`, "WHAT:
// PATH: ...") where WHAT is env.what, for a missing file, a directory, an empty (0-byte) or
// unreadable file (the file as env.file names it; the reader's own errors name `path`), an image of more than kMaxEnvironmentTexels texels, or a texel that is NaN
// or infinite. Finite negative texels are read as 0 and said in env.notice.
void load_environment_image(Environment& env, const std::string& path, ExitCode code);

// The light of a scene that has none (docs/environment.md, "The default light"): a soft white
// studio gradient, radiance 1 at the zenith falling linearly in cos(theta) to 0.25 at the nadir
// (0.625 at the horizon), as an image of kDefaultEnvironmentWidth x kDefaultEnvironmentHeight
// texels, so that it is sampled like any environment image. env.what names it.
constexpr int kDefaultEnvironmentWidth = 8, kDefaultEnvironmentHeight = 256;
Environment default_environment();

// Gives a scene without lights, emissive materials or an environment default_environment() and
// returns a one-line notice naming the scene and what lit it; "" (the scene unchanged) when it
// has light of its own.
std::string light_unlit_scene(Scene& scene);

// The command line's environment options (`clpt render`).
struct EnvironmentOverrides {
  std::optional<std::string> file;      // --environment FILE (relative to the working directory), or "none"
  std::optional<double> strength;       // --environment-strength S (>= 0)
  std::optional<double> rotation_deg;   // --environment-rotation DEG
};

// Replaces the scene's environment by --environment's image (strength 1, rotation 0 unless
// given), or removes it for --environment none, and sets strength and rotation; chains the environment into scene.file_hash. Throws
// Error(Usage) naming the option for a bad file or value, and for a strength or rotation given
// to a scene without an environment.
void apply_environment_overrides(Scene& scene, const EnvironmentOverrides& overrides);

// Chains the environment (its texels' hash, colour, strength, rotation) into scene.file_hash, so
// that checkpoints and clpt:scene_hash see a changed environment. No environment: unchanged.
void chain_environment_hash(Scene& scene);

}  // namespace clpt
