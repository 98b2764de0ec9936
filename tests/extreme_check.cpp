#include "extreme_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

#include "device_test_util.h"
#include "render/render_session.h"
#include "render_test_util.h"

namespace clpt::test {
namespace {

constexpr double kPi = 3.14159265358979323846;


struct Rendered {
  std::vector<float> mean, variance;
  uint64_t dropped = 0;
  double seconds = 0;
  std::string build_options;
};

Rendered render(const Extreme& e, const ExtremeRun& run) {
  RenderRequest request = test_request(e.scene, e.width, e.height, e.spp, run.seed, Sampler::Jitter);
  request.precision = run.precision;
  if (e.megakernel) {
    request.form = ExecutionForm::Megakernel;
    request.launch_target_s = 0;  // one launch per pass
  }
  RenderReport report;
  const Film film = run_render(request, report);
  return {film.mean_rgb(), film.variance_rgb(), report.dropped, report.render_seconds, report.build_options};
}

// The reference's render (the unit book scene unless the extreme names another), once per
// (reference, preset, seed, size, spp) in this process.
const Rendered& reference_render(const Extreme& e, const ExtremeRun& run) {
  static std::map<std::tuple<std::string, int, uint64_t, int, int, int64_t>, Rendered> cache;
  const auto key = std::make_tuple(e.reference_name, int(run.precision), run.seed, e.width, e.height, e.spp);
  auto it = cache.find(key);
  if (it == cache.end()) {
    Extreme ref = e;
    ref.scene = e.reference_name.empty() ? unit_book_scene() : e.reference;
    it = cache.emplace(key, render(ref, run)).first;
  }
  return it->second;
}

std::string describe(const char* what, double value, double expected) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%s: %.9g, expected %.9g (%.2g relative)", what, value, expected,
                std::abs(value - expected) / expected);
  return buf;
}

ExtremeResult same_image(const Extreme& e, const ExtremeRun& run, const Rendered& r) {
  const Rendered& ref = reference_render(e, run);
  const double z = sidak_z(run.family_comparisons);
  ExtremeResult out;
  out.pass = true;
  const double f = e.image_factor;
  for (const Region& g : e.regions.empty() ? book_regions() : e.regions) {
    if (std::find(e.skip_regions.begin(), e.skip_regions.end(), g.name) != e.skip_regions.end()) continue;
    const RegionStats a = region_stats(r.mean, r.variance, e.width, g.x0, g.y0, g.x1, g.y1);
    const RegionStats b = region_stats(ref.mean, ref.variance, e.width, g.x0, g.y0, g.x1, g.y1);
    for (int c = 0; c < 3; ++c) {
      const double value = a.mean[c] / f;
      const double sigma = std::sqrt(a.variance_of_mean[c] / (f * f) + b.variance_of_mean[c]);
      const double diff = std::abs(value - b.mean[c]);
      const double rel = diff / b.mean[c];
      const double zz = sigma > 0 ? diff / sigma : 0;  // zero variance: judged by kExactTolerance
      if (rel >= out.worst_relative_error) {
        out.worst_relative_error = rel;
        char buf[200];
        std::snprintf(buf, sizeof buf, "region %s %c: %.6g vs reference %.6g (%.2g sigma, limit %.2f)",
                      g.name.c_str(), "RGB"[c], value, b.mean[c], zz, z);
        out.detail = buf;
      }
      out.worst_z = std::max(out.worst_z, zz);
      // Zero-variance regions (the light) differ only by float rounding of the emission scale.
      if (diff > z * sigma + kExactTolerance * b.mean[c]) out.pass = false;
    }
  }
  return out;
}

ExtremeResult uniform(const Extreme& e, const Rendered& r) {
  ExtremeResult out;
  size_t worst = 0;
  for (size_t i = 0; i < r.mean.size(); ++i) {
    const double rel = std::abs(r.mean[i] - e.expected) / e.expected;
    if (rel > out.worst_relative_error) out.worst_relative_error = rel, worst = i;
  }
  out.pass = out.worst_relative_error <= e.tolerance;
  out.detail = describe(("pixel " + std::to_string(worst / 3)).c_str(), r.mean[worst], e.expected);
  return out;
}

// Relative error of every channel of the pixels selected by `inside` against `expected`.
template <typename Select>
void check_exact_pixels(const Extreme& e, const Rendered& r, double expected, const char* what,
                        Select inside, ExtremeResult& out) {
  for (int y = 0; y < e.height; ++y)
    for (int x = 0; x < e.width; ++x) {
      if (!inside(x, y)) continue;
      for (int c = 0; c < 3; ++c) {
        const double value = r.mean[(size_t(y) * e.width + x) * 3 + c];
        const double rel = std::abs(value - expected) / expected;
        if (rel > out.worst_relative_error) {
          out.worst_relative_error = rel;
          out.detail = describe((std::string(what) + " pixel " + std::to_string(x) + "," + std::to_string(y)).c_str(),
                                value, expected);
        }
      }
    }
}

