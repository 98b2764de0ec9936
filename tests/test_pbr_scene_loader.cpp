// The TOML side of the glTF material and lights: `type = "pbr"` keys with glTF's defaults,
// [[light]] tables (radiometric `intensity`, or candela / lux x color / 683), the orthographic
// camera, a scene with lights defaulting to next-event estimation, and the scene writer writing
// all of it back so that it loads as the same scene. Bad values: tests/scenes/bad/pbr_*.toml,
// light_*.toml and camera_ortho_*.toml (SceneLoader's corpus test).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "scene/scene_loader.h"
#include "scene/scene_transform.h"
#include "scene/scene_writer.h"
#include "util/error.h"

namespace clpt {
namespace {

const char* kScene = R"(
[camera]
position = [0, 1, 5]
look_at = [0, 1, 0]
projection = "orthographic"
height = 3.5

[[sphere]]
name = "metal"
center = [0, 1, 0]
radius = 1
material = { type = "pbr", base_color = [0.9, 0.6, 0.3], metallic = 1, roughness = 0.25 }

[[sphere]]
name = "defaults"
center = [2, 1, 0]
radius = 1
material = { type = "pbr" }

[[sphere]]
name = "glassy"
center = [-2, 1, 0]
radius = 1
material = { type = "pbr", metallic = 0, roughness = 0.1, ior = 1.4, transmission = 0.9, emission = [0.1, 0, 0], double_sided = false }

[[light]]
name = "bulb"
type = "point"
position = [0, 4, 0]
candela = 683
color = [1, 0.5, 0.25]
range = 10

[[light]]
type = "spot"
position = [1, 4, 0]
direction = [0, -2, 0]
intensity = [2, 2, 2]
inner_cone_deg = 10
outer_cone_deg = 30

[[light]]
type = "directional"
direction = [0, -1, -1]
lux = 1366
)";

TEST(PbrSceneLoader, ReadsMaterialsLightsAndTheOrthographicCamera) {
  const Scene s = load_scene_string(kScene, "pbr.toml");
  EXPECT_EQ(s.camera.projection, Projection::Orthographic);
  EXPECT_EQ(s.camera.ortho_height, 3.5);
  ASSERT_EQ(s.spheres.size(), 3u);
  const Material& metal = s.spheres[0].material;
  EXPECT_EQ(metal.type, MaterialType::Pbr);
  EXPECT_EQ(metal.reflectance, (Vec3{0.9, 0.6, 0.3}));
  EXPECT_EQ(metal.metallic, 1);
  EXPECT_EQ(metal.roughness, 0.25);
  const Material& d = s.spheres[1].material;  // glTF's defaults
  EXPECT_EQ(d.reflectance, (Vec3{1, 1, 1}));
  EXPECT_EQ(d.metallic, 1);
  EXPECT_EQ(d.roughness, 1);
  EXPECT_EQ(d.ior, 1.5);
  EXPECT_EQ(d.transmission, 0);
  EXPECT_TRUE(d.double_sided);
  const Material& g = s.spheres[2].material;
  EXPECT_EQ(g.ior, 1.4);
  EXPECT_EQ(g.transmission, 0.9);
  EXPECT_EQ(g.emission, (Vec3{0.1, 0, 0}));
  EXPECT_FALSE(g.double_sided);
  ASSERT_EQ(s.lights.size(), 3u);
  EXPECT_EQ(s.lights[0].name, "bulb");
  EXPECT_EQ(s.lights[0].type, LightType::Point);
  EXPECT_DOUBLE_EQ(s.lights[0].intensity[0], 1.0);  // 683 cd x 1 / 683
  EXPECT_DOUBLE_EQ(s.lights[0].intensity[1], 0.5);
  EXPECT_EQ(s.lights[0].range, 10);
  EXPECT_EQ(s.lights[1].name, "light[1]");
  EXPECT_EQ(s.lights[1].type, LightType::Spot);
  EXPECT_DOUBLE_EQ(s.lights[1].inner_cone_rad, 10 * 3.14159265358979323846 / 180);
  EXPECT_DOUBLE_EQ(s.lights[2].intensity[2], 2.0);  // 1366 lux / 683
  // Punctual lights make next-event estimation the scene's default.
  EXPECT_EQ(s.settings.estimator, "nee");
}

TEST(PbrSceneLoader, WriterWritesItBackAsTheSameScene) {
  const Scene a = load_scene_string(kScene, "pbr.toml");
  const Scene b = load_scene_string(scene_to_toml(a, "", "again.toml"), "again.toml");
  ASSERT_EQ(b.spheres.size(), a.spheres.size());
  for (size_t i = 0; i < a.spheres.size(); ++i) {
    const Material &x = a.spheres[i].material, &y = b.spheres[i].material;
    EXPECT_EQ(x.type, y.type);
    EXPECT_EQ(x.reflectance, y.reflectance);
    EXPECT_EQ(x.metallic, y.metallic);
    EXPECT_EQ(x.roughness, y.roughness);
    EXPECT_EQ(x.ior, y.ior);
    EXPECT_EQ(x.transmission, y.transmission);
    EXPECT_EQ(x.emission, y.emission);
    EXPECT_EQ(x.double_sided, y.double_sided);
  }
  ASSERT_EQ(b.lights.size(), a.lights.size());
  for (size_t i = 0; i < a.lights.size(); ++i) {
    EXPECT_EQ(a.lights[i].name, b.lights[i].name);
    EXPECT_EQ(a.lights[i].type, b.lights[i].type);
    EXPECT_EQ(a.lights[i].position, b.lights[i].position);
    EXPECT_EQ(a.lights[i].direction, b.lights[i].direction);
    for (int c = 0; c < 3; ++c) EXPECT_DOUBLE_EQ(a.lights[i].intensity[c], b.lights[i].intensity[c]);
    EXPECT_EQ(a.lights[i].range, b.lights[i].range);
    EXPECT_NEAR(a.lights[i].inner_cone_rad, b.lights[i].inner_cone_rad, 1e-9);
    EXPECT_NEAR(a.lights[i].outer_cone_rad, b.lights[i].outer_cone_rad, 1e-9);
  }
  EXPECT_EQ(b.camera.projection, Projection::Orthographic);
  EXPECT_EQ(b.camera.ortho_height, 3.5);
  EXPECT_EQ(b.settings.estimator, "nee");
}

// A scene with lights that asks for the book estimator keeps it (the plan then refuses it).
TEST(PbrSceneLoader, AnExplicitEstimatorIsKept) {
  const std::string text = std::string("[render]\nestimator = \"book\"\n") + kScene;
  EXPECT_EQ(load_scene_string(text, "pbr.toml").settings.estimator, "book");
}

// Scaling a scene keeps its image: lights move and point lights brighten by the square of the
// factor, ranges, volumes and an orthographic camera's height scale with it.
TEST(PbrSceneLoader, ScaleSceneCarriesLightsAndTheOrthographicCamera) {
  Scene a = load_scene_string(kScene, "pbr.toml");
  a.spheres[2].material.thickness = 0.5;
  const Scene b = scale_scene(translate_scene(a, {1, 2, 3}), 2);
  EXPECT_EQ(b.lights[0].position, (Vec3{2, 12, 6}));
  EXPECT_DOUBLE_EQ(b.lights[0].intensity[0], 4 * a.lights[0].intensity[0]);
  EXPECT_EQ(b.lights[0].range, 20);
  EXPECT_EQ(b.lights[2].intensity, a.lights[2].intensity);  // directional
  EXPECT_EQ(b.camera.ortho_height, 7);
  EXPECT_EQ(b.spheres[2].material.thickness, 1);
  EXPECT_DOUBLE_EQ(scale_emission(a, 3).lights[1].intensity[0], 6);
}

}  // namespace
}  // namespace clpt
