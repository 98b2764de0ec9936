// Precision presets against the double preset, and the kernel variants of the nee estimator.
//
// Bounds the README states ("Precision presets"): with the same seed on the same device, the
// robust and fast presets give the double preset's image up to float rounding on the book's
// scenes: image means within 1e-4 relative, >= 99% of pixel values within 1e-4 relative. On
// PoCL fast maths computes accurately, so the fast test here checks its intersection formula and
// native functions only; a GPU's fast maths is measured by scripts, not asserted here.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "device_test_util.h"
#include "render_test_util.h"
#include "util/error.h"

namespace clpt::test {
namespace {

struct Variant {
  Precision precision = Precision::Robust;
  std::string estimator = "book";
  ExecutionForm form = ExecutionForm::Megakernel;
  bool generic = false;
};

std::vector<float> render_variant(const std::string& scene_name, const Variant& v) {
  return render_book_variant(scene_name, 91, [&](RenderRequest& request) {
    request.scene.settings.estimator = v.estimator;
    request.precision = v.precision;
    request.form = v.form;
    request.generic_kernel = v.generic;
  });
}

class Presets : public ::testing::TestWithParam<std::string> {};

TEST_P(Presets, RobustEqualsDoubleUpToRounding) {
  if (!test_device().device().fp64) GTEST_SKIP() << "the test device has no fp64";
  expect_same_image(render_variant(GetParam(), {Precision::Double}), render_variant(GetParam(), {Precision::Robust}));
}

TEST_P(Presets, FastEqualsDoubleUpToRounding) {
  if (!test_device().device().fp64) GTEST_SKIP() << "the test device has no fp64";
  expect_same_image(render_variant(GetParam(), {Precision::Double}), render_variant(GetParam(), {Precision::Fast}));
}

// The double preset's wavefront state buffers are 8 bytes a field: both forms still agree.
TEST_P(Presets, DoubleMegakernelEqualsDoubleWavefront) {
  if (!test_device().device().fp64) GTEST_SKIP() << "the test device has no fp64";
  expect_same_image(render_variant(GetParam(), {Precision::Double, "book", ExecutionForm::Megakernel}),
                    render_variant(GetParam(), {Precision::Double, "book", ExecutionForm::Wavefront}));
}

TEST_P(Presets, NeeMegakernelEqualsWavefront) {
  expect_same_image(render_variant(GetParam(), {Precision::Robust, "nee", ExecutionForm::Megakernel}),
                    render_variant(GetParam(), {Precision::Robust, "nee", ExecutionForm::Wavefront}));
}

TEST_P(Presets, NeeSpecialisedEqualsGeneric) {
  expect_same_image(render_variant(GetParam(), {Precision::Robust, "nee", ExecutionForm::Megakernel, false}),
                    render_variant(GetParam(), {Precision::Robust, "nee", ExecutionForm::Megakernel, true}));
}

INSTANTIATE_TEST_SUITE_P(BookScenes, Presets, ::testing::Values("diffuse", "specular", "glass"));

// A device without cl_khr_fp64 (PoCL has it; CLPT_HIDE_FP64 hides it) refuses the double preset
// with an error that names the device and the option.
TEST(PresetErrors, DoubleWithoutFp64NamesTheDevice) {
  ::setenv("CLPT_HIDE_FP64", "1", 1);
  try {
    render_variant("diffuse", {Precision::Double});
    ::unsetenv("CLPT_HIDE_FP64");
    FAIL() << "the double preset ran on a device without fp64";
  } catch (const Error& e) {
    ::unsetenv("CLPT_HIDE_FP64");
    EXPECT_EQ(e.code(), ExitCode::DeviceError);
    const std::string message = e.what();
    EXPECT_NE(message.find("--precision double: device '"), std::string::npos) << message;
    EXPECT_NE(message.find("does not report cl_khr_fp64"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace clpt::test
