// The PNG preview's picture of a linear film (`clpt render --exposure EV --tonemap clamp|aces`;
// the EXR stays linear): each channel x is exposed, x 2^EV, then shaped by the tone curve and
// encoded for display as value^(1/2.2), quantised to 8 bits by rounding.
//   clamp (the default, the book's renderer's): min(max(x, 0), 1)
//   aces:  the ACES filmic fit of Narkowicz (2015), per channel,
//          x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14), clamped to [0, 1]
//          (no 0.6 pre-scale: --exposure -0.737 gives the fit's exposure of his note)
// NaN and infinite values preview as 0.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace clpt {

enum class ToneCurve { Clamp, Aces };
const char* tone_curve_name(ToneCurve curve);                         // "clamp" | "aces"
std::optional<ToneCurve> parse_tone_curve(const std::string& name);  // nullopt for others

struct PreviewSettings {
  double exposure_ev = 0;  // --exposure: the film x 2^exposure_ev
  ToneCurve curve = ToneCurve::Clamp;
};

// The tone curve alone, on an exposed linear value: in [0, 1].
double tone_curve(double x, ToneCurve curve);

// The display value in [0, 1] of linear film value x (exposure, curve, then the 1/2.2 gamma).
double preview_value(double x, const PreviewSettings& settings);

// The 8-bit preview of interleaved linear values.
std::vector<unsigned char> tone_map_preview(const std::vector<float>& rgb, const PreviewSettings& settings = {});

}  // namespace clpt
