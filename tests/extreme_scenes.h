// The extreme scenes of README "Numerical extremes" (clpt issue 6), shared by the CI tests
// (test_extremes.cpp) and the full preset x extreme matrix (extremes_matrix.cpp). Each extreme is
// a scene plus the way its image is judged:
//   SameImage:   a transform of the book's diffuse scene whose image is exactly the unit scene's
//                (scaled by `image_factor` for emission changes): region means against a render of
//                the unit scene (or `reference`) with the same seed, within z sigma of both
//                films' noise.
//   Uniform:     every sample of every pixel equals `expected` exactly (zero variance).
//   SmallSphere: a ball of albedo a in an emitting enclosure: its inner disc must be a Le, the
//                surroundings Le, and the image mean must match the analytic disc area.
//   (Uniform also judges a glass ball of reflectance 1 in an emitting enclosure: radiance scales
//   by 1/n^2 entering and n^2 leaving, so every sample is Le unless a hit point lands on the
//   wrong side of the surface.)
//   Horizon:     a camera grazing a huge floor of albedo a in an emitting enclosure: rows wholly
//                below the horizon a Le, rows wholly above Le.
#pragma once

#include <string>
#include <vector>

#include "render_test_util.h"  // Region
#include "scene/scene.h"

namespace clpt::test {

enum class ExtremeCheck { SameImage, Uniform, SmallSphere, Horizon };

struct Extreme {
  std::string name;  // row label of the matrix, e.g. "scale 1e-4"
  Scene scene;
  ExtremeCheck check = ExtremeCheck::SameImage;
  double image_factor = 1;  // SameImage: expected image / reference image
  // SameImage: the scene whose image is expected (empty name: the unit book scene), and regions
  // of tests/reference/book_regions.txt not compared (e.g. where a light was moved).
  std::string reference_name;
  Scene reference;
  std::vector<std::string> skip_regions;
  // SameImage: the rectangles compared; empty: tests/reference/book_regions.txt (the book scene's).
  std::vector<Region> regions;
  double expected = 0;      // Uniform: the exact pixel value; SmallSphere/Horizon: Le
  double albedo = 0;        // SmallSphere/Horizon: the Lambertian albedo a
  double disc_radius_px = 0;  // SmallSphere: analytic radius of the ball's image, pixels
  double tolerance = 1e-6;   // Uniform/SmallSphere/Horizon: accepted relative error of exact pixels
  int width = 160, height = 120;
  int64_t spp = 64;
  bool megakernel = false;  // long accumulation: fewer launches per pass
  bool needs_nee = false;   // only meaningful with next-event estimation (not yet in the kernels)
  std::string known_issue;  // non-empty: expected to fail for this documented reason
  // Non-empty: a build option the render's kernel must have had (the code path the row is there
  // for, e.g. "-DCLPT_BVH_ROOT=1"); a render built without it fails the row.
  std::string build_option;
};

// The book's diffuse scene as loaded from scenes/diffuse.toml.
Scene unit_book_scene();

Extreme scaled_book(double factor);
Extreme translated_book(double offset);  // offset added to x, y and z
Extreme scaled_translated_book(double factor, double offset);
Extreme book_with_emission(double emission);  // the light's emission set to this value
Extreme tiny_light();
Extreme small_sphere_far(double distance_over_radius);
Extreme glass_ball_far(double distance_over_radius);
Extreme grazing_camera(double height_over_view);
Extreme albedo_one_furnace(double factor, double offset);
Extreme long_accumulation(double emission, int64_t spp);

// A mesh scene (scenes/NAME.toml: "cornell-box", "torus-knot"; "cornell-box-ball": the Cornell box
// with a ball of 768 small triangles, mesh_test_util.h, whose walls the lockstep megakernel tests in
// its triangle loop beside the hierarchy of the rest) scaled by `factor` about the world
// origin, then translated by `offset` in x, y and z, against the unit scene: SameImage over a 4 x 4
// grid of blocks (a mesh scene has no named regions), with next-event estimation as its file says,
// 80x60 at 64 spp. The torus knot's mesh is generated (scripts/make_mesh_scene.py);
// mesh_scene_available says whether it is there.
Extreme transformed_mesh_scene(const std::string& name, double factor, double offset);
bool mesh_scene_available(const std::string& name);

// Every row of the matrix, in table order (the torus knot's rows only where its mesh exists).
std::vector<Extreme> all_extremes();

}  // namespace clpt::test
