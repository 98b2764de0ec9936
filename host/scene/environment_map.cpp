#include "scene/environment_map.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "util/error.h"

namespace clpt {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr size_t kHeaderWords = sizeof(GpuEnvironment) / sizeof(float);
static_assert(sizeof(GpuEnvironment) % sizeof(float) == 0, "the header is whole words");

// Walker's alias table (Vose's construction) for probabilities p (summing to 1): (threshold,
// alias) per entry, so that slot i = floor(u n) is kept when frac(u n) < threshold[i], else
// alias[i] is taken. Appended to `out` as words (the alias as the uint's bits).
void append_alias_table(const std::vector<double>& p, std::vector<float>& out) {
  const size_t n = p.size();
  std::vector<double> scaled(n);
  std::vector<uint32_t> alias(n);
  std::vector<size_t> small, large;
  for (size_t i = 0; i < n; ++i) {
    scaled[i] = p[i] * double(n);
    alias[i] = uint32_t(i);
    (scaled[i] < 1 ? small : large).push_back(i);
  }
  while (!small.empty() && !large.empty()) {
    const size_t s = small.back(), l = large.back();
    small.pop_back();
    alias[s] = uint32_t(l);
    scaled[l] -= 1 - scaled[s];
    if (scaled[l] < 1) {
      large.pop_back();
      small.push_back(l);
    }
  }
  for (size_t i : small) scaled[i] = 1;  // rounding leftovers: kept always
  for (size_t i : large) scaled[i] = 1;
  for (size_t i = 0; i < n; ++i) {
    out.push_back(static_cast<float>(std::min(1.0, scaled[i])));
    float bits;
    std::memcpy(&bits, &alias[i], sizeof bits);
    out.push_back(bits);
  }
}

uint32_t word_index(size_t words) {
  if (words > UINT32_MAX) throw Error(ExitCode::BadScene, "environment: the image's device data exceeds 2^32 words");
  return uint32_t(words);
}

}  // namespace

