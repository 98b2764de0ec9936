// TOML -> Scene: reads the file, parses it with toml++, checks structure, key names and value
// types, and records where every value sits; scene_validate.cpp then judges the values.
// The format is described in the README; every error is clpt::Error(ExitCode::BadScene) with a
// "FILE:LINE:COLUMN: KEY: MESSAGE" message.
#include "scene/scene_loader.h"

#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "scene/environment.h"
#include "scene/gltf_error.h"
#include "scene/gltf_loader.h"
#include "scene/mesh_file.h"
#include "scene/mesh_placement.h"
#include "scene/pbr_params.h"
#include "scene/scene_validate.h"
#include "scene/texture_load.h"
#include "util/error.h"
#include "util/hash.h"

namespace clpt {

// The TOML key of a tangent-space normal map (docs/textures.md).
constexpr const char* kNormalMapKey = "normal_map";

const char* material_type_name(MaterialType type) {
  switch (type) {
    case MaterialType::Lambertian:
      return "lambertian";
    case MaterialType::Phong:
      return "phong";
    case MaterialType::Glass:
      return "glass";
    case MaterialType::Emitter:
      return "emitter";
    case MaterialType::Mirror:
      return "mirror";
    case MaterialType::Pbr:
      return "pbr";
  }
  return "unknown";
}

const char* light_type_name(LightType type) {
  switch (type) {
    case LightType::Point:
      return "point";
    case LightType::Spot:
      return "spot";
    case LightType::Directional:
      return "directional";
  }
  return "unknown";
}

const char* sampler_name(Sampler sampler) {
  switch (sampler) {
    case Sampler::Jitter:
      return "jitter";
    case Sampler::Grid:
      return "grid";
    case Sampler::Sobol:
      return "sobol";
    case Sampler::SobolGrid:
      return "sobol-grid";
  }
  return "unknown";
}

const char* pixel_filter_name(Sampler sampler) {
  return sampler == Sampler::Grid || sampler == Sampler::SobolGrid ? "grid" : "box";
}

namespace {
constexpr Sampler kSamplers[] = {Sampler::Jitter, Sampler::Grid, Sampler::Sobol, Sampler::SobolGrid};
}  // namespace

std::vector<std::string> sampler_names() {
  std::vector<std::string> names;
  for (Sampler s : kSamplers) names.emplace_back(sampler_name(s));
  return names;
}

std::optional<Sampler> sampler_from_name(const std::string& name) {
  for (Sampler s : kSamplers)
    if (name == sampler_name(s)) return s;
  return std::nullopt;
}

namespace {

using scene_detail::fail;
using scene_detail::SourceMap;

constexpr MaterialType kMaterialTypes[] = {MaterialType::Lambertian, MaterialType::Phong,
                                           MaterialType::Glass, MaterialType::Emitter,
                                           MaterialType::Mirror, MaterialType::Pbr};
constexpr LightType kLightTypes[] = {LightType::Point, LightType::Spot, LightType::Directional};

// Levenshtein distance; keys are short, so the O(n m) table is cheap.
size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t substitution = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
      diagonal = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, substitution});
    }
  }
  return row[b.size()];
}

// The candidate within edit distance 2 of `word` (closest first, then first listed), or nothing.
// A candidate must keep at least one of its characters: "x" does not suggest "up".
std::optional<std::string> closest_match(std::string_view word,
                                         const std::vector<std::string>& candidates) {
  std::optional<std::string> best;
  size_t best_distance = 3;
  for (const std::string& candidate : candidates) {
    const size_t distance = edit_distance(word, candidate);
    if (distance < best_distance && distance < candidate.size()) {
      best = candidate;
      best_distance = distance;
    }
  }
  return best;
}

// "'a', 'b' or 'c'"
std::string quoted_list(const std::vector<std::string>& words) {
  std::string out;
  for (size_t i = 0; i < words.size(); ++i) {
    if (i > 0) out += i + 1 == words.size() ? " or " : ", ";
    out += "'" + words[i] + "'";
  }
  return out;
}

// A near miss gets "unknown KIND 'phnog'; did you mean 'phong'?"; anything else gets
// "unknown KIND 'WORD' (ALTERNATIVES)", so the user always learns what would be accepted.
std::string unknown_word_message(const std::string& kind, const std::string& word,
                                 const std::vector<std::string>& known,
                                 const std::string& alternatives) {
  const std::string head = "unknown " + kind + " '" + word + "'";
  if (const auto match = closest_match(word, known))
    return head + "; did you mean '" + *match + "'?";
  return head + " (" + alternatives + ")";
}

// English name of a TOML value's type, with its article, for "expected X, got Y" messages.
std::string type_description(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a floating-point number";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    case toml::node_type::none:
      break;
  }
  return "nothing";
}

std::string join_key(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}

// Reads the keys of one TOML table, whose dotted path is `path` ("" for the document root).
// Every value it hands out has passed its type check and has its position recorded in the
// SourceMap under its dotted key. The table's own position `where` stands in for nodes that
// carry none (tables toml++ created implicitly, e.g. [camera] when only [camera.x] is written).
class TableReader {
 public:
  TableReader(const toml::table& table, std::string path, SourcePosition where, SourceMap& sources)
      : table_(table), path_(std::move(path)), where_(std::move(where)), sources_(sources) {
    if (!path_.empty()) sources_.record(path_, where_);
  }

  const std::string& path() const { return path_; }
  const SourcePosition& where() const { return where_; }
  std::string key_path(std::string_view key) const { return join_key(path_, key); }

  SourcePosition position_of(const toml::node& node) const { return position_of(node.source()); }
  SourcePosition position_of(const toml::source_region& source) const {
    if (source.begin.line == 0) return where_;
    return SourcePosition{where_.file, static_cast<int>(source.begin.line),
                          static_cast<int>(source.begin.column)};
  }

