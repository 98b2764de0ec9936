// The book's pinhole camera: directions of pixel corners and the centre, against the book's
// construction computed here in double (docs/book-scenes.md, "The camera").
#include <gtest/gtest.h>

#include <cmath>

#include "device_test_util.h"
#include "scene/device_scene.h"
#include "scene/scene_loader.h"

namespace clpt::test {
namespace {

using V = std::array<double, 3>;
V sub(V a, V b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V add(V a, V b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
V mul(V a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
V norm(V a) { return mul(a, 1.0 / std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])); }
V cross(V a, V b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }

// The book: sensor 30 high, 30*w/h wide, 45 in front of the pinhole; image row 0 is the top.
V book_direction(int w, int h, double col, double row_from_top) {
  const V pos = {7, 3, 7}, dir = norm(sub({0, 1, 0}, pos));
  const V sx = mul(norm(cross(dir, {0, 1, 0})), 30.0 * w / h);
  const V sy = mul(norm(cross(sx, dir)), 30.0);
  const V center = add(pos, mul(dir, 45.0));
  const double y_up = h - row_from_top;  // position measured from the bottom edge
  return norm(sub(add(add(center, mul(sx, col / w - 0.5)), mul(sy, y_up / h - 0.5)), pos));
}

TEST(Camera, BookCornersAndCentre) {
  const Scene scene = load_scene_file(source_dir() + "/scenes/diffuse.toml");
  const int w = 640, h = 480;
  const DeviceScene ds = make_device_scene(scene, w, h);
  GpuRenderParams params{};
  params.camera = ds.camera;
  params.width = w;
  params.height = h;
  // (col, row, subpixel x, subpixel y): top-left corner, bottom-right corner, centre, a pixel centre.
  const std::vector<cl_float4> requests = {
      {{0, 0, 0, 1}}, {{639, 479, 1, 0}}, {{320, 240, 0, 1}}, {{100, 50, 0.5f, 0.5f}}};
  // The same points in image coordinates (col + sx, row_from_top) with y measured downwards.
  const std::vector<std::array<double, 2>> expected_at = {{0, 0}, {640, 480}, {320, 240}, {100.5, 50.5}};
  Kernel kernel(test_program("probe_stages.cl"), "probe_camera", test_device().where());
  Buffer in = upload(requests);
  Buffer out(test_device(), requests.size() * sizeof(cl_float4), CL_MEM_WRITE_ONLY, "dirs");
  kernel.set_arg(0, params);
  kernel.set_arg(1, in);
  kernel.set_arg(2, out);
  test_device().launch(kernel, requests.size(), 0, "probe_camera");
  const auto dirs = download<cl_float4>(out, requests.size());
  for (size_t i = 0; i < requests.size(); ++i) {
    const V ref = book_direction(w, h, expected_at[i][0], expected_at[i][1]);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(dirs[i].s[k], ref[k], 2e-6) << "request " << i << " axis " << k;
  }
  // The centre looks at the look-at point.
  const V centre = norm(sub({0, 1, 0}, {7, 3, 7}));
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(dirs[2].s[k], centre[k], 2e-6);
}

}  // namespace
}  // namespace clpt::test
