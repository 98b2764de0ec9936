// The PNG preview's tone curves (io/tone_map.h) against their closed forms: clamp (the book's) and
// Narkowicz's ACES fit, after the exposure 2^EV, then the 1/2.2 gamma and 8-bit rounding.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "io/tone_map.h"

namespace clpt {
namespace {

double aces(double x) { return std::clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }

TEST(ToneMap, ClampIsTheBooksCurve) {
  for (double x : {0.0, 0.001, 0.18, 0.5, 0.999, 1.0, 3.0, 1e9}) {
    EXPECT_DOUBLE_EQ(tone_curve(x, ToneCurve::Clamp), std::min(x, 1.0));
    EXPECT_NEAR(preview_value(x, {}), std::pow(std::min(x, 1.0), 1 / 2.2), 1e-15);
  }
  EXPECT_EQ(tone_curve(-1, ToneCurve::Clamp), 0.0);
  EXPECT_EQ(tone_curve(std::nan(""), ToneCurve::Clamp), 0.0);
  // The default preview is byte for byte the book's: lround(pow(clamp(v), 1/2.2) * 255).
  const std::vector<float> v = {0.0f, 0.18f, 0.5f, 1.0f, 2.0f, -1.0f, INFINITY};
  const std::vector<unsigned char> png = tone_map_preview(v);
  const unsigned char expected[] = {0, 117, 186, 255, 255, 0, 0};
  for (size_t i = 0; i < v.size(); ++i) EXPECT_EQ(png[i], expected[i]) << v[i];
}

TEST(ToneMap, AcesIsNarkowiczsFit) {
  for (double x : {0.0, 0.01, 0.18, 0.5, 1.0, 2.0, 10.0, 1e6}) EXPECT_NEAR(tone_curve(x, ToneCurve::Aces), aces(x), 1e-15);
  // Its landmarks: 0 at 0, about 0.8 at 1 (a shoulder, not a clip), 1 in the limit 2.51 / 2.43.
  EXPECT_NEAR(tone_curve(1.0, ToneCurve::Aces), 2.54 / 3.16, 1e-12);
  EXPECT_DOUBLE_EQ(tone_curve(1e9, ToneCurve::Aces), 1.0);
  // Monotone.
  double last = 0;
  for (double x = 0; x < 20; x += 0.01) {
    const double y = tone_curve(x, ToneCurve::Aces);
    EXPECT_GE(y, last);
    last = y;
  }
}

TEST(ToneMap, ExposureMultipliesBy2ToTheEv) {
  PreviewSettings s;
  s.exposure_ev = 2;
  EXPECT_NEAR(preview_value(0.1, s), std::pow(0.4, 1 / 2.2), 1e-15);
  s.exposure_ev = -1;
  s.curve = ToneCurve::Aces;
  EXPECT_NEAR(preview_value(3.0, s), std::pow(aces(1.5), 1 / 2.2), 1e-15);
  const std::vector<unsigned char> png = tone_map_preview({3.0f}, s);
  EXPECT_EQ(png[0], static_cast<unsigned char>(std::lround(std::pow(aces(1.5), 1 / 2.2) * 255)));
  EXPECT_EQ(parse_tone_curve("aces"), ToneCurve::Aces);
  EXPECT_EQ(parse_tone_curve("clamp"), ToneCurve::Clamp);
  EXPECT_FALSE(parse_tone_curve("reinhard"));
}

}  // namespace
}  // namespace clpt