  // Rejects the key earliest in the file that is not in `known`, suggesting a near miss.
  void reject_unknown_keys(const std::vector<std::string>& known) const;

  // The value under `key` or nullptr; records its position.
  const toml::node* get(std::string_view key) const;
  [[noreturn]] void fail_missing(std::string_view key) const {
    fail(where_, path_, "missing required key '" + std::string(key) + "'");
  }
  [[noreturn]] void fail_type(std::string_view key, const toml::node& node,
                              const std::string& expected) const {
    fail(position_of(node), key_path(key),
         "expected " + expected + ", got " + type_description(node));
  }

  std::optional<int64_t> integer(std::string_view key) const;
  std::optional<double> number(std::string_view key) const;
  std::optional<std::string> string(std::string_view key) const;
  std::optional<bool> boolean(std::string_view key) const;
  std::optional<Vec3> vec3(std::string_view key) const;
  // The array of arrays under `key`, each of N numbers (integers when T is int64_t); records
  // each row's position as "KEY[i]". Empty when the key is absent.
  template <typename T, size_t N>
  std::vector<std::array<T, N>> rows(std::string_view key) const;
  // The sub-table under `key`: a [header] table or an inline { } table.
  std::optional<TableReader> table(std::string_view key) const;
  // A reader for a table reached other than by key (an element of an array of tables).
  TableReader child(const toml::table& table, std::string path, SourcePosition where) const {
    return TableReader(table, std::move(path), std::move(where), sources_);
  }

  double required_number(std::string_view key) const {
    if (auto value = number(key)) return *value;
    fail_missing(key);
  }
  Vec3 required_vec3(std::string_view key) const {
    if (auto value = vec3(key)) return *value;
    fail_missing(key);
  }

 private:
  const toml::table& table_;
  std::string path_;
  SourcePosition where_;
  SourceMap& sources_;
};

void TableReader::reject_unknown_keys(const std::vector<std::string>& known) const {
  // toml::table iterates in key order; report the first unknown key in file order instead.
  const toml::key* first = nullptr;
  for (const auto& [key, value] : table_) {
    if (std::find(known.begin(), known.end(), key.str()) != known.end()) continue;
    const auto& at = key.source().begin;
    if (!first || at < first->source().begin) first = &key;
  }
  if (!first) return;
  const std::string word(first->str());
  std::string alternatives = "expected one of: ";
  for (size_t i = 0; i < known.size(); ++i) alternatives += (i > 0 ? ", " : "") + known[i];
  fail(position_of(first->source()), key_path(word),
       unknown_word_message("key", word, known, alternatives));
}

const toml::node* TableReader::get(std::string_view key) const {
  const toml::node* node = table_.get(key);
  if (node) sources_.record(key_path(key), position_of(*node));
  return node;
}

std::optional<int64_t> TableReader::integer(std::string_view key) const {
  const toml::node* node = get(key);
  if (!node) return std::nullopt;
  if (const auto* value = node->as_integer()) return value->get();
  fail_type(key, *node, "an integer");
}

std::optional<double> TableReader::number(std::string_view key) const {
  const toml::node* node = get(key);
  if (!node) return std::nullopt;
  if (const auto* value = node->as_floating_point()) return value->get();
  if (const auto* value = node->as_integer()) return static_cast<double>(value->get());
  fail_type(key, *node, "a number");
}

std::optional<bool> TableReader::boolean(std::string_view key) const {
  const toml::node* node = get(key);
  if (!node) return std::nullopt;
  if (const auto* value = node->as_boolean()) return value->get();
  fail_type(key, *node, "true or false");
}

std::optional<std::string> TableReader::string(std::string_view key) const {
  const toml::node* node = get(key);
  if (!node) return std::nullopt;
  if (const auto* value = node->as_string()) return value->get();
  fail_type(key, *node, "a string");
}

std::optional<Vec3> TableReader::vec3(std::string_view key) const {
  const toml::node* node = get(key);
  if (!node) return std::nullopt;
  const toml::array* array = node->as_array();
  if (!array) fail_type(key, *node, "an array of 3 numbers");
  if (array->size() != 3)
    fail(position_of(*node), key_path(key),
         "expected an array of 3 numbers, got " + std::to_string(array->size()) + " elements");
  Vec3 out{};
  for (size_t i = 0; i < 3; ++i) {
    const toml::node& element = *array->get(i);
    if (const auto* f = element.as_floating_point())
      out[i] = f->get();
    else if (const auto* n = element.as_integer())
      out[i] = static_cast<double>(n->get());
    else
      fail(position_of(element), key_path(key),
           "expected an array of 3 numbers, element " + std::to_string(i) + " is " +
               type_description(element));
  }
  return out;
}

// One element of a row of rows<T, N>(): a number (double) or an integer (int64_t), or nothing.
std::optional<double> row_element(const toml::node& node, double*) {
  if (const auto* f = node.as_floating_point()) return f->get();
  if (const auto* n = node.as_integer()) return static_cast<double>(n->get());
  return std::nullopt;
}
std::optional<int64_t> row_element(const toml::node& node, int64_t*) {
  if (const auto* n = node.as_integer()) return n->get();
  return std::nullopt;
}

template <typename T, size_t N>
std::vector<std::array<T, N>> TableReader::rows(std::string_view key) const {
  const std::string what = "an array of arrays of " + std::to_string(N) +
                           (std::is_integral_v<T> ? " integers" : " numbers");
  std::vector<std::array<T, N>> out;
  const toml::node* node = get(key);
  if (!node) return out;
  const toml::array* array = node->as_array();
  if (!array) fail_type(key, *node, what);
  for (size_t i = 0; i < array->size(); ++i) {
    const toml::node& row_node = *array->get(i);
    const std::string row_key = key_path(key) + "[" + std::to_string(i) + "]";
    sources_.record(row_key, position_of(row_node));
    const toml::array* row = row_node.as_array();
    if (!row || row->size() != N)
      fail(position_of(row_node), row_key,
           "expected " + what + ", got " + (row ? std::to_string(row->size()) + " elements" : type_description(row_node)));
    std::array<T, N> values{};
    for (size_t j = 0; j < N; ++j) {
      const auto value = row_element(*row->get(j), static_cast<T*>(nullptr));
      if (!value)
        fail(position_of(*row->get(j)), row_key,
             "expected " + what + ", element " + std::to_string(j) + " is " + type_description(*row->get(j)));
      values[j] = *value;
    }
    out.push_back(values);
  }
  return out;
}

