// `clpt compare A B`: are two renders estimates of the same image? Reads the mean and variance
// channels, runs the tests of tools/image_compare.h, prints the report and optionally writes it
// as JSON and a false-colour difference PNG. Exit 0 on PASS, 1 on FAIL, 2 on unusable input.

#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli/commands.h"
#include "io/image_io.h"
#include "io/render_file.h"
#include "util/atomic_file.h"
#include "tools/image_compare.h"
#include "util/error.h"

namespace clpt {
namespace {

struct CompareCommandOptions {
  std::string path_a, path_b;
  std::string json_path;
  std::string diff_png_path;
  CompareOptions test;
};

// A render file (io/render_file.h): a clpt EXR, or a raw NAME.pfm film with NAME.var.pfm.
MeanVarianceImage load_render(const std::string& path, ComparedFile& info) {
  RenderFile file = read_render_file(path);
  info.path = path;
  info.spp = file.info.spp;
  return std::move(file.image);
}

// Output paths are checked before any work, so a typo costs nothing.
void check_output_path(const std::string& option, const std::string& path, const char* extension) {
  if (path.empty()) return;
  if (std::filesystem::path(path).extension() != extension)
    throw Error(ExitCode::Usage, option + " " + path + ": the file must end in " + extension);
  check_output_file(option, path);
}

int run(const CompareCommandOptions& o) {
  check_output_path("--json", o.json_path, ".json");
  check_output_path("--diff-png", o.diff_png_path, ".png");
  ComparedFile info_a, info_b;
  const MeanVarianceImage a = load_render(o.path_a, info_a);
  const MeanVarianceImage b = load_render(o.path_b, info_b);
  if (a.width != b.width || a.height != b.height)
    throw Error(ExitCode::Usage, o.path_a + " is " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                                     " but " + o.path_b + " is " + std::to_string(b.width) + "x" +
                                     std::to_string(b.height) + ": compare needs images of the same size");
  const CompareResult result = compare_renders(a, b, o.test);
  if (!o.json_path.empty()) write_file_atomically(o.json_path, compare_report_json(result, info_a, info_b), "--json");
  if (!o.diff_png_path.empty())
    write_rgb8_image(o.diff_png_path, a.width, a.height, z_to_colour_ramp(pixel_average_z(a, b)));
  std::fputs(format_compare_report(result, info_a, info_b).c_str(), stdout);
  return static_cast<int>(result.pass ? ExitCode::Ok : ExitCode::Failure);
}

}  // namespace

std::function<int()> add_compare_command(CLI::App& app) {
  auto o = std::make_shared<CompareCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "Test whether two renders (EXRs with variance channels) estimate the same image");
  cmd->add_option("a", o->path_a, "First render (EXR from `clpt render`, or a raw .pfm with its .var.pfm)")->required();
  cmd->add_option("b", o->path_b, "Second render, the same size")->required();
  cmd->add_option("--json", o->json_path, "Also write the report's figures to this .json file");
  cmd->add_option("--diff-png", o->diff_png_path,
                  "Write a false-colour z map: blue (A darker) - white - red (A brighter), saturating at |z| = 4");
  cmd->add_flag("--same-seed", o->test.same_seed,
                "Renders of the same seed: pass when nearly all pixels are equal (see --tolerance, --min-equal)");
  cmd->add_option("--tolerance", o->test.tolerance, "Same-seed relative tolerance per channel")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--min-equal", o->test.min_equal, "Same-seed: fraction of equal pixels needed")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--min-accept", o->test.min_accept, "Fraction of accepting pixels needed")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--pixel-alpha", o->test.pixel_alpha,
                  "False-rejection rate of one pixel's test (over its 3 channels)")
      ->capture_default_str()
      ->check(CLI::Range(1e-12, 0.5));
  cmd->add_option("--alpha", o->test.alpha, "Family-wise level of each block scale and of the image mean")
      ->capture_default_str()
      ->check(CLI::Range(1e-12, 0.5));
  return [o] { return run(*o); };
}

}  // namespace clpt
