// The environment light as the kernels read it (kernels/types.h GpuEnvironment, kernels/
// environment.cl) and the sampling distribution behind it, built on the host in double: a
// piecewise-constant 2D distribution over f = luminance x sin(theta) per texel (theta at the
// row's centre), as marginal (rows) and conditional (texels of a row) CDFs; the device draws from
// the same probabilities through alias tables made from them (constant time, as the light pick,
// scene/light_pick.h). docs/environment.md.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "kernels/types.h"
#include "scene/scene.h"

namespace clpt {

// The mapping of docs/environment.md in the environment's own frame (+Y up): the image's top
// row is the zenith, v = acos(y) / pi from the top, u = 0.5 + atan2(z, x) / (2 pi).
Vec3 environment_direction(double u, double v);       // unit direction of image position (u, v)
std::array<double, 2> environment_uv(const Vec3& d);  // (u, v) of a unit direction
// World <-> environment frame for rotation_deg about +Y: world = R_y(rotation) local.
Vec3 environment_to_world(const Vec3& local, double rotation_deg);
Vec3 environment_to_local(const Vec3& world, double rotation_deg);

// Rec. 709 luminance, the weight of the sampling distribution.
double environment_luminance(double r, double g, double b);

struct EnvironmentDistribution {
  int width = 0, height = 0;
  std::vector<double> f;                // per texel, row-major from the top: luminance x sin(theta_row)
  std::vector<double> marginal_cdf;     // height + 1 values from 0 to 1: rows by their sums of f
  std::vector<double> conditional_cdf;  // height x (width + 1): each row's texels, 0 to 1
  double mean_f = 0;                    // sum f / (width height); 0: a black image (sampled uniformly)
  // The density of texel `texel` in (u, v): f / mean_f (1 everywhere for a black image).
  double density_uv(size_t texel) const;
  // Probability of drawing texel `texel`: from the CDFs (marginal x conditional).
  double texel_probability(size_t texel) const;
  // Solid-angle density of drawing the environment-frame unit direction d: density_uv of its
  // texel / (2 pi^2 sin(theta)).
  double pdf(const Vec3& d) const;
};

// The distribution of an image of width x height RGB texels (row 0 the zenith).
EnvironmentDistribution environment_distribution(int width, int height, const std::vector<float>& rgb);

// What a kernel's environment buffer holds (types.h, GpuEnvironment, then its data as 32-bit
// words): the scene's environment (strength applied to the texels; a colour packed as a 1x1
// image with its radiance also in the header), or an empty one (kind NONE, one black texel) when
// there is none. `other_lights`: whether next-event estimation has other lights to choose from
// (then the environment's pick probability is 1/2, else 1).
std::vector<float> environment_device_data(const std::optional<Environment>& environment, bool other_lights);

// The header at the start of environment_device_data's words.
GpuEnvironment environment_header(const std::vector<float>& words);

}  // namespace clpt