std::optional<TableReader> TableReader::table(std::string_view key) const {
  const toml::node* node = get(key);
  if (!node) return std::nullopt;
  const toml::table* sub = node->as_table();
  if (!sub) fail_type(key, *node, "a table");
  return TableReader(*sub, key_path(key), position_of(*node), sources_);
}

// Integer settings: type-checked here, range-checked before narrowing to the field's type.
template <typename Field>
void read_integer_setting(const TableReader& reader, std::string_view key, Field& field) {
  const toml::node* node = reader.get(key);
  if (const auto value = reader.integer(key)) {
    scene_detail::check_integer_setting(reader.key_path(key), *value, reader.position_of(*node));
    field = static_cast<Field>(*value);
  }
}

void read_image(const TableReader& image, RenderSettings& settings) {
  image.reject_unknown_keys({"width", "height"});
  read_integer_setting(image, "width", settings.width);
  read_integer_setting(image, "height", settings.height);
}

Sampler parse_sampler(const TableReader& render, const std::string& name) {
  if (const auto sampler = sampler_from_name(name)) return *sampler;
  const std::vector<std::string> names = sampler_names();
  fail(render.position_of(*render.get("sampler")), render.key_path("sampler"),
       unknown_word_message("sampler", name, names, "expected " + quoted_list(names)));
}

void read_render(const TableReader& render, RenderSettings& settings) {
  render.reject_unknown_keys({"spp", "seed", "max_bounces", "sampler", "estimator", "rr_from", "light_sampling"});
  read_integer_setting(render, "spp", settings.spp);
  read_integer_setting(render, "seed", settings.seed);
  read_integer_setting(render, "max_bounces", settings.max_bounces);
  if (const auto name = render.string("sampler")) settings.sampler = parse_sampler(render, *name);
  if (const auto estimator = render.string("estimator")) settings.estimator = *estimator;
  read_integer_setting(render, "rr_from", settings.rr_from);
  if (const auto sampling = render.string("light_sampling")) settings.light_sampling = *sampling;
}

// `projection`: "perspective" (the default: vertical_fov_deg) or "orthographic" (height, the
// sensor's height in world units); each projection's own key only.
void read_camera(const TableReader& camera_table, Camera& camera) {
  camera_table.reject_unknown_keys({"position", "look_at", "up", "vertical_fov_deg", "projection", "height"});
  camera.position = camera_table.required_vec3("position");
  camera.look_at = camera_table.required_vec3("look_at");
  if (const auto up = camera_table.vec3("up")) camera.up = *up;
  const std::string projection = camera_table.string("projection").value_or("perspective");
  const std::vector<std::string> projections = {"perspective", "orthographic"};
  if (projection != projections[0] && projection != projections[1])
    fail(camera_table.position_of(*camera_table.get("projection")), camera_table.key_path("projection"),
         unknown_word_message("projection", projection, projections, "expected " + quoted_list(projections)));
  camera.projection = projection == "orthographic" ? Projection::Orthographic : Projection::Perspective;
  const char* foreign = camera.projection == Projection::Orthographic ? "vertical_fov_deg" : "height";
  if (const toml::node* node = camera_table.get(foreign))
    fail(camera_table.position_of(*node), camera_table.key_path(foreign),
         "'" + std::string(foreign) + "' does not apply to a " + projection + " camera");
  if (const auto fov = camera_table.number("vertical_fov_deg")) camera.vertical_fov_deg = *fov;
  if (camera.projection == Projection::Orthographic) camera.ortho_height = camera_table.required_number("height");
}

MaterialType parse_material_type(const TableReader& material) {
  const auto name = material.string("type");
  if (!name) material.fail_missing("type");
  std::vector<std::string> names;
  for (MaterialType t : kMaterialTypes) {
    if (*name == material_type_name(t)) return t;
    names.emplace_back(material_type_name(t));
  }
  fail(material.position_of(*material.get("type")), material.key_path("type"),
       unknown_word_message("material type", *name, names, "expected " + quoted_list(names)));
}

// The parameter keys each material type takes (besides "type"); anything else in the table is
// an error, so a parameter that does nothing for this type is caught instead of ignored.
std::vector<std::string> material_parameters(MaterialType type) {
  switch (type) {
    case MaterialType::Lambertian:
      return {"reflectance", kNormalMapKey};
    case MaterialType::Phong:
      return {"reflectance", "exponent", kNormalMapKey};
    case MaterialType::Glass:
      return {"reflectance", "ior", kNormalMapKey};
    case MaterialType::Emitter:
      return {"emission"};
    case MaterialType::Mirror:
      return {"reflectance", kNormalMapKey};
    case MaterialType::Pbr: {
      std::vector<std::string> keys{kPbrDoubleSidedKey, kNormalMapKey};
      for (const PbrNumber& n : kPbrNumbers) keys.emplace_back(n.key);
      for (const PbrColour& c : kPbrColours) keys.emplace_back(c.key);
      return keys;
    }
  }
  return {};
}

// Every key any material type takes, "type" first.
std::vector<std::string> all_material_keys() {
  std::vector<std::string> keys{"type"};
  for (MaterialType t : kMaterialTypes)
    for (const std::string& k : material_parameters(t))
      if (std::find(keys.begin(), keys.end(), k) == keys.end()) keys.push_back(k);
  return keys;
}

