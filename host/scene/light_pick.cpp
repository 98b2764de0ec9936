// The light pick distribution and its alias table (light_pick.h).
#include "scene/light_pick.h"

#include <cmath>

#include "util/error.h"

namespace clpt {

double light_power(const GpuLight& light, const float emission[3]) {
  return double(light.cap_area) * (double(emission[0]) + double(emission[1]) + double(emission[2])) / 3.0;
}

double punctual_light_power(const GpuLight& light, double scene_radius) {
  const double mean = (double(light.intensity[0]) + double(light.intensity[1]) + double(light.intensity[2])) / 3.0;
  switch (light.punctual) {
    case CLPT_LIGHT_POINT:
      return 4 * mean;
    case CLPT_LIGHT_SPOT: {
      // The ramp is 1 at cos = (1 - offset) / scale and 0 at cos = -offset / scale.
      const double cos_inner = light.spot_scale > 0 ? (1 - double(light.spot_offset)) / double(light.spot_scale) : 1;
      const double cos_outer = light.spot_scale > 0 ? -double(light.spot_offset) / double(light.spot_scale) : 1;
      return 2 * (1 - 0.5 * (cos_inner + cos_outer)) * mean;
    }
    default:
      return mean * scene_radius * scene_radius;
  }
}

void fill_light_pick(std::vector<GpuLight>& lights, const std::vector<double>& weights) {
  const size_t n = lights.size();
  if (weights.size() != n) throw Error(ExitCode::Failure, "light pick: one weight per light is needed");
  if (n == 0) return;
  double sum = 0;
  for (double w : weights) {
    if (!(w >= 0) || !std::isfinite(w)) throw Error(ExitCode::Failure, "light pick: a light has a negative or non-finite power");
    sum += w;
  }
  if (!(sum > 0)) throw Error(ExitCode::Failure, "light pick: the lights' powers sum to zero");
  // Vose: scaled[i] = n p_i; entries below 1 are topped up from one entry above 1, which keeps
  // the remainder. Every entry ends with threshold scaled[i] (<= 1) and an alias.
  std::vector<double> scaled(n);
  std::vector<size_t> small, large;
  for (size_t i = 0; i < n; ++i) {
    lights[i].pick_probability = static_cast<float>(weights[i] / sum);
    scaled[i] = weights[i] / sum * double(n);
    lights[i].alias = static_cast<clpt_u32>(i);
    (scaled[i] < 1 ? small : large).push_back(i);
  }
  while (!small.empty() && !large.empty()) {
    const size_t s = small.back(), l = large.back();
    small.pop_back();
    lights[s].alias_threshold = static_cast<float>(scaled[s]);
    lights[s].alias = static_cast<clpt_u32>(l);
    scaled[l] -= 1 - scaled[s];
    if (scaled[l] < 1) {
      large.pop_back();
      small.push_back(l);
    }
  }
  // What is left is 1 up to rounding: always kept.
  for (size_t i : small) lights[i].alias_threshold = 1, lights[i].alias = static_cast<clpt_u32>(i);
  for (size_t i : large) lights[i].alias_threshold = 1, lights[i].alias = static_cast<clpt_u32>(i);
}

std::vector<double> alias_table_probabilities(const std::vector<GpuLight>& lights) {
  const size_t n = lights.size();
  std::vector<double> p(n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    const double keep = std::min(1.0, std::max(0.0, double(lights[i].alias_threshold)));
    p[i] += keep / double(n);
    p[lights[i].alias] += (1 - keep) / double(n);
  }
  return p;
}

}  // namespace clpt
