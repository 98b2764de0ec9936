// Scene loading: the book's three scenes load as specified, every file in tests/scenes/bad fails
// with exactly the message on its first line, and a few in-memory cases.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "scene/scene_loader.h"
#include "util/error.h"
#include "util/hash.h"

#ifndef CLPT_SOURCE_DIR
#error "CLPT_SOURCE_DIR must name the source tree (set by tests/CMakeLists.txt)"
#endif

namespace clpt {
namespace {

const std::string kSourceDir = CLPT_SOURCE_DIR;

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The message the scene load threw, or "" with a test failure if it did not throw Error.
std::string load_error(const std::function<void()>& load) {
  try {
    load();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::BadScene);
    return e.what();
  }
  ADD_FAILURE() << "the scene loaded without error";
  return "";
}

std::string string_error(const std::string& text) {
  return load_error([&] { load_scene_string(text, "mem.toml"); });
}

const Sphere& sphere_named(const Scene& scene, const std::string& name) {
  const auto it = std::find_if(scene.spheres.begin(), scene.spheres.end(),
                               [&](const Sphere& s) { return s.name == name; });
  if (it == scene.spheres.end()) throw std::runtime_error("no sphere named " + name);
  return *it;
}

// ---- The book's scenes --------------------------------------------------------------------------

Scene load_book_scene(const std::string& name) {
  return load_scene_file(kSourceDir + "/scenes/" + name + ".toml");
}

void expect_book_room(const Scene& scene) {
  ASSERT_EQ(scene.spheres.size(), 8u);
  const char* names[] = {"floor",     "ceiling", "left_wall", "right_wall",
                         "back_wall", "light",   "left_ball", "right_ball"};
  for (size_t i = 0; i < 8; ++i) EXPECT_EQ(scene.spheres[i].name, names[i]);
  EXPECT_EQ(scene.settings.width, 640);
  EXPECT_EQ(scene.settings.height, 480);
  EXPECT_EQ(scene.settings.spp, 16);
  EXPECT_EQ(scene.settings.seed, 1u);
  EXPECT_EQ(scene.settings.max_bounces, 9);
  EXPECT_EQ(scene.settings.sampler, Sampler::Grid);
  EXPECT_EQ(scene.settings.estimator, "book");
  EXPECT_EQ(scene.camera.position, (Vec3{7, 3, 7}));
  EXPECT_EQ(scene.camera.look_at, (Vec3{0, 1, 0}));
  EXPECT_EQ(scene.camera.up, (Vec3{0, 1, 0}));
  EXPECT_DOUBLE_EQ(scene.camera.vertical_fov_deg, 36.869897645844021);

  const Sphere& light = sphere_named(scene, "light");
  EXPECT_EQ(light.center, (Vec3{0, 103.99, 0}));
  EXPECT_EQ(light.radius, 100.0);
  EXPECT_EQ(light.material.type, MaterialType::Emitter);
  EXPECT_EQ(light.material.emission, (Vec3{8, 8, 8}));
  EXPECT_EQ(sphere_named(scene, "left_wall").center, (Vec3{-100003, 0, 0}));
  EXPECT_EQ(sphere_named(scene, "left_wall").material.reflectance, (Vec3{0.7, 0.1, 0.1}));
  EXPECT_EQ(sphere_named(scene, "back_wall").material.reflectance, (Vec3{0.1, 0.7, 0.1}));
  EXPECT_EQ(sphere_named(scene, "right_wall").center, (Vec3{100009, 0, 0}));
  EXPECT_EQ(sphere_named(scene, "ceiling").center, (Vec3{0, 100004, 0}));
  EXPECT_EQ(sphere_named(scene, "left_ball").center, (Vec3{-2, 1, 0}));
  EXPECT_EQ(sphere_named(scene, "left_ball").radius, 1.0);
}

TEST(BookScenes, Diffuse) {
  const Scene scene = load_book_scene("diffuse");
  expect_book_room(scene);
  for (const Sphere& s : scene.spheres) {
    const MaterialType expected =
        s.name == "light" ? MaterialType::Emitter : MaterialType::Lambertian;
    EXPECT_EQ(s.material.type, expected) << s.name;
  }
  EXPECT_EQ(sphere_named(scene, "floor").material.reflectance, (Vec3{0.7, 0.7, 0.7}));
  EXPECT_EQ(sphere_named(scene, "right_ball").material.reflectance, (Vec3{0.1, 0.1, 0.7}));
}

TEST(BookScenes, SpecularHasAPhongFloor) {
  const Scene scene = load_book_scene("specular");
  expect_book_room(scene);
  const Material& floor = sphere_named(scene, "floor").material;
  EXPECT_EQ(floor.type, MaterialType::Phong);
  EXPECT_EQ(floor.reflectance, (Vec3{0.999, 0.999, 0.999}));
  EXPECT_EQ(floor.phong_exponent, 100.0);
  EXPECT_EQ(sphere_named(scene, "right_ball").material.type, MaterialType::Lambertian);
}

TEST(BookScenes, GlassHasAGlassRightBall) {
  const Scene scene = load_book_scene("glass");
  expect_book_room(scene);
  const Material& ball = sphere_named(scene, "right_ball").material;
  EXPECT_EQ(ball.type, MaterialType::Glass);
  EXPECT_EQ(ball.reflectance, (Vec3{0.999999, 0.999999, 0.999999}));
  EXPECT_EQ(ball.ior, 1.5);
  EXPECT_EQ(sphere_named(scene, "floor").material.type, MaterialType::Lambertian);
}

TEST(BookScenes, ProvenanceIsThePathAndTheHashOfTheBytes) {
  const std::string path = kSourceDir + "/scenes/diffuse.toml";
  const Scene scene = load_scene_file(path);
  EXPECT_EQ(scene.file, path);
  EXPECT_EQ(scene.file_hash, hex64(fnv1a64(read_text(path))));
  EXPECT_EQ(scene.spheres[0].where.str(),
            path + ":" + std::to_string(scene.spheres[0].where.line) + ":1");
  EXPECT_GT(scene.spheres[0].where.line, 1);
}

// ---- The corpus of broken scenes ----------------------------------------------------------------

std::vector<std::string> bad_scene_files() {
  std::vector<std::string> files;
  const std::filesystem::path dir = std::filesystem::path(kSourceDir) / "tests/scenes/bad";
  if (!std::filesystem::is_directory(dir)) return files;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.path().extension() == ".toml") files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

// First line "# expect: MESSAGE", with the token @FILE@ standing for the path.
std::string expected_message(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  const std::string prefix = "# expect: ";
  if (line.compare(0, prefix.size(), prefix) != 0) return "(no '# expect: ' line in " + path + ")";
  std::string message = line.substr(prefix.size());
  for (size_t at; (at = message.find("@FILE@")) != std::string::npos;) message.replace(at, 6, path);
  return message;
}

TEST(BadScenes, CorpusIsThere) { EXPECT_GE(bad_scene_files().size(), 20u); }

class BadScene : public testing::TestWithParam<std::string> {};

TEST_P(BadScene, FailsWithTheExpectedMessage) {
  const std::string& path = GetParam();
  EXPECT_EQ(load_error([&] { load_scene_file(path); }), expected_message(path));
}

std::string test_name(const testing::TestParamInfo<std::string>& info) {
  std::string name = std::filesystem::path(info.param).stem().string();
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Corpus, BadScene, testing::ValuesIn(bad_scene_files()), test_name);

// ---- In-memory scenes ---------------------------------------------------------------------------

const char* const kMinimalScene = R"(
[camera]
position = [0, 1, 5]
look_at = [0, 1, 0]

[[sphere]]
center = [0, 5, 0]
radius = 1
material = { type = "emitter", emission = [1, 2, 3] }

[[sphere]]
center = [0, 1, 0]
radius = 0.5
[sphere.material]
type = "phong"
reflectance = [0.5, 0.5, 0.5]
exponent = 20
)";