void reject_foreign_parameters(const TableReader& material, MaterialType type) {
  const std::vector<std::string> own = material_parameters(type);
  for (const std::string& key : all_material_keys()) {
    if (key == "type" || std::find(own.begin(), own.end(), key) != own.end() || !material.get(key)) continue;
    fail(material.position_of(*material.get(key)), material.key_path(key),
         "'" + std::string(key) + "' does not apply to material type '" + material_type_name(type) +
             "'");
  }
}

// Textured values (docs/textures.md): `KEY = { texture = "wood.png", scale = ..., wrap = ...,
// filter = ..., uv_scale = ..., color_space = ..., channel = ... }` instead of a colour or number.
// `images` is the scene's image list; nullptr makes any texture an error (kept for objects
// without texture coordinates; spheres have theirs from the spherical mapping, docs/textures.md).
bool is_texture_value(const TableReader& material, std::string_view key) {
  const toml::node* node = material.get(key);
  return node && node->is_table();
}

// The texture table under `key`. Colours (`colour`) take `scale` as a number or [r, g, b] into
// *colour_factor, scalars as a number into *number_factor, and `channel`; a normal map (`normal`)
// takes `scale` as glTF's normalTexture.scale. The image is loaded into `images`.
TextureRef read_texture_value(const TableReader& material, std::string_view key, std::vector<TextureImage>* images,
                              bool colour, bool normal, Vec3* colour_factor, double* number_factor,
                              double* normal_scale) {
  const toml::node* node = material.get(key);
  const SourcePosition at = material.position_of(*node);
  if (!images)
    fail(at, material.key_path(key), "a texture needs texture coordinates, and this object has none");
  const auto table = material.table(key);
  std::vector<std::string> keys{"texture", "scale", "wrap", "filter", "uv_scale", "color_space"};
  if (!colour && !normal) keys.emplace_back("channel");
  table->reject_unknown_keys(keys);
  const auto file = table->string("texture");
  if (!file) table->fail_missing("texture");
  TextureRef ref;
  ref.where = at.str() + ": " + material.key_path(key);
  if (const toml::node* scale = table->get("scale")) {
    if (colour && scale->is_array()) {
      *colour_factor = *table->vec3("scale");
    } else {
      const auto value = table->number("scale");
      if (!value) table->fail_type("scale", *scale, colour ? "a number or an array of 3 numbers" : "a number");
      if (colour) *colour_factor = {*value, *value, *value};
      if (!colour && !normal) *number_factor = *value;
      if (normal) *normal_scale = *value;
    }
    if (normal && !(std::isfinite(*normal_scale) && std::fabs(*normal_scale) <= 100))
      fail(table->position_of(*scale), table->key_path("scale"), "must be a number in [-100, 100]");
  }
  const auto word = [&](const char* name, std::initializer_list<const char*> words) -> int {
    const auto value = table->string(name);
    if (!value) return 0;
    std::vector<std::string> names(words.begin(), words.end());
    for (size_t i = 0; i < names.size(); ++i)
      if (*value == names[i]) return int(i);
    fail(table->position_of(*table->get(name)), table->key_path(name),
         unknown_word_message(name, *value, names, "expected " + quoted_list(names)));
  };
  ref.wrap_u = ref.wrap_v = static_cast<TextureWrap>(word("wrap", {"repeat", "clamp", "mirror"}));
  ref.filter = static_cast<TextureFilter>(word("filter", {"bilinear", "nearest"}));
  std::optional<ColorSpace> space;
  if (table->get("color_space")) space = static_cast<ColorSpace>(word("color_space", {"srgb", "linear"}));
  if (!colour && !space) space = ColorSpace::Linear;  // data, not colour: scalars and normal maps
  if (const toml::node* uv = table->get("uv_scale")) {
    double su = 1, sv = 1;
    if (uv->is_number()) {
      su = sv = *table->number("uv_scale");
    } else {
      const toml::array* a = uv->as_array();
      if (!a || a->size() != 2 || !a->get(0)->is_number() || !a->get(1)->is_number())
        table->fail_type("uv_scale", *uv, "a number or an array of 2 numbers");
      su = a->get(0)->value<double>().value_or(1);
      sv = a->get(1)->value<double>().value_or(1);
    }
    if (!(std::isfinite(su) && std::isfinite(sv) && su != 0 && sv != 0 && std::fabs(su) <= 1e6 && std::fabs(sv) <= 1e6))
      fail(table->position_of(*uv), table->key_path("uv_scale"), "must be non-zero and at most 1e6 in size");
    ref.uv_transform = {su, 0, 0, 0, sv, 0};  // about (0, 0), the image's bottom-left
  }
  if (const auto channel = table->integer("channel")) {
    if (*channel < 0 || *channel > 3)
      fail(table->position_of(*table->get("channel")), table->key_path("channel"), "must be 0, 1, 2 or 3 (R, G, B, A)");
    ref.channel = int(*channel);
  }
  const std::string file_key = table->position_of(*table->get("texture")).str() + ": " + table->key_path("texture");
  ref.image = load_texture_image(*images, resolve_mesh_path(material.where().file, *file), *file, space, file_key);
  return ref;
}

// A colour parameter: [r, g, b], or a texture table (its factor `scale`, default 1).
std::optional<Vec3> textured_vec3(const TableReader& material, std::string_view key, TextureRef& ref,
                                  std::vector<TextureImage>* images) {
  if (!is_texture_value(material, key)) return material.vec3(key);
  Vec3 factor{1, 1, 1};
  ref = read_texture_value(material, key, images, true, false, &factor, nullptr, nullptr);
  return factor;
}

