// `clpt verify`: does this OpenCL device render clpt's images correctly? For each chosen device it
// renders small fixed-seed images of the book's three scenes in each execution form and
// precision preset, and tests each against a reference with compare_renders (tools/
// image_compare.h) at CompareOptions' default alphas:
//   device mode   the reference is the first PoCL CPU device, rendering the same scene, form,
//                 precision, size, spp and seed (once per scene x form x precision, shared by
//                 every tested device); the same-seed fraction is reported beside the verdict
//   builtin mode  the reference is gemspt's converged 160x120 render of the scene, shipped in
//                 tests/reference (used when no PoCL device exists, or when asked for; needs a
//                 build with OpenImageIO, which reads its EXRs)
//   films mode    the reference is a directory of films a PoCL device rendered before, on another
//                 machine (`--save-reference-films DIR` in device mode; scripts/offline-bundle.sh),
//                 with the size, spp and seed its films.json records: device mode's comparison,
//                 for a machine without PoCL (scripts/gpu-report.sh)
// The verdict is the statistical one only: a correct device may round differently from PoCL, so
// the same-seed fraction is information, not a criterion.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "kernels/kernel_options.h"
#include "render/renderer.h"
#include "tools/image_compare.h"

namespace clpt {

enum class ReferenceMode { Auto, Device, Builtin, Films };
const char* reference_mode_name(ReferenceMode mode);

// Device mode's default image: 64x48 at 1280 spp, 3.9 M samples a render. Why that many: the
// weakest test of a shift in one channel is the image mean, z = shift / sqrt(var_dev + var_ref)
// with var = sum(pixel variance of the mean) / pixels^2 = sigma^2 / (spp * pixels), sigma the
// standard deviation of one sample. Measured on PoCL at 64x48, 256 spp, the book's estimator:
// sigma / mean = 3.18 (diffuse G), 3.37 (specular G), 2.97 (glass G), at most 3.52 (specular B).
// For a device whose G samples come out 2% bright (CLPT_INJECT_FAULT=perturb:D:G:1.02) beside a
// same-seed reference, var_dev = 1.02^2 var_ref, so
//   z = 0.02 sqrt(spp * pixels) / (sqrt(1 + 1.02^2) * sigma / mean),
// 8.2 for specular G at 3.9 M samples: 5.3 over the image mean's critical z of 2.94 (alpha 0.01,
// Sidak over 3 channels). Same-seed renders are strongly correlated, so the true variance of the
// difference is far below var_dev + var_ref: the Welch z is conservative and the power above is
// a lower bound. Each row reports the z a 2% shift would reach (VerifyRow::shift_z_2pct).
constexpr int kVerifyWidth = 64, kVerifyHeight = 48;
constexpr int64_t kVerifySpp = 1280;
// Builtin mode: the references' size. Against an independent converged reference the per-pixel
// test decides: at 512 spp 1.2% of the specular scene's pixels rejected (skewed pixels whose
// few bright samples make the variance estimate unreliable), at 2048 spp 0.19%, under the 0.25%
// allowed. 2048 spp it is: 39 M samples a render, under a second on a GPU.
constexpr int kBuiltinWidth = 160, kBuiltinHeight = 120;
constexpr int64_t kBuiltinSpp = 2048;

// The book's scenes verify renders, in order.
const std::vector<std::string>& verify_scene_names();

struct VerifyConfig {
  std::vector<std::string> scenes = verify_scene_names();  // names: diffuse, specular, glass
  std::vector<ExecutionForm> forms = {ExecutionForm::Megakernel, ExecutionForm::Wavefront};
  std::vector<Precision> precisions = {Precision::Robust, Precision::Fast, Precision::Double};
  std::string device = "all";  // --device syntax (select_devices)
  ReferenceMode reference = ReferenceMode::Auto;
  std::optional<int> width, height;  // unset: the mode's default
  std::optional<int64_t> spp;        // unset: the mode's default; a multiple of 16 (grid sampler)
  std::optional<uint64_t> seed;      // unset: 1 (films mode: the films' own)
  std::string scene_dir;      // holds NAME.toml; "" = default_scene_dir()
  // Builtin mode: holds gemspt_NAME_160x120.exr ("" = default_reference_dir()). Films mode: the
  // films' directory (required).
  std::string reference_dir;
  // Device mode: also write each reference render into this existing directory as a raw film
  // (reference_film_name) and, at the end, films.json: what films mode reads.
  std::string save_films_dir;
};

// The file of one reference film in a films directory: verify_SCENE_FORM_PRECISION.pfm (its
// variance beside it, .var.pfm).
std::string reference_film_name(const std::string& scene, const std::string& form, const std::string& precision);

// The statistics of one row, from compare_renders(device, reference).
struct VerifyRow {
  int device_index = 0;  // as in `clpt devices`
  size_t position = 0;   // in the --device list (CLPT_INJECT_FAULT's D)
  std::string device;    // label
  std::string driver;    // CL_DRIVER_VERSION
  bool is_reference_device = false;  // device mode: this row compares the reference device with itself
  std::string scene, form, precision;
  bool pass = false;
  std::string error;  // non-empty: a render threw clpt::Error (the row fails, no statistics)
  // Worst |z|: the largest |z| among the worst block of every block scale and the image mean's
  // three channels (the pixel test has its own figure, accept_fraction); signed, positive when
  // the device is brighter. Its test ("16x16 blocks", "image mean"), channel and critical |z|.
  double worst_z = 0;
  std::string worst_test;
  int worst_channel = 0;  // 0 = R, 1 = G, 2 = B
  double worst_z_critical = 0;
  double accept_fraction = 0;               // pixels whose 3-channel test accepts
  std::optional<double> same_seed_fraction;  // device mode only: pixels equal within 1e-4 relative
  double paths_per_s = 0;                   // the device's render, passes only
  // The image-mean z that a device 2% bright in one channel would reach, for the weakest
  // channel: 0.02 m_ref / sqrt(v_ref + 1.02^2 v_dev), v the variances of the two image means.
  double shift_z_2pct = 0;
  std::string failure;  // a failing row: what failed, naming the test and the channel
};

struct VerifyReport {
  ReferenceMode mode = ReferenceMode::Device;  // as run (never Auto)
  std::string reference;  // the reference device's label, or the directory of the gemspt images or films
  std::string reference_driver;  // device and films modes
  int width = 0, height = 0;
  int64_t spp = 0;
  uint64_t seed = 0;
  CompareOptions compare;                 // the options of every comparison
  std::vector<std::string> devices;       // "INDEX LABEL" of every tested device, in --device order
  std::vector<std::string> notes;         // rows skipped (double without fp64), and why
  std::vector<VerifyRow> rows;
  size_t passed() const;
};

// Where the scenes and the gemspt references are looked for when not given: the source tree this
// clpt was built from, else beside the executable (scenes/, reference/).
std::string default_scene_dir();
std::string default_reference_dir();

// Renders and compares every row. Before the first render it resolves the mode, size, spp,
// devices and files, and throws Error(Usage) for a bad option (naming it), a missing scene or
// reference file (naming the path) or a malformed CLPT_INJECT_FAULT, and Error(DeviceError) for
// --reference device without a PoCL CPU device; then on_start sees the report without rows (for
// the header). on_row sees each row when it is finished. A row whose render throws clpt::Error
// fails with the message and the other rows go on.
VerifyReport run_verify(const VerifyConfig& config, const std::function<void(const VerifyReport&)>& on_start,
                        const std::function<void(const VerifyRow&)>& on_row);

// The row's statistics from a comparison of the device's render (A) with the reference (B).
void fill_row_statistics(const CompareResult& result, bool report_same_seed, VerifyRow& row);

// Text: the header (mode, sizes, reference, alphas, column names), one line per row, a line per
// failing row naming scene, form, precision, device and the failed test with its channel, and
// the final "verify: N of M rows passed".
std::string verify_header(const VerifyReport& report);
std::string verify_row_line(const VerifyRow& row);
std::string verify_footer(const VerifyReport& report);

// The same rows as JSON (nlohmann::json); non-finite numbers become null.
std::string verify_json(const VerifyReport& report);

}  // namespace clpt