// The mirror takes a reflectance and nothing else; the writer writes it back.
TEST(SceneString, MirrorMaterialTakesOnlyAReflectance) {
  const std::string mirror_scene = std::string(kMinimalScene) +
      "\n[[sphere]]\ncenter = [1, 1, 0]\nradius = 0.5\nmaterial = { type = \"mirror\", reflectance = [0.9, 0.8, 0.7] }\n";
  const Scene scene = load_scene_string(mirror_scene, "mem.toml");
  ASSERT_EQ(scene.spheres.size(), 3u);
  EXPECT_EQ(scene.spheres[2].material.type, MaterialType::Mirror);
  EXPECT_EQ(scene.spheres[2].material.reflectance, (Vec3{0.9, 0.8, 0.7}));
  const std::string with_ior = std::string(kMinimalScene) +
      "\n[[sphere]]\ncenter = [1, 1, 0]\nradius = 0.5\nmaterial = { type = \"mirror\", reflectance = [0.9, 0.8, 0.7], ior = 1.5 }\n";
  EXPECT_NE(string_error(with_ior).find("'ior' does not apply to material type 'mirror'"), std::string::npos)
      << string_error(with_ior);
  const std::string too_bright = std::string(kMinimalScene) +
      "\n[[sphere]]\ncenter = [1, 1, 0]\nradius = 0.5\nmaterial = { type = \"mirror\", reflectance = [1.5, 0.8, 0.7] }\n";
  EXPECT_NE(string_error(too_bright).find("reflectance"), std::string::npos) << string_error(too_bright);
}

