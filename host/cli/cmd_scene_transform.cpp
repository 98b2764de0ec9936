// `clpt scene-transform IN.toml --scale S --translate X,Y,Z [--emission-scale E] -o OUT.toml`:
// writes a scaled and/or translated copy of a scene (host/scene/scene_transform.h), e.g. the
// extreme scenes of README "Numerical extremes". Scaling is applied first, then translation.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <vector>

#include "cli/commands.h"
#include "scene/scene_loader.h"
#include "scene/scene_transform.h"
#include "scene/scene_writer.h"
#include "util/atomic_file.h"
#include "util/error.h"

namespace clpt {
namespace {

struct TransformOptions {
  std::string input;
  std::string output;
  double scale = 1;
  std::vector<double> translate;  // empty or 3 numbers
  double emission_scale = 1;
  bool quiet = false;
};

std::string describe(const TransformOptions& o) {
  std::ostringstream s;
  s.precision(17);
  s << "made by `clpt scene-transform` from " << o.input << ": scale " << o.scale;
  if (!o.translate.empty())
    s << ", then translate by (" << o.translate[0] << ", " << o.translate[1] << ", " << o.translate[2] << ")";
  if (o.emission_scale != 1) s << ", emission x " << o.emission_scale;
  return s.str();
}

int run(const TransformOptions& o) {
  check_output_file("-o", o.output);
  for (double t : o.translate)
    if (!std::isfinite(t)) throw Error(ExitCode::Usage, "--translate: every component must be finite");
  Scene scene = load_scene_file(o.input);
  scene = scale_scene(scene, o.scale);
  if (!o.translate.empty()) scene = translate_scene(scene, {o.translate[0], o.translate[1], o.translate[2]});
  if (o.emission_scale != 1) scene = scale_emission(scene, o.emission_scale);
  write_scene_file(o.output, scene, describe(o));
  if (!o.quiet) std::printf("wrote %s\n", o.output.c_str());
  return 0;
}

}  // namespace

std::function<int()> add_scene_transform_command(CLI::App& app) {
  auto o = std::make_shared<TransformOptions>();
  CLI::App* cmd = app.add_subcommand("scene-transform", "Write a scaled and/or translated copy of a scene file");
  cmd->add_option("scene", o->input, "Scene file (TOML) to transform")->required();
  cmd->add_option("-o,--output", o->output, "Output scene file (TOML)")->required();
  cmd->add_option("--scale", o->scale, "Multiply every centre, radius, mesh vertex and camera point by S (first)")
      ->check(CLI::Range(1e-30, 1e30));
  cmd->add_option("--translate", o->translate, "Add X,Y,Z to every centre, mesh vertex and camera point (after scaling)")
      ->delimiter(',')
      ->expected(3);
  cmd->add_option("--emission-scale", o->emission_scale, "Multiply every emitter's emission by E")
      ->check(CLI::Range(1e-30, 1e30));
  cmd->add_flag("-q,--quiet", o->quiet, "Print nothing but errors");
  return [o] { return run(*o); };
}

}  // namespace clpt
