// `clpt verify`: render the book's scenes on each chosen device and test them against a reference
// (a PoCL CPU device, or gemspt's images shipped in the tree); tools/verify.h holds the logic.
// Exit 0 when every row passes, 1 when any row fails (or none could run), 2 on bad options or a
// missing file, 4 when --reference device finds no PoCL device.
#include <cstdio>
#include <string>
#include <filesystem>
#include <memory>

#include "cli/commands.h"
#include "tools/verify.h"
#include "util/atomic_file.h"
#include "util/error.h"

namespace clpt {
namespace {

struct VerifyCommandOptions {
  VerifyConfig config;
  std::vector<std::string> forms, precisions;
  std::string reference = "auto";
  std::optional<int64_t> spp;
  std::string json_path;
  bool quiet = false;
};

// --json FILE: a .json name where a file can be written, checked before any rendering.
void check_json_path(const std::string& path) {
  if (path.empty()) return;
  if (std::filesystem::path(path).extension() != ".json")
    throw Error(ExitCode::Usage, "--json " + path + ": the file must end in .json");
  check_output_file("--json", path);
}

int run(VerifyCommandOptions& o) {
  check_json_path(o.json_path);
  VerifyConfig& c = o.config;
  if (!o.forms.empty()) {
    c.forms.clear();
    for (const std::string& f : o.forms)
      c.forms.push_back(f == "wavefront" ? ExecutionForm::Wavefront : ExecutionForm::Megakernel);
  }
  if (!o.precisions.empty()) {
    c.precisions.clear();
    for (const std::string& p : o.precisions) c.precisions.push_back(*parse_precision(p));  // CLI11 checked
  }
  c.spp = o.spp;
  c.reference = o.reference == "device"    ? ReferenceMode::Device
                : o.reference == "builtin" ? ReferenceMode::Builtin
                : o.reference == "films"   ? ReferenceMode::Films
                                           : ReferenceMode::Auto;
  const bool quiet = o.quiet;
  VerifyReport report = run_verify(
      c,
      [quiet](const VerifyReport& r) {
        if (!quiet) std::fputs(verify_header(r).c_str(), stdout);
        std::fflush(stdout);
      },
      [quiet](const VerifyRow& row) {
        if (!quiet) std::fputs(verify_row_line(row).c_str(), stdout);
        std::fflush(stdout);
      });
  if (!o.json_path.empty()) write_file_atomically(o.json_path, verify_json(report), "--json");
  std::fputs(verify_footer(report).c_str(), stdout);
  const bool all_passed = !report.rows.empty() && report.passed() == report.rows.size();
  return static_cast<int>(all_passed ? ExitCode::Ok : ExitCode::Failure);
}

// The --help text after the options; the alphas, sizes and spp come from the code that uses them.
std::string help_footer() {
  const CompareOptions o;
  std::string blocks;
  for (size_t i = 0; i < o.block_sizes.size(); ++i)
    blocks += (i ? i + 1 == o.block_sizes.size() ? " and " : ", " : "") + std::to_string(o.block_sizes[i]) + "x" +
              std::to_string(o.block_sizes[i]);
  char text[3072];
  std::snprintf(
      text, sizeof text,
      "Rows: device x scene x form x precision (double only where the device has cl_khr_fp64), the "
      "book's grid sampler and estimator. The reference (--reference device, the default when PoCL is "
      "present) is the first PoCL CPU device, rendering the same scene, form, precision, size (default "
      "%dx%d), spp (%lld) and seed, once per scene x form x precision; when that device is also under "
      "test its rows are kept: they compare it with itself and prove the harness. --reference builtin "
      "(the default without PoCL) compares with gemspt's converged renders (--reference-dir) at "
      "%dx%d, %lld spp; no same-seed fraction there (n/a). --reference films compares with films a PoCL "
      "device rendered earlier, elsewhere (--reference device --save-reference-films DIR writes them; "
      "--reference-dir DIR reads them, at their own size, spp and seed): for machines without PoCL "
      "(scripts/gpu-report.sh).\n"
      "Verdict (PASS/FAIL): compare_renders at its fixed defaults: a pixel accepts at alpha %g over "
      "its 3 channels and >= %.2f%% of pixels must; %s block means and the image mean at family-wise "
      "alpha %g each. Worst |z|: the largest |z| among every block scale's worst block and the image "
      "mean's 3 channels; accept: the pixel test's accept fraction; same-seed: pixels equal within %g "
      "relative (information only: a correct device may round differently).\n"
      "Exit: 0 every row passed; 1 a row failed (its FAIL line names scene, test and channel) or no "
      "row could run; 2 bad option or missing scene or reference file; 4 --reference device without "
      "a PoCL device.",
      kVerifyWidth, kVerifyHeight, (long long)kVerifySpp, kBuiltinWidth, kBuiltinHeight, (long long)kBuiltinSpp,
      o.pixel_alpha, 100 * o.min_accept, blocks.c_str(), o.alpha, o.tolerance);
  return text;
}

}  // namespace

std::function<int()> add_verify_command(CLI::App& app) {
  auto o = std::make_shared<VerifyCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "verify", "Check that a device renders correctly: the book's scenes in every form and precision, "
                "tested against a PoCL reference (or gemspt's images)");
  cmd->footer(help_footer());
  VerifyConfig& c = o->config;
  cmd->add_option("--device", c.device, "Devices to test: all, or as render --device (index, cpu, gpu, "
                                        "cpu:N, gpu:N, name substring, comma list)")
      ->capture_default_str();
  cmd->add_option("--scenes", c.scenes, "Subset of the book's scenes (default: diffuse,specular,glass)")
      ->delimiter(',')
      ->check(CLI::IsMember(verify_scene_names()));
  cmd->add_option("--forms", o->forms, "Execution forms (default: megakernel,wavefront)")
      ->delimiter(',')
      ->check(CLI::IsMember({"megakernel", "wavefront"}));
  cmd->add_option("--precisions", o->precisions, "Precision presets (default: robust,fast,double)")
      ->delimiter(',')
      ->check(CLI::IsMember({"fast", "robust", "double"}));
  cmd->add_option("--reference", o->reference,
                  "auto (a PoCL device when present, else builtin), device (PoCL), builtin (gemspt images) or films (--reference-dir)")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "device", "builtin", "films"}));
  cmd->add_option("--reference-dir", c.reference_dir,
                  "builtin: directory of gemspt_{diffuse,specular,glass}_160x120.exr (default: the tree's "
                  "tests/reference); films: the films' directory");
  cmd->add_option("--save-reference-films", c.save_films_dir,
                  "--reference device: also write each reference render and films.json into this directory");
  cmd->add_option("--width", c.width, "Image width (default 64; --reference builtin: 160 only)")->check(CLI::Range(1, 16384));
  cmd->add_option("--height", c.height, "Image height (default 48; --reference builtin: 120 only)")->check(CLI::Range(1, 16384));
  cmd->add_option("--spp", o->spp, "Samples per pixel, a multiple of 16 (default 1280; --reference builtin: 2048)")
      ->check(CLI::Range(int64_t(16), int64_t(1) << 31));
  cmd->add_option("--seed", c.seed, "Random seed of every render (device and reference; default 1, films: theirs)");
  cmd->add_option("--json", o->json_path, "Also write the rows to this .json file (atomically)");
  cmd->add_flag("-q,--quiet", o->quiet, "Print only the FAIL lines and the final count");
  return [o] { return run(*o); };
}

}  // namespace clpt