TEST(SceneString, MinimalSceneTakesTheDefaults) {
  const Scene scene = load_scene_string(kMinimalScene, "mem.toml");
  EXPECT_EQ(scene.file, "mem.toml");
  EXPECT_EQ(scene.file_hash, hex64(fnv1a64(kMinimalScene)));
  const RenderSettings defaults;
  EXPECT_EQ(scene.settings.width, defaults.width);
  EXPECT_EQ(scene.settings.spp, defaults.spp);
  EXPECT_EQ(scene.settings.sampler, defaults.sampler);
  EXPECT_EQ(scene.camera.up, (Vec3{0, 1, 0}));
  EXPECT_DOUBLE_EQ(scene.camera.vertical_fov_deg, 36.869897645844021);
  ASSERT_EQ(scene.spheres.size(), 2u);
  EXPECT_EQ(scene.spheres[0].name, "sphere[0]");
  EXPECT_EQ(scene.spheres[1].name, "sphere[1]");
  EXPECT_EQ(scene.spheres[0].material.emission, (Vec3{1, 2, 3}));
  EXPECT_EQ(scene.spheres[1].material.type, MaterialType::Phong);  // from [sphere.material]
  EXPECT_EQ(scene.spheres[1].material.phong_exponent, 20.0);
  EXPECT_EQ(scene.spheres[1].where.str(), "mem.toml:11:1");
}

TEST(SceneString, SettingsAreRead) {
  const std::string text = std::string(
                               "[image]\nwidth = 32\nheight = 16\n[render]\nspp = 48\n"
                               "seed = 7\nmax_bounces = 0\nsampler = \"grid\"\n") +
                           kMinimalScene;
  const Scene scene = load_scene_string(text, "mem.toml");
  EXPECT_EQ(scene.settings.width, 32);
  EXPECT_EQ(scene.settings.height, 16);
  EXPECT_EQ(scene.settings.spp, 48);
  EXPECT_EQ(scene.settings.seed, 7u);
  EXPECT_EQ(scene.settings.max_bounces, 0);
  EXPECT_EQ(scene.settings.sampler, Sampler::Grid);
}

// Every sampler's name reads back as that sampler, and a near miss is suggested.
TEST(SceneString, EverySamplerNameIsRead) {
  for (const std::string& name : sampler_names()) {
    const Scene scene = load_scene_string("[render]\nsampler = \"" + name + "\"\n" + kMinimalScene, "mem.toml");
    EXPECT_EQ(sampler_name(scene.settings.sampler), name);
  }
  EXPECT_EQ(load_scene_string(std::string("[render]\nsampler = \"sobol\"\n") + kMinimalScene, "mem.toml").settings.sampler,
            Sampler::Sobol);
  EXPECT_EQ(string_error(std::string("[render]\nsampler = \"sobl\"\n") + kMinimalScene),
            "mem.toml:2:11: render.sampler: unknown sampler 'sobl'; did you mean 'sobol'?");
}

TEST(SceneString, SyntaxErrorNamesThePosition) {
  EXPECT_EQ(
      string_error("[camera\n"),
      "mem.toml:1:8: syntax error: Error while parsing table header: expected ']', saw '\\n'");
}

TEST(SceneString, MisspelledMaterialTypeGetsASuggestion) {
  std::string text = kMinimalScene;
  text.replace(text.find("\"phong\""), 7, "\"phnog\"");
  EXPECT_EQ(string_error(text),
            "mem.toml:15:8: sphere[1].material.type: unknown material type 'phnog'; did you mean "
            "'phong'?");
}

TEST(SceneString, EmptySphereArrayHasNoSpheres) {
  EXPECT_EQ(string_error("sphere = []\n[camera]\nposition = [0, 0, 1]\nlook_at = [0, 0, 0]\n"),
            "mem.toml:1:10: sphere: the scene has no spheres or meshes");
}

TEST(SceneString, HugeIntegerIsOutOfRangeNotWrapped) {
  EXPECT_EQ(string_error(std::string("[image]\nwidth = 4294967297\n") + kMinimalScene),
            "mem.toml:2:9: image.width: width must be in [1, 16384] (got 4294967297)");
  EXPECT_EQ(string_error(std::string("[render]\nseed = -1\n") + kMinimalScene),
            "mem.toml:2:8: render.seed: seed must be >= 0 (got -1)");
}

TEST(SceneString, ElementOfTheWrongType) {
  std::string text = kMinimalScene;
  text.replace(text.find("[0, 1, 0]"), 9, "[0, true, 0]");
  EXPECT_EQ(
      string_error(text),
      "mem.toml:4:15: camera.look_at: expected an array of 3 numbers, element 1 is a boolean");
}

TEST(SceneFile, MissingFileCannotBeOpened) {
  const std::string path = kSourceDir + "/tests/scenes/no_such_scene.toml";
  EXPECT_EQ(load_error([&] { load_scene_file(path); }),
            path + ": cannot open scene file: No such file or directory");
}

}  // namespace
}  // namespace clpt
