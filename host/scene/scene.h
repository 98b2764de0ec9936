// The scene as loaded from a file: validated, in double precision, in world units, with the
// source position of every value so that later checks can still point at the file.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "scene/texture.h"

namespace clpt {

using Vec3 = std::array<double, 3>;

// Where a value came from, for error messages ("file:line:column").
struct SourcePosition {
  std::string file;
  int line = 0;
  int column = 0;
  // "file:line:column"; a position without a line (never produced by the loader) names the file.
  std::string str() const { return line <= 0 ? file : file + ":" + std::to_string(line) + ":" + std::to_string(column); }
};

// Pbr: the glTF 2.0 metallic-roughness material (the specification's Appendix B) with its
// KHR_materials_ior, _transmission, _volume and _emissive_strength extensions; TOML `type = "pbr"`.
enum class MaterialType : uint32_t { Lambertian = 0, Phong = 1, Glass = 2, Emitter = 3, Mirror = 4, Pbr = 5 };
const char* material_type_name(MaterialType type);

struct Material {
  MaterialType type = MaterialType::Lambertian;
  // albedo rho per channel, in [0, 1] (Lambertian, Phong, glass, mirror); Pbr: the base colour
  Vec3 reflectance{0, 0, 0};
  double phong_exponent = 0;  // Phong lobe exponent n >= 0
  double ior = 1.5;           // index of refraction inside (glass, Pbr); outside is 1
  // Emitted radiance per channel, >= 0 (emitters; Pbr: emissiveFactor x emissive strength, so an
  // emission of 1 writes 1 into the film).
  Vec3 emission{0, 0, 0};
  // Pbr only. metallic and roughness in [0, 1] (glTF's defaults 1 and 1); the GGX alpha is
  // roughness^2, and roughness 0 is a delta lobe. transmission in [0, 1]: the thin-walled
  // KHR_materials_transmission. thickness > 0 (KHR_materials_volume) on a closed mesh makes the
  // transmission a rough refraction through the volume instead (attenuation: Beer's law,
  // attenuation_color at attenuation_distance; infinity: none).
  double metallic = 1;
  double roughness = 1;
  double transmission = 0;
  double thickness = 0;
  Vec3 attenuation_color{1, 1, 1};
  double attenuation_distance = 0;  // world units; 0: no attenuation (glTF's +infinity)
  // glTF doubleSided (TOML meshes and every non-Pbr material: true). docs/materials.md says how a
  // single-sided surface seen from behind is rendered.
  bool double_sided = true;
  // Parameters read from images (docs/textures.md): each multiplies its value above.
  MaterialTextures textures;
};

// KHR_lights_punctual in physical units, converted by the loader: a light of I candela has a
// radiant intensity of I/683 W/sr, a directional light of E lux an irradiance of E/683 W/m^2 (the
// lumens-per-watt factor Blender's glTF importer uses in its default, physical, mode).
constexpr double kLumensPerWatt = 683;  // candela -> W/sr and lux -> W/m^2 divide by this
enum class LightType : uint32_t { Point = 0, Spot = 1, Directional = 2 };
const char* light_type_name(LightType type);
struct PunctualLight {
  std::string name;  // from the file, or "lights[i]"
  LightType type = LightType::Point;
  Vec3 position{0, 0, 0};   // world units (point, spot)
  Vec3 direction{0, 0, -1}; // unit, the direction the light travels: the node's local -Z (spot, directional)
  // Point and spot: radiant intensity per channel, W/sr (colour x candela / 683).
  // Directional: irradiance per channel on a surface facing the light, W/m^2 (colour x lux / 683).
  Vec3 intensity{0, 0, 0};
  double range = 0;               // world units; 0: unlimited (glTF's undefined range)
  double inner_cone_rad = 0;      // spot: half-angles, 0 <= inner < outer <= pi/2
  double outer_cone_rad = 0.7853981633974483;
  SourcePosition where;           // the file and element it came from
};

struct Sphere {
  std::string name;  // from the file, or "sphere[i]"
  Vec3 center{0, 0, 0};
  double radius = 1;  // world units, > 0
  Material material;
  SourcePosition where;  // position of the [[sphere]] table
};

// How a [[mesh]] table places its vertices in the world: p_world = translate + Rz Ry Rx (scale * p),
// i.e. scale per axis first, then rotate about x, then y, then z (degrees, right-handed), then
// translate. Kept beside the world-space positions so that `clpt scene-transform` can write a file
// mesh back as the same file with the composed placement.
struct MeshPlacement {
  Vec3 scale{1, 1, 1};       // > 0 per axis
  Vec3 rotate_deg{0, 0, 0};  // about x, then y, then z
  Vec3 translate{0, 0, 0};   // world units, applied last
};

// A triangle mesh in world space, as the loader leaves it: positions after the [[mesh]] table's
// scale, rotation and translation; triangles as indices into positions, degenerate ones already
// dropped. Normals, when the mesh file has them, are one unit vector per position, in world space
// (shading normals); otherwise empty and the geometric normal shades.
struct TriangleMesh {
  std::string name;       // from the file, or "mesh[i]"
  std::string file;       // the mesh file as the scene names it; "" for a mesh written inline
  std::string file_hash;  // FNV-1a 64 of the mesh file's bytes, hex; "" inline
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;  // empty, or positions.size() entries
  // Texture coordinates, one per position, or empty, in OBJ's convention: (0, 0) at the image's
  // bottom-left. The glTF loader flips TEXCOORD_0's v (glTF's (0, 0) is the top-left) and
  // conjugates KHR_texture_transform likewise (docs/textures.md).
  std::vector<std::array<double, 2>> uvs;
  // Tangents (glTF TANGENT: xyz, w the bitangent's sign), one per position, in world space, or
  // empty: normal-mapped meshes without them get generated ones (device_textures.cpp).
  std::vector<std::array<double, 4>> tangents;
  // Vertex colours (glTF COLOR_0: linear RGBA, a VEC3's alpha 1, each >= 0), one per position, or
  // empty: RGB multiplies the base colour, A its alpha (device_textures.cpp, docs/textures.md).
  std::vector<std::array<double, 4>> colors;
  std::vector<std::array<uint32_t, 3>> triangles;
  Material material;
  SourcePosition where;  // position of the [[mesh]] table
  // The table's scale/rotate_deg/translate (positions and normals already include it); for an
  // inline mesh written back by the scene writer the positions are written as they are.
  MeshPlacement placement;
  // A glTF primitive (docs/gltf.md): "nodes[N] meshes[M].primitives[P]" of the glTF file `file`
  // (file_hash: that file's with its buffers), placed by the node's world transform and, under a
  // TOML [[gltf]] table, by the table's placement (kept in `placement`). "" for [[mesh]] meshes.
  std::string gltf_element;
};

// Pinhole camera. The book's camera: a sensor sensor_height units high placed sensor_distance in
// front of the pinhole, i.e. vertical_fov = 2 atan(sensor_height / 2 / sensor_distance).
// An orthographic camera (glTF `orthographic`) looks along look_at - position with parallel rays
// from a sensor ortho_height world units high (2 ymag), its width from the image's aspect.
enum class Projection : uint32_t { Perspective = 0, Orthographic = 1 };
struct Camera {
  Vec3 position{0, 0, 0};
  Vec3 look_at{0, 0, -1};
  Vec3 up{0, 1, 0};
  double vertical_fov_deg = 36.869897645844021;
  Projection projection = Projection::Perspective;
  double ortho_height = 2;  // world units, > 0 (orthographic only)
};

// Values equal the kernels' CLPT_SAMPLER_* (types.h) and are stored in checkpoints.
enum class Sampler : uint32_t { Jitter = 0, Grid = 1, Sobol = 2, SobolGrid = 3 };
const char* sampler_name(Sampler sampler);
// The image a sampler converges to: "grid", the mean over the book's 16 sub-pixel positions
// (grid, sobol-grid), or "box", the pixel's area average (jitter, sobol). The two differ where an
// edge crosses a pixel.
const char* pixel_filter_name(Sampler sampler);
// Every sampler's name, in enum order (the scene key's and the command lines' accepted words).
std::vector<std::string> sampler_names();
// The sampler called `name`, or nullopt.
std::optional<Sampler> sampler_from_name(const std::string& name);

// Everything a render needs besides geometry; the file sets defaults, the command line overrides.
struct RenderSettings {
  int width = 640;
  int height = 480;
  int64_t spp = 16;         // samples per pixel
  uint64_t seed = 1;        // key of the counter-based RNG
  int max_bounces = 9;      // camera ray + at most max_bounces bounce rays
  Sampler sampler = Sampler::Jitter;
  std::string estimator = "book";  // "book" | "nee" (kernels/kernel_options.h: Estimator)
  int rr_from = -1;                // Russian roulette from this bounce on; -1: none
  std::string light_sampling = "cap";  // "cap" | "sphere" (scene/device_scene.h: LightSampling)
};

// The environment light (docs/environment.md, scene/environment.h): radiance arriving from
// infinitely far, an equirectangular image (TOML [environment] file, --environment) or one colour,
// times strength, turned rotation_deg about +Y.
struct Environment {
  std::string file;     // the image as named ("" for a colour and for the default light, environment.h)
  std::string what;     // what named it, for messages: "scene.toml:3:1: environment.file" or "--environment"
  Vec3 color{0, 0, 0};  // radiance when file is "", linear, >= 0
  double strength = 1;  // >= 0, multiplies the image or colour
  double rotation_deg = 0;  // about +Y, right-handed: 90 turns what was seen along +X to -Z
  int width = 0, height = 0;  // the decoded image (file only)
  std::shared_ptr<const std::vector<float>> rgb;  // width x height x 3 linear floats, row 0 the zenith
  std::string hash;     // FNV-1a 64 of the decoded texels, hex (file only)
  // Finite negative texels (lossy EXR compression leaves a few) read as 0: how many and the most
  // negative, said once ("" when none; `clpt render` prints it as a warning).
  std::string notice;
  bool is_image() const { return rgb != nullptr; }  // else one colour
};

struct Scene {
  std::string file;        // path it was loaded from
  // FNV-1a 64 of the file's bytes, hex; with mesh files, chained over each one's name and
  // file_hash too (scene_loader.cpp), so --resume, checkpoints and clpt:scene_hash see a changed mesh.
  std::string file_hash;
  Camera camera;
  RenderSettings settings;
  std::vector<Sphere> spheres;
  std::vector<TriangleMesh> meshes;  // the [[mesh]] tables, in file order; then glTF primitives
  std::vector<PunctualLight> lights;  // KHR_lights_punctual (glTF), in node order
  std::optional<Environment> environment;  // [environment] or --environment; none: escaping rays are black
  std::vector<TextureImage> images;   // every image a material's TextureRef names
  // Non-fatal findings of the loader ("FILE:LINE:COLUMN: ..."), e.g. degenerate triangles dropped;
  // the commands print each as "clpt: warning: ...".
  std::vector<std::string> warnings;
};

}  // namespace clpt