std::optional<double> textured_number(const TableReader& material, std::string_view key, TextureRef& ref,
                                      std::vector<TextureImage>* images) {
  if (!is_texture_value(material, key)) return material.number(key);
  double factor = 1;
  ref = read_texture_value(material, key, images, false, false, nullptr, &factor, nullptr);
  return factor;
}

// The pbr keys that may be textures, and their slots.
TextureRef* pbr_texture_slot(Material& m, const char* key) {
  const std::string k = key;
  if (k == "base_color") return &m.textures.base_color;
  if (k == "emission") return &m.textures.emission;
  if (k == "metallic") return &m.textures.metallic;
  if (k == "roughness") return &m.textures.roughness;
  return nullptr;
}

// A `type = "pbr"` material: the keys of pbr_params.h, each at glTF's default when absent.
void read_pbr_material(const TableReader& material, Material& m, std::vector<TextureImage>* images) {
  const auto untextured = [&](const char* key) {
    if (is_texture_value(material, key))
      fail(material.position_of(*material.get(key)), material.key_path(key),
           "cannot be a texture (base_color, metallic, roughness and emission can)");
  };
  for (const PbrNumber& n : kPbrNumbers) {
    TextureRef* slot = pbr_texture_slot(m, n.key);
    if (!slot) untextured(n.key);
    TextureRef unused;
    m.*n.field = textured_number(material, n.key, slot ? *slot : unused, images).value_or(n.fallback);
  }
  for (const PbrColour& c : kPbrColours) {
    TextureRef* slot = pbr_texture_slot(m, c.key);
    if (!slot) untextured(c.key);
    TextureRef unused;
    m.*c.field = textured_vec3(material, c.key, slot ? *slot : unused, images).value_or(c.fallback);
  }
  m.double_sided = material.boolean(kPbrDoubleSidedKey).value_or(true);
}

void read_normal_map(const TableReader& material, Material& m, std::vector<TextureImage>* images) {
  const toml::node* node = material.get(kNormalMapKey);
  if (!node) return;
  if (!node->is_table()) material.fail_type(kNormalMapKey, *node, "a texture table ({ texture = \"FILE\", ... })");
  m.textures.normal = read_texture_value(material, kNormalMapKey, images, false, true, nullptr, nullptr, &m.textures.normal_scale);
}

// `images`: the scene's image list.
Material read_material(const TableReader& material, std::vector<TextureImage>* images) {
  // Unknown keys first, against every material key, so a misspelling gets its suggestion.
  material.reject_unknown_keys(all_material_keys());
  Material m;
  m.type = parse_material_type(material);
  reject_foreign_parameters(material, m.type);
  if (m.type != MaterialType::Emitter) read_normal_map(material, m, images);
  if (m.type == MaterialType::Pbr) {
    read_pbr_material(material, m, images);
    return m;
  }
  if (m.type == MaterialType::Emitter) {
    const auto emission = textured_vec3(material, "emission", m.textures.emission, images);
    if (!emission) material.fail_missing("emission");
    m.emission = *emission;
    return m;
  }
  const auto reflectance = textured_vec3(material, "reflectance", m.textures.base_color, images);
  if (!reflectance) material.fail_missing("reflectance");
  m.reflectance = *reflectance;
  if (m.type == MaterialType::Phong) m.phong_exponent = material.required_number("exponent");
  if (m.type == MaterialType::Glass) m.ior = material.required_number("ior");
  return m;
}

// Sphere::where and TriangleMesh::where: the [[sphere]] or [[mesh]] header (or inline table); if toml++ gave the table no position,
// its first key in the file; failing that, `fallback` (the array's position).
SourcePosition table_position(const toml::table& table, const TableReader& top,
                               const SourcePosition& fallback) {
  const toml::source_position* first = nullptr;
  if (table.source().begin.line > 0) first = &table.source().begin;
  for (const auto& [key, value] : table) {
    const toml::source_position& at = key.source().begin;
    if (!first && at.line > 0) first = &at;
    if (first && at.line > 0 && at < *first) first = &at;
  }
  if (!first) return fallback;
  return top.position_of(toml::source_region{*first, *first, nullptr});
}

// A sphere's material may be textured through the spherical mapping (docs/textures.md), all but
// a normal map (spheres have no tangent frame in the kernels).
Sphere read_sphere(const TableReader& sphere, size_t index, std::vector<TextureImage>& images) {
  sphere.reject_unknown_keys({"name", "center", "radius", "material"});
  Sphere s;
  s.name = sphere.string("name").value_or("sphere[" + std::to_string(index) + "]");
  s.center = sphere.required_vec3("center");
  s.radius = sphere.required_number("radius");
  const auto material = sphere.table("material");
  if (!material) sphere.fail_missing("material");
  if (const toml::node* normal = material->get(kNormalMapKey))
    fail(material->position_of(*normal), material->key_path(kNormalMapKey),
         "sphere '" + s.name + "': normal maps apply to meshes only (a sphere's material takes colour, metallic, "
         "roughness and emission textures: docs/textures.md)");
  s.material = read_material(*material, &images);
  s.where = sphere.where();
  return s;
}

// `scale`: one number for all three axes or [sx, sy, sz]; 1 when absent.
Vec3 read_mesh_scale(const TableReader& mesh) {
  const toml::node* node = mesh.get("scale");
  if (!node) return {1, 1, 1};
  if (node->is_number()) {
    const double s = *mesh.number("scale");
    return {s, s, s};
  }
  if (!node->is_array()) mesh.fail_type("scale", *node, "a number or an array of 3 numbers");
  return *mesh.vec3("scale");
}