Vec3 environment_direction(double u, double v) {
  const double phi = 2 * kPi * (u - 0.5), theta = kPi * v;
  return {std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
}

std::array<double, 2> environment_uv(const Vec3& d) {
  const double y = std::clamp(d[1], -1.0, 1.0);
  return {0.5 + std::atan2(d[2], d[0]) / (2 * kPi), std::acos(y) / kPi};
}

Vec3 environment_to_world(const Vec3& l, double rotation_deg) {
  const double a = rotation_deg * kPi / 180, c = std::cos(a), s = std::sin(a);
  return {c * l[0] + s * l[2], l[1], c * l[2] - s * l[0]};
}

Vec3 environment_to_local(const Vec3& d, double rotation_deg) {
  const double a = rotation_deg * kPi / 180, c = std::cos(a), s = std::sin(a);
  return {c * d[0] - s * d[2], d[1], s * d[0] + c * d[2]};
}

double environment_luminance(double r, double g, double b) { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }

double EnvironmentDistribution::density_uv(size_t texel) const { return mean_f > 0 ? f[texel] / mean_f : 1.0; }

double EnvironmentDistribution::texel_probability(size_t texel) const {
  const size_t row = texel / size_t(width), column = texel % size_t(width);
  const double* c = &conditional_cdf[row * (size_t(width) + 1)];
  return (marginal_cdf[row + 1] - marginal_cdf[row]) * (c[column + 1] - c[column]);
}

double EnvironmentDistribution::pdf(const Vec3& d) const {
  const std::array<double, 2> uv = environment_uv(d);
  const int column = std::min(width - 1, std::max(0, int(uv[0] * width)));
  const int row = std::min(height - 1, std::max(0, int(uv[1] * height)));
  const double sin_theta = std::sqrt(std::max(0.0, 1 - d[1] * d[1]));
  return sin_theta > 0 ? density_uv(size_t(row) * width + column) / (2 * kPi * kPi * sin_theta) : 0.0;
}

EnvironmentDistribution environment_distribution(int width, int height, const std::vector<float>& rgb) {
  EnvironmentDistribution d;
  d.width = width;
  d.height = height;
  const size_t w = size_t(width), h = size_t(height);
  d.f.resize(w * h);
  double total = 0;
  for (size_t row = 0; row < h; ++row) {
    const double sin_theta = std::sin(kPi * (double(row) + 0.5) / double(h));
    for (size_t column = 0; column < w; ++column) {
      const size_t t = row * w + column;
      d.f[t] = environment_luminance(rgb[3 * t], rgb[3 * t + 1], rgb[3 * t + 2]) * sin_theta;
      total += d.f[t];
    }
  }
  d.mean_f = total / double(w * h);
  // A black image is sampled uniformly in (u, v): any density is unbiased where nothing shines.
  const auto weight = [&](size_t t) { return total > 0 ? d.f[t] : 1.0; };
  d.marginal_cdf.assign(h + 1, 0.0);
  d.conditional_cdf.assign(h * (w + 1), 0.0);
  std::vector<double> row_sum(h, 0.0);
  for (size_t row = 0; row < h; ++row) {
    double* c = &d.conditional_cdf[row * (w + 1)];
    for (size_t column = 0; column < w; ++column) c[column + 1] = c[column] + weight(row * w + column);
    row_sum[row] = c[w];
    for (size_t column = 1; column <= w; ++column) c[column] = row_sum[row] > 0 ? c[column] / row_sum[row] : double(column) / double(w);
    c[w] = 1;
  }
  for (size_t row = 0; row < h; ++row) d.marginal_cdf[row + 1] = d.marginal_cdf[row] + row_sum[row];
  const double rows_total = d.marginal_cdf[h];
  for (size_t row = 1; row <= h; ++row) d.marginal_cdf[row] /= rows_total;
  d.marginal_cdf[h] = 1;
  return d;
}

std::vector<float> environment_device_data(const std::optional<Environment>& environment, bool other_lights) {
  GpuEnvironment header{};
  header.kind = CLPT_ENVIRONMENT_NONE;
  int width = 1, height = 1;
  std::vector<float> rgb(3, 0.0f);
  if (environment) {
    const Environment& e = *environment;
    const double turns = e.rotation_deg / 360;
    header.rotation_turns = static_cast<float>(turns - std::floor(turns));
    if (!e.is_image()) {
      header.kind = CLPT_ENVIRONMENT_CONSTANT;
      for (int c = 0; c < 3; ++c) {
        header.radiance[c] = static_cast<float>(e.color[c] * e.strength);
        rgb[c] = header.radiance[c];
      }
    } else {
      header.kind = CLPT_ENVIRONMENT_IMAGE;
      width = e.width;
      height = e.height;
      rgb.resize(size_t(width) * size_t(height) * 3);
      for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<float>(double((*e.rgb)[i]) * e.strength);
    }
  }
  const EnvironmentDistribution d = environment_distribution(width, height, rgb);
  const size_t w = size_t(width), h = size_t(height);
  header.width = uint32_t(width);
  header.height = uint32_t(height);
  header.pick_probability = header.kind == CLPT_ENVIRONMENT_NONE || !(d.mean_f > 0) ? 0.0f : other_lights ? 0.5f : 1.0f;
  std::vector<float> words(kHeaderWords, 0.0f);
  words.reserve(kHeaderWords + 7 * w * h + 2 * h);
  header.texel_offset = word_index(words.size());
  words.insert(words.end(), rgb.begin(), rgb.end());
  header.density_offset = word_index(words.size());
  for (size_t t = 0; t < w * h; ++t) words.push_back(static_cast<float>(d.density_uv(t)));
  header.row_alias_offset = word_index(words.size());
  std::vector<double> p(h);
  for (size_t row = 0; row < h; ++row) p[row] = d.marginal_cdf[row + 1] - d.marginal_cdf[row];
  append_alias_table(p, words);
  header.column_alias_offset = word_index(words.size());
  p.resize(w);
  for (size_t row = 0; row < h; ++row) {
    const double* c = &d.conditional_cdf[row * (w + 1)];
    for (size_t column = 0; column < w; ++column) p[column] = c[column + 1] - c[column];
    append_alias_table(p, words);
  }
  std::memcpy(words.data(), &header, sizeof header);
  return words;
}

GpuEnvironment environment_header(const std::vector<float>& words) {
  GpuEnvironment header{};
  if (words.size() >= kHeaderWords) std::memcpy(&header, words.data(), sizeof header);
  return header;
}

}  // namespace clpt
