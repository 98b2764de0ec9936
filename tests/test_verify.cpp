// `clpt verify`'s device-free parts (tools/verify.h): how a row's figures come out of a
// comparison (worst |z|, the named test and channel, the same-seed fraction), its table line and
// its JSON. Synthetic noise-free images: the statistics are then exact.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "tools/image_compare.h"
#include "tools/verify.h"

namespace clpt::test {
namespace {

constexpr int kSize = 128;  // larger than the biggest block, so the image mean is its own test

// A flat image of 0.5 in every channel, each pixel mean with variance of the mean 1e-4; `factor`
// scales channel `channel` inside [x0, x0 + w) x [y0, y0 + w).
MeanVarianceImage flat(int channel = 0, double factor = 1, int x0 = 0, int y0 = 0, int w = 0) {
  MeanVarianceImage img;
  img.width = img.height = kSize;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      for (int c = 0; c < 3; ++c) {
        const bool inside = c == channel && x >= x0 && x < x0 + w && y >= y0 && y < y0 + w;
        img.mean.push_back(float(0.5 * (inside ? factor : 1)));
        img.variance.push_back(1e-4f);
      }
  return img;
}

VerifyRow row_from(const MeanVarianceImage& device, const MeanVarianceImage& reference, bool same_seed) {
  VerifyRow row;
  row.scene = "diffuse";
  row.form = "megakernel";
  row.precision = "robust";
  row.device = "device 'X' (P)";
  row.driver = "1.0";
  fill_row_statistics(compare_renders(device, reference, CompareOptions{}), same_seed, row);
  return row;
}

TEST(VerifyRow, EqualImagesPassWithEverythingEqual) {
  const VerifyRow row = row_from(flat(), flat(), true);
  EXPECT_TRUE(row.pass);
  EXPECT_EQ(row.worst_z, 0);
  EXPECT_EQ(row.worst_test, "image mean");  // ties go to the image mean
  EXPECT_EQ(row.accept_fraction, 1);
  ASSERT_TRUE(row.same_seed_fraction.has_value());
  EXPECT_EQ(*row.same_seed_fraction, 1);
  EXPECT_TRUE(row.failure.empty());
}

TEST(VerifyRow, AWholeImageShiftIsNamedByTheImageMeanAndItsChannel) {
  // G 2% bright everywhere: per pixel z = 0.01 / sqrt(2e-4) = 0.71 (accepts), image mean z = 0.71 * 128.
  const VerifyRow row = row_from(flat(1, 1.02, 0, 0, kSize), flat(), true);
  EXPECT_FALSE(row.pass);
  EXPECT_EQ(row.worst_test, "image mean");
  EXPECT_EQ(row.worst_channel, 1);
  EXPECT_NEAR(row.worst_z, 0.01 / std::sqrt(2e-4) * kSize, 0.01 * row.worst_z);
  EXPECT_EQ(row.failure.rfind("image mean channel G: z = +", 0), 0u) << row.failure;
  EXPECT_EQ(row.failure.find("pixels"), std::string::npos) << row.failure;  // the pixel test passed
  EXPECT_EQ(*row.same_seed_fraction, 0);
}

TEST(VerifyRow, ALocalShiftIsNamedByItsBlockScaleAndChannel) {
  // One 16x16 block 20% dark in R: each pixel rejects (z = -7.1), 1.6% of the pixels.
  const VerifyRow row = row_from(flat(0, 0.8, 32, 48, 16), flat(), false);
  EXPECT_FALSE(row.pass);
  EXPECT_FALSE(row.same_seed_fraction.has_value());
  EXPECT_LT(row.worst_z, 0);
  EXPECT_EQ(row.worst_channel, 0);
  EXPECT_EQ(row.failure.rfind("16x16 blocks channel R: z = -", 0), 0u) << row.failure;
  EXPECT_NE(row.failure.find("; pixels: 98.438% accept (need >= 99.75%)"), std::string::npos) << row.failure;
  EXPECT_NE(verify_row_line(row).find(" n/a "), std::string::npos) << verify_row_line(row);
}

TEST(VerifyRow, APixelOnlyFailureStillNamesAChannel) {
  // 32 pairs of pixels in B, one 50% bright and one 40% dark in the same 16x16 block: 64 pixels
  // reject (0.39%, over the 0.25% allowed; |z| >= 0.2 / sqrt(2e-4) = 14) while the blocks and the
  // image mean move little (the image mean most: z = 32 * 0.05 / 16384 / sqrt(2e-4 / 16384) = 0.88).
  MeanVarianceImage device = flat();
  for (size_t j = 0; j < 32; ++j) {
    const size_t row = (j / 8) * 16 + 5, column = (j % 8) * 16 + 3;
    device.mean[(row * kSize + column) * 3 + 2] *= 1.5f;
    device.mean[(row * kSize + column + 6) * 3 + 2] *= 0.6f;
  }
  const VerifyRow row = row_from(device, flat(), true);
  EXPECT_FALSE(row.pass);
  EXPECT_EQ(row.failure.rfind("pixels: 99.609% accept (need >= 99.75%); worst: ", 0), 0u) << row.failure;
  EXPECT_NE(row.failure.find("worst: image mean channel B, z = +0.88"), std::string::npos) << row.failure;
}

TEST(VerifyReport, FooterAndJsonCarryEveryRow) {
  VerifyReport report;
  report.width = kSize;
  report.height = kSize;
  report.rows.push_back(row_from(flat(), flat(), true));
  report.rows.push_back(row_from(flat(2, 1.02, 0, 0, kSize), flat(), true));
  VerifyRow broken;
  broken.scene = "glass";
  broken.form = "wavefront";
  broken.precision = "double";
  broken.error = broken.failure = "clBuildProgram failed with CL_BUILD_PROGRAM_FAILURE on device 'X' (P)";
  report.rows.push_back(broken);
  const std::string footer = verify_footer(report);
  EXPECT_NE(footer.find("FAIL: diffuse, megakernel, robust on device 0 (device 'X' (P)): image mean channel B"),
            std::string::npos) << footer;
  EXPECT_NE(footer.find("FAIL: glass, wavefront, double on device 0 (): clBuildProgram failed"), std::string::npos)
      << footer;
  EXPECT_NE(footer.find("verify: 1 of 3 rows passed\n"), std::string::npos) << footer;
  const nlohmann::json j = nlohmann::json::parse(verify_json(report));
  ASSERT_EQ(j["rows"].size(), 3u);
  EXPECT_EQ(j["passed"], 1);
  EXPECT_EQ(j["rows"][0]["verdict"], "PASS");
  EXPECT_EQ(j["rows"][1]["worst"]["channel"], "B");
  EXPECT_TRUE(j["rows"][0]["error"].is_null());
  EXPECT_EQ(j["rows"][2]["verdict"], "FAIL");
  EXPECT_FALSE(j["rows"][2].contains("worst"));  // no statistics for a row that did not render
  EXPECT_EQ(j["alphas"]["pixel_alpha"], 0.001);
  EXPECT_EQ(j["alphas"]["alpha"], 0.01);
}

}  // namespace
}  // namespace clpt::test