// `file`: read through assimp (mesh_file.h); every MeshFileError gets the `file` value's position
// and the file's name as the scene writes it. The file's warnings are returned prefixed the same.
LocalMesh read_mesh_file_table(const TableReader& mesh, const std::string& file, const std::string& scene_file,
                               TriangleMesh& out, std::vector<std::string>& warnings) {
  const SourcePosition at = mesh.position_of(*mesh.get("file"));
  const std::string prefix = at.str() + ": " + mesh.key_path("file") + ": " + file + ": ";
  try {
    const std::string extension = mesh_file_extension(file);
    const std::string bytes = read_mesh_file(resolve_mesh_path(scene_file, file));
    out.file_hash = hex64(fnv1a64(bytes));
    MeshFileContents contents = parse_mesh_file(bytes, extension);
    for (const std::string& w : contents.warnings) warnings.push_back(prefix + w);
    return std::move(contents.mesh);
  } catch (const MeshFileError& e) {
    throw Error(ExitCode::BadScene, prefix + e.what());
  }
}

// One [[mesh]] table: a mesh file or inline vertices, placed, degenerate triangles dropped (and
// counted in a warning).
TriangleMesh read_mesh(const TableReader& mesh, size_t index, const SourceMap& sources,
                       std::vector<std::string>& warnings, std::vector<TextureImage>& images) {
  mesh.reject_unknown_keys(
      {"name", "file", "scale", "rotate_deg", "translate", "material", "vertices", "normals", "uvs", "triangles", "quads"});
  TriangleMesh m;
  m.name = mesh.string("name").value_or("mesh[" + std::to_string(index) + "]");
  m.where = mesh.where();
  m.placement.scale = read_mesh_scale(mesh);
  if (const auto r = mesh.vec3("rotate_deg")) m.placement.rotate_deg = *r;
  if (const auto t = mesh.vec3("translate")) m.placement.translate = *t;
  const auto material = mesh.table("material");
  if (!material) mesh.fail_missing("material");
  m.material = read_material(*material, &images);
  scene_detail::check_mesh_placement(m.placement, mesh.path(), sources);

  const auto file = mesh.string("file");
  LocalMesh local;
  if (file) {
    for (const char* inline_key : {"vertices", "normals", "uvs", "triangles", "quads"})
      if (const toml::node* node = mesh.get(inline_key))
        fail(mesh.position_of(*node), mesh.key_path(inline_key),
             "'" + std::string(inline_key) + "' does not go with 'file' (a mesh is a file or written inline)");
    m.file = *file;
    local = read_mesh_file_table(mesh, *file, sources.file(), m, warnings);
  } else {
    if (!mesh.get("vertices")) fail(mesh.where(), mesh.path(), "a mesh needs 'file' or inline 'vertices'");
    scene_detail::InlineMeshRows rows;
    rows.vertices = mesh.rows<double, 3>("vertices");
    rows.normals = mesh.rows<double, 3>("normals");
    rows.uvs = mesh.rows<double, 2>("uvs");
    rows.triangles = mesh.rows<int64_t, 3>("triangles");
    rows.quads = mesh.rows<int64_t, 4>("quads");
    local = scene_detail::inline_local_mesh(rows, mesh.path(), sources);
  }
  const size_t dropped = place_mesh(local, m);
  scene_detail::check_placed_mesh(m, dropped, mesh.path(), sources);
  if (dropped > 0)
    warnings.push_back(m.where.str() + ": mesh '" + m.name + "': " + std::to_string(dropped) + " of " +
                       std::to_string(local.triangles.size()) + " triangles have zero area and were dropped");
  return m;
}

// One [[gltf]] table: the glTF file's meshes and lights placed by scale, rotate_deg and translate
// as [[mesh]] places a mesh file; every GltfError gets the `file` value's position and the file's
// name as the scene writes it, and so do the glTF's warnings.
GltfContents read_gltf(const TableReader& table, const SourceMap& sources, std::vector<std::string>& warnings,
                       std::vector<std::pair<std::string, std::string>>& gltf_files) {
  table.reject_unknown_keys({"file", "scale", "rotate_deg", "translate"});
  const auto file = table.string("file");
  if (!file) table.fail_missing("file");
  MeshPlacement placement;
  placement.scale = read_mesh_scale(table);
  if (const auto r = table.vec3("rotate_deg")) placement.rotate_deg = *r;
  if (const auto t = table.vec3("translate")) placement.translate = *t;
  scene_detail::check_mesh_placement(placement, table.path(), sources);
  const SourcePosition at = table.position_of(*table.get("file"));
  const std::string prefix = at.str() + ": " + table.key_path("file") + ": " + *file + ": ";
  try {
    GltfContents contents = load_gltf_contents(resolve_mesh_path(sources.file(), *file), placement);
    for (TriangleMesh& m : contents.meshes) {
      m.file = *file;
      m.where = table.where();
    }
    for (const std::string& w : contents.warnings) warnings.push_back(prefix + w);
    gltf_files.emplace_back(*file, contents.hash);
    return contents;
  } catch (const GltfError& e) {
    throw Error(ExitCode::BadScene, prefix + e.what());
  }
}

LightType parse_light_type(const TableReader& light) {
  const auto name = light.string("type");
  if (!name) light.fail_missing("type");
  std::vector<std::string> names;
  for (LightType t : kLightTypes) {
    if (*name == light_type_name(t)) return t;
    names.emplace_back(light_type_name(t));
  }
  fail(light.position_of(*light.get("type")), light.key_path("type"),
       unknown_word_message("light type", *name, names, "expected " + quoted_list(names)));
}

