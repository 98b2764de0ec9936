// How next-event estimation picks one light of the light list: the pick probabilities (uniform
// when the scene has no emitting triangles, as before they were lights; by power otherwise) and
// the alias table (Walker; Vose's construction) that draws from them in constant time on the
// device (kernels/light.cl). Chosen over a CDF with binary search because the draw is two reads
// and a select, with no data-dependent loop that would stop PoCL's vectoriser or diverge on a GPU.
#pragma once

#include <vector>

#include "kernels/types.h"

namespace clpt {

// Power of a light as the pick weighs it: area (world units^2) times the mean of its emitted
// radiance's channels. (The factor pi of a Lambertian emitter is common to every light.)
double light_power(const GpuLight& light, const float emission[3]);

// The same measure (power / pi) of a punctual light, from its mean intensity I (W/sr) or
// irradiance E (W/m^2): a point light 4 pi I; a spot light 2 pi (1 - cos) I over the cone up to
// halfway between its inner and outer cosines; a directional light E pi R^2, R the radius of a
// sphere around the scene (scene_radius), the disc of the scene it can light at most (pbrt's
// estimate). Each divided by pi.
double punctual_light_power(const GpuLight& light, double scene_radius);

// Fills pick_probability, alias_threshold and alias of every entry so that the device's draw
// (entry i = floor(u n), kept when frac(u n) < alias_threshold[i], else alias[i]) chooses entry k
// with probability weights[k] / sum(weights). Weights must be >= 0 with a positive sum; throws
// (ExitCode::Failure, naming the problem) otherwise. `lights` and `weights` have the same size.
void fill_light_pick(std::vector<GpuLight>& lights, const std::vector<double>& weights);

// The probability with which the draw above picks each entry, recomputed from the table alone
// (for tests: it must equal each entry's pick_probability).
std::vector<double> alias_table_probabilities(const std::vector<GpuLight>& lights);

}  // namespace clpt
