// What `clpt render` reports when it is done: the render (size, samples, form, device), the
// passes' rates over the passes' own time (their launches and the waits for them, as `clpt bench`
// times a pass), and where the whole wall time went, each part measured on its own: scene load,
// image load (textures, environment), device discovery, the conversion and hierarchy, kernel build, first launch, passes, output
// writing, and the rest.
// The EXR records the same split (clpt:*_s keys, io/render_file.h; docs/render-summary.md).
#pragma once

#include "render/render_session.h"
#include "scene/scene.h"
#include "util/clock.h"

namespace clpt {

// The command's own steps, beside the render's (RenderReport); seconds of wall clock.
struct RenderCommandTimes {
  Clock::time_point start = Clock::now();  // the command's start
  double scene_load = 0;   // the scene file and its mesh files read and checked, overrides applied
                           // (without image_load)
  double image_load = 0;   // the images the scene names (textures, environment) read and decoded
  double resume_load = 0;  // --resume: the checkpoint read and checked
  double output = 0;       // checkpoints and outputs written so far
};

// The wall time from `times.start` until now, split into parts that do not overlap; `other` is
// the rest (the devices' contexts, scene uploads, the work between passes, start-up).
struct RenderTimeSplit {
  double wall = 0, scene_load = 0, image_load = 0, resume_load = 0, discovery = 0, convert = 0, kernel_build = 0,
         first_launch = 0, passes = 0, output = 0, other = 0;
};
RenderTimeSplit render_time_split(const RenderReport& report, const RenderCommandTimes& times);

// "compiled" or "clpt cache hit": how the kernel build was served.
const char* kernel_build_source(const RenderReport& report);

// The summary after the passes: the render, the passes' rates, stage times, error estimate, and
// each device's (or MPI rank's) share.
void print_render_summary(const Scene& scene, const RenderReport& report);

// The last line, once the outputs are written: the wall time and its parts.
void print_render_times(const RenderReport& report, const RenderCommandTimes& times);

}  // namespace clpt