// One [[light]] table, a punctual light (docs/materials.md, "Lights"). Its strength is
// `intensity` (per channel, W/sr for point and spot, W/m^2 for directional) or, photometric as
// glTF writes it, `candela` (point, spot) or `lux` (directional) times `color`, divided by 683
// lm/W. Keys that do not apply to the type are errors.
PunctualLight read_light(const TableReader& light, size_t index) {
  light.reject_unknown_keys({"name", "type", "position", "direction", "intensity", "candela", "lux", "color",
                             "range", "inner_cone_deg", "outer_cone_deg"});
  PunctualLight l;
  l.name = light.string("name").value_or("light[" + std::to_string(index) + "]");
  l.where = light.where();
  l.type = parse_light_type(light);
  const bool directional = l.type == LightType::Directional;
  std::vector<std::string> foreign = {directional ? "candela" : "lux"};
  if (directional) foreign.insert(foreign.end(), {"position", "range"});
  if (l.type != LightType::Spot) foreign.insert(foreign.end(), {"inner_cone_deg", "outer_cone_deg"});
  if (l.type == LightType::Point) foreign.emplace_back("direction");
  for (const std::string& key : foreign)
    if (const toml::node* node = light.get(key))
      fail(light.position_of(*node), light.key_path(key),
           "'" + key + "' does not apply to light type '" + light_type_name(l.type) + "'");
  if (!directional) l.position = light.required_vec3("position");
  if (l.type != LightType::Point) l.direction = light.required_vec3("direction");
  const char* photometric = directional ? "lux" : "candela";
  const auto intensity = light.vec3("intensity");
  const auto amount = light.number(photometric);
  if (intensity && amount)
    fail(light.position_of(*light.get(photometric)), light.key_path(photometric),
         "'" + std::string(photometric) + "' does not go with 'intensity' (a light's strength is one of them)");
  if (intensity && light.get("color"))
    fail(light.position_of(*light.get("color")), light.key_path("color"),
         "'color' goes with '" + std::string(photometric) + "', not with 'intensity' (which is per channel)");
  if (!intensity && !amount)
    fail(light.where(), light.path(), "missing required key 'intensity' (or '" + std::string(photometric) + "')");
  if (intensity) l.intensity = *intensity;
  if (amount) {
    const Vec3 color = light.vec3("color").value_or(Vec3{1, 1, 1});
    for (int i = 0; i < 3; ++i) l.intensity[i] = color[i] * *amount / kLumensPerWatt;
  }
  l.range = light.number("range").value_or(0);
  const double degrees = 3.14159265358979323846 / 180;
  l.inner_cone_rad = light.number("inner_cone_deg").value_or(0) * degrees;
  l.outer_cone_rad = light.number("outer_cone_deg").value_or(45) * degrees;
  return l;
}

// The [environment] table (docs/environment.md): an equirectangular image `file` (resolved
// against the scene file's directory, read through scene/scene_image.h) or a `color`, times
// `strength`, turned `rotation_deg` about +Y.
Environment read_environment(const TableReader& table, const SourceMap& sources) {
  table.reject_unknown_keys({"file", "color", "strength", "rotation_deg"});
  Environment e;
  const auto file = table.string("file");
  const auto color = table.vec3("color");
  if (file && color)
    fail(table.position_of(*table.get("color")), table.key_path("color"),
         "'color' does not go with 'file' (an environment is an image or one colour)");
  if (!file && !color) fail(table.where(), table.path(), "missing required key 'file' (or 'color')");
  if (const auto strength = table.number("strength")) {
    if (!(std::isfinite(*strength) && *strength >= 0))
      fail(table.position_of(*table.get("strength")), table.key_path("strength"),
           "must be finite and >= 0, got " + scene_detail::format_number(*strength));
    e.strength = *strength;
  }
  if (const auto rotation = table.number("rotation_deg")) {
    if (!std::isfinite(*rotation))
      fail(table.position_of(*table.get("rotation_deg")), table.key_path("rotation_deg"),
           "must be finite, got " + scene_detail::format_number(*rotation));
    e.rotation_deg = *rotation;
  }
  if (color) {
    for (int i = 0; i < 3; ++i)
      if (!(std::isfinite((*color)[i]) && (*color)[i] >= 0))
        fail(table.position_of(*table.get("color")), table.key_path("color"),
             "radiance must be finite and >= 0, element " + std::to_string(i) + " is " +
                 scene_detail::format_number((*color)[i]));
    e.color = *color;
    return e;
  }
  if (file->empty()) fail(table.position_of(*table.get("file")), table.key_path("file"), "empty file name");
  e.file = *file;
  e.what = table.position_of(*table.get("file")).str() + ": " + table.key_path("file");
  load_environment_image(e, resolve_mesh_path(sources.file(), *file), ExitCode::BadScene);
  return e;
}

// The array of tables under `key` ([[sphere]], [[mesh]], [[gltf]], [[light]]), each element read by
// read(reader, index); none when the key is absent.
template <typename Read>
auto read_table_array(const TableReader& top, const std::string& key, Read read) {
  std::vector<decltype(read(top, size_t(0)))> out;
  const toml::node* node = top.get(key);
  if (!node) return out;
  const toml::array* array = node->as_array();
  if (!array) top.fail_type(key, *node, "an array of tables ([[" + key + "]])");
  for (size_t i = 0; i < array->size(); ++i) {
    const toml::node& element = *array->get(i);
    const std::string path = key + "[" + std::to_string(i) + "]";
    const toml::table* table = element.as_table();
    if (!table)
      fail(top.position_of(element), path, "expected a table, got " + type_description(element));
    const SourcePosition where = table_position(*table, top, top.position_of(element));
    out.push_back(read(top.child(*table, path, where), i));
  }
  return out;
}

// The mesh files' names and hashes chained onto the scene file's hash (Scene::file_hash), then
// each [[gltf]] file's (its name and the hash over it and its buffers), so that a [[gltf]]
// placing only lights counts too.
std::string scene_hash(const std::string& text, const std::vector<TriangleMesh>& meshes,
                       const std::vector<std::pair<std::string, std::string>>& gltf_files,
                       const std::vector<TextureImage>& images) {
  uint64_t hash = fnv1a64(text);
  for (const TriangleMesh& m : meshes)
    if (!m.file.empty()) hash = fnv1a64(m.file + '\0' + m.file_hash + '\n', hash);
  for (const auto& [file, file_hash] : gltf_files) hash = fnv1a64(file + '\0' + file_hash + '\n', hash);
  // Texture files (a TOML scene's; a glTF file's images are in its own hash when embedded, and
  // chained here too when separate).
  for (const TextureImage& image : images) hash = fnv1a64(image.file + '\0' + image.hash + '\n', hash);
  return hex64(hash);
}