// Inner disc (pixels wholly inside 0.8 of the analytic radius) is a Le, pixels wholly outside
// 1.2 of it are Le, and the image mean matches the analytic disc area within z sigma.
ExtremeResult small_sphere(const Extreme& e, const ExtremeRun& run, const Rendered& r) {
  ExtremeResult out;
  const double cx = e.width / 2.0, cy = e.height / 2.0, rad = e.disc_radius_px;
  auto far_corner = [&](int x, int y) {
    const double dx = std::max(std::abs(x - cx), std::abs(x + 1 - cx));
    const double dy = std::max(std::abs(y - cy), std::abs(y + 1 - cy));
    return std::hypot(dx, dy);
  };
  auto near_corner = [&](int x, int y) {
    const double dx = (x <= cx && cx <= x + 1) ? 0 : std::min(std::abs(x - cx), std::abs(x + 1 - cx));
    const double dy = (y <= cy && cy <= y + 1) ? 0 : std::min(std::abs(y - cy), std::abs(y + 1 - cy));
    return std::hypot(dx, dy);
  };
  check_exact_pixels(e, r, e.albedo * e.expected, "ball",
                     [&](int x, int y) { return far_corner(x, y) < 0.8 * rad; }, out);
  check_exact_pixels(e, r, e.expected, "enclosure",
                     [&](int x, int y) { return near_corner(x, y) > 1.2 * rad; }, out);
  bool pass = out.worst_relative_error <= e.tolerance;

  // Image mean vs the analytic coverage of the disc.
  const double pixels = double(e.width) * e.height;
  const double coverage = kPi * rad * rad / pixels;
  const double expected_mean = e.expected * (1 - coverage * (1 - e.albedo));
  double mean = 0, var = 0;
  for (size_t i = 0; i < r.mean.size(); i += 3) mean += r.mean[i] / pixels, var += r.variance[i] / (pixels * pixels);
  const double diff = std::abs(mean - expected_mean);
  const double sigma = std::sqrt(var);
  out.worst_z = sigma > 0 ? diff / sigma : (diff > 0 ? INFINITY : 0);
  const double rel = diff / expected_mean;
  if (out.worst_z > sidak_z(run.family_comparisons)) {
    pass = false;
    char buf[200];
    std::snprintf(buf, sizeof buf, "image mean %.7g, analytic %.7g (%.2g sigma)", mean, expected_mean, out.worst_z);
    out.detail = buf;
  }
  if (rel > out.worst_relative_error) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "image mean %.7g, analytic %.7g (%.2g sigma)", mean, expected_mean, out.worst_z);
    out.detail = buf;
    out.worst_relative_error = rel;
  }
  out.pass = pass;
  return out;
}

// Rows wholly below the middle of the image see the floor (a Le), rows wholly above the
// enclosure (Le); the horizon row itself is mixed.
ExtremeResult horizon(const Extreme& e, const Rendered& r) {
  ExtremeResult out;
  const int mid = e.height / 2;
  check_exact_pixels(e, r, e.expected, "sky", [&](int, int y) { return y < mid - 1; }, out);
  check_exact_pixels(e, r, e.albedo * e.expected, "floor", [&](int, int y) { return y > mid; }, out);
  out.pass = out.worst_relative_error <= e.tolerance;
  if (out.detail.empty()) out.detail = "every sky and floor pixel exact";
  return out;
}

}  // namespace

int comparisons_of(const Extreme& extreme) {
  switch (extreme.check) {
    case ExtremeCheck::SameImage:
      return int(extreme.regions.empty() ? book_regions().size() : extreme.regions.size()) * 3;
    case ExtremeCheck::SmallSphere:
      return 1;
    default:
      return 0;
  }
}


ExtremeResult check_extreme(const Extreme& extreme, const ExtremeRun& run) {
  const Rendered r = render(extreme, run);
  ExtremeResult out;
  switch (extreme.check) {
    case ExtremeCheck::SameImage:
      out = same_image(extreme, run, r);
      break;
    case ExtremeCheck::Uniform:
      out = uniform(extreme, r);
      break;
    case ExtremeCheck::SmallSphere:
      out = small_sphere(extreme, run, r);
      break;
    case ExtremeCheck::Horizon:
      out = horizon(extreme, r);
      break;
  }
  out.dropped = r.dropped;
  out.render_seconds = r.seconds;
  if (r.dropped > 0) {
    out.pass = false;
    out.detail = std::to_string(r.dropped) + " NaN/Inf samples dropped; " + out.detail;
  }
  if (!extreme.build_option.empty() && r.build_options.find(extreme.build_option) == std::string::npos) {
    out.pass = false;
    out.detail = "the kernel was built without " + extreme.build_option + " (the path this row is for); " + out.detail;
  }
  return out;
}

}  // namespace clpt::test
