#include "io/tone_map.h"

#include <algorithm>
#include <cmath>

namespace clpt {

const char* tone_curve_name(ToneCurve curve) { return curve == ToneCurve::Aces ? "aces" : "clamp"; }

std::optional<ToneCurve> parse_tone_curve(const std::string& name) {
  if (name == "clamp") return ToneCurve::Clamp;
  if (name == "aces") return ToneCurve::Aces;
  return std::nullopt;
}

double tone_curve(double x, ToneCurve curve) {
  if (!std::isfinite(x) || x <= 0) return 0;
  if (curve == ToneCurve::Aces) x = x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14);
  return std::clamp(x, 0.0, 1.0);
}

double preview_value(double x, const PreviewSettings& settings) {
  const double exposed = x * std::exp2(settings.exposure_ev);
  return std::pow(tone_curve(exposed, settings.curve), 1.0 / 2.2);
}

std::vector<unsigned char> tone_map_preview(const std::vector<float>& rgb, const PreviewSettings& settings) {
  std::vector<unsigned char> out(rgb.size());
  if (settings.exposure_ev == 0 && settings.curve == ToneCurve::Clamp) {
    // The book's preview exactly as before (float arithmetic), so default PNGs do not change.
    for (size_t i = 0; i < rgb.size(); ++i) {
      const float v = std::isfinite(rgb[i]) ? std::clamp(rgb[i], 0.0f, 1.0f) : 0.0f;
      out[i] = static_cast<unsigned char>(std::lround(std::pow(v, 1.0f / 2.2f) * 255.0f));
    }
    return out;
  }
  for (size_t i = 0; i < rgb.size(); ++i)
    out[i] = static_cast<unsigned char>(std::lround(preview_value(rgb[i], settings) * 255.0));
  return out;
}

}  // namespace clpt