// Structure and types of the whole document, then the semantic rules.
// `gltf_files`: each [[gltf]] table's file and hash, for scene_hash.
Scene build_scene(const toml::table& root, const std::string& file,
                  std::vector<std::pair<std::string, std::string>>& gltf_files) {
  SourceMap sources(file);
  const TableReader top(root, "", SourcePosition{file, 1, 1}, sources);
  top.reject_unknown_keys({"image", "render", "camera", "sphere", "mesh", "gltf", "light", "environment"});
  Scene scene;
  if (const auto image = top.table("image")) read_image(*image, scene.settings);
  const auto render = top.table("render");
  if (render) read_render(*render, scene.settings);
  const auto camera = top.table("camera");
  if (!camera) fail(top.where(), "camera", "missing required table [camera]");
  read_camera(*camera, scene.camera);
  scene.spheres = read_table_array(top, "sphere",
                                   [&](const TableReader& sphere, size_t i) { return read_sphere(sphere, i, scene.images); });
  scene.meshes = read_table_array(top, "mesh", [&](const TableReader& mesh, size_t i) {
    return read_mesh(mesh, i, sources, scene.warnings, scene.images);
  });
  scene.lights = read_table_array(top, "light", read_light);
  const auto gltfs = read_table_array(top, "gltf", [&](const TableReader& gltf, size_t) {
    return read_gltf(gltf, sources, scene.warnings, gltf_files);
  });
  for (const GltfContents& contents : gltfs) {
    const size_t first_mesh = scene.meshes.size();
    scene.meshes.insert(scene.meshes.end(), contents.meshes.begin(), contents.meshes.end());
    // The glTF file's images join the scene's; its materials' indices move with them.
    for (size_t i = first_mesh; i < scene.meshes.size(); ++i) offset_texture_images(scene.meshes[i].material, int(scene.images.size()));
    scene.images.insert(scene.images.end(), contents.images.begin(), contents.images.end());
    scene.lights.insert(scene.lights.end(), contents.lights.begin(), contents.lights.end());
  }
  // Punctual lights are reached only by next-event estimation: it is the default of a scene that
  // has them (a file asking for the book estimator is refused by the plan, kernel_options.h).
  if (!scene.lights.empty() && !(render && render->get("estimator"))) scene.settings.estimator = "nee";
  if (scene.spheres.empty() && scene.meshes.empty()) {
    const toml::node* sphere = top.get("sphere");
    fail(sphere ? top.position_of(*sphere) : top.where(), "sphere", "the scene has no spheres or meshes");
  }
  if (const auto environment = top.table("environment")) scene.environment = read_environment(*environment, sources);
  scene_detail::validate_scene(scene, sources);
  check_textured_meshes(scene);
  return scene;
}

// Scene files are ASCII. toml++ 3.3.0 (Debian 12) reaches __builtin_unreachable on most
// non-ASCII code points outside strings (found by fuzzing; upstream issues 190 and 295), so such
// bytes are rejected here, with their position, before toml++ sees them.
void reject_non_ascii(const std::string& text, const std::string& name) {
  int line = 1, column = 1;
  for (unsigned char c : text) {
    if (c >= 0x80) {
      const SourcePosition where{name, line, column};
      throw Error(ExitCode::BadScene,
                  where.str() + ": syntax error: non-ASCII character (scene files are ASCII)");
    }
    if (c == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
}

toml::table parse_toml(const std::string& text, const std::string& name) {
  reject_non_ascii(text, name);
  try {
    return toml::parse(std::string_view(text), std::string_view(name));
  } catch (const toml::parse_error& e) {
    const toml::source_position& at = e.source().begin;
    const SourcePosition where{name, std::max(1, static_cast<int>(at.line)),
                               std::max(1, static_cast<int>(at.column))};
    throw Error(ExitCode::BadScene,
                where.str() + ": syntax error: " + std::string(e.description()));
  }
}

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};

[[noreturn]] void fail_cannot_open(const std::string& path, int error_number) {
  throw Error(ExitCode::BadScene,
              path + ": cannot open scene file: " + std::strerror(error_number));
}

// The whole file as bytes (the hash is of the bytes, and toml++ wants the text in memory).
std::string read_whole_file(const std::string& path) {
  errno = 0;
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) fail_cannot_open(path, errno);
  std::string text;
  char buffer[1 << 16];
  size_t count = 0;
  while ((count = std::fread(buffer, 1, sizeof buffer, file.get())) > 0) text.append(buffer, count);
  // Reading a directory opens fine and then fails here with EISDIR.
  if (std::ferror(file.get())) fail_cannot_open(path, errno);
  return text;
}

}  // namespace

Scene load_scene_file(const std::string& path, const GltfView& view) {
  const std::string bytes = read_whole_file(path);
  if (is_gltf_file(path, bytes)) return load_gltf_scene(bytes, path, view);
  if (view.camera)
    throw Error(ExitCode::Usage, "--camera " + *view.camera + ": " + path +
                                     " is a TOML scene, whose one camera is its [camera] table (--camera chooses among a "
                                     "glTF file's cameras)");
  return load_scene_string(bytes, path);
}

Scene load_scene_string(const std::string& text, const std::string& name) {
  const toml::table root = parse_toml(text, name);
  std::vector<std::pair<std::string, std::string>> gltf_files;
  Scene scene = build_scene(root, name, gltf_files);
  scene.file = name;
  scene.file_hash = scene_hash(text, scene.meshes, gltf_files, scene.images);
  chain_environment_hash(scene);
  return scene;
}

}  // namespace clpt
