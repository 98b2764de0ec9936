#include "tools/verify.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <nlohmann/json.hpp>

#include "cl/cl_device.h"
#ifdef CLPT_WITH_OIIO
#include "io/render_file.h"
#endif
#include "render/fault_injection.h"
#include "render/film_raw.h"
#include "render/render_session.h"
#include "scene/scene_loader.h"
#include "util/appendf.h"
#include "util/atomic_file.h"
#include "util/error.h"

#ifndef CLPT_SOURCE_TREE
#define CLPT_SOURCE_TREE ""
#endif

namespace clpt {
namespace {

namespace fs = std::filesystem;

constexpr const char* kChannels = "RGB";

// The directory holding this executable, or "" where /proc/self/exe cannot be read.
fs::path executable_dir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : exe.parent_path();
}

// `in_tree` under the source tree when that exists, else `beside` next to the executable when
// that exists, else the source tree's path (so that a missing-file error names where clpt looked).
std::string data_dir(const char* in_tree, const char* beside) {
  const fs::path tree = fs::path(CLPT_SOURCE_TREE) / in_tree;
  if (*CLPT_SOURCE_TREE && fs::is_directory(tree)) return tree.string();
  const fs::path exe_dir = executable_dir();
  if (!exe_dir.empty() && fs::is_directory(exe_dir / beside)) return (exe_dir / beside).string();
  return tree.string();
}

std::string reference_file(const std::string& dir, const std::string& scene) {
  return (fs::path(dir) / ("gemspt_" + scene + "_" + std::to_string(kBuiltinWidth) + "x" +
                           std::to_string(kBuiltinHeight) + ".exr"))
      .string();
}

// A gemspt reference: a render file (io/render_file.h) of the references' size.
MeanVarianceImage load_reference(const std::string& path) {
#ifndef CLPT_WITH_OIIO
  throw Error(ExitCode::Usage, path + ": this clpt was built without OpenImageIO (CLPT_WITH_OIIO=OFF), which "
                                      "reads gemspt's EXR references; use --reference device or films");
#else
  RenderFile file = read_render_file(path);
  if (file.image.width != kBuiltinWidth || file.image.height != kBuiltinHeight)
    throw Error(ExitCode::Usage, path + ": a gemspt reference must be " + std::to_string(kBuiltinWidth) + "x" +
                                     std::to_string(kBuiltinHeight) + ", this one is " +
                                     std::to_string(file.image.width) + "x" + std::to_string(file.image.height));
  return std::move(file.image);
#endif
}

constexpr const char* kFilmsManifest = "films.json";

// What films mode reads from DIR/films.json: the films' size, spp, seed and reference device.
struct FilmsManifest {
  int width = 0, height = 0;
  int64_t spp = 0;
  uint64_t seed = 0;
  std::string reference, reference_driver;
};

FilmsManifest read_films_manifest(const std::string& dir) {
  const std::string path = (fs::path(dir) / kFilmsManifest).string();
  if (!fs::is_regular_file(path))
    throw Error(ExitCode::Usage, "--reference films: " + path + ": no such file (write one with --reference device "
                                 "--save-reference-films DIR)");
  if (fs::file_size(path) > (1u << 20)) throw Error(ExitCode::Usage, path + ": larger than a films manifest can be");
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw Error(ExitCode::Usage, path + ": cannot read");
  std::string text(fs::file_size(path), '\0');
  const size_t got = std::fread(text.data(), 1, text.size(), f);
  std::fclose(f);
  text.resize(got);
  FilmsManifest m;
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    m.width = j.at("width").get<int>();
    m.height = j.at("height").get<int>();
    m.spp = j.at("spp").get<int64_t>();
    m.seed = j.at("seed").get<uint64_t>();
    m.reference = j.at("reference").get<std::string>();
    m.reference_driver = j.at("reference_driver").get<std::string>();
  } catch (const nlohmann::json::exception& e) {
    throw Error(ExitCode::Usage, path + ": not a clpt verify films manifest: " + e.what());
  }
  if (m.width < 1 || m.width > 16384 || m.height < 1 || m.height > 16384 || m.spp < 16 || m.spp % 16 != 0)
    throw Error(ExitCode::Usage, path + ": its width, height or spp is out of range");
  return m;
}

std::string films_manifest_json(const VerifyReport& report) {
  nlohmann::json j = {{"width", report.width},        {"height", report.height},
                      {"spp", report.spp},            {"seed", report.seed},
                      {"reference", report.reference}, {"reference_driver", report.reference_driver},
                      {"sampler", "grid"},            {"estimator", "book"}};
  return j.dump(2) + "\n";
}

// Variance of the image mean per channel: sum of the pixels' variances of the mean / pixels^2.
std::array<double, 3> image_mean_variance(const MeanVarianceImage& img) {
  std::array<double, 3> v = {0, 0, 0};
  const size_t pixels = size_t(img.width) * img.height;
  for (size_t p = 0; p < pixels; ++p)
    for (int c = 0; c < 3; ++c) v[size_t(c)] += img.variance[p * 3 + c];
  for (double& x : v) x /= double(pixels) * double(pixels);
  return v;
}

// See VerifyRow::shift_z_2pct: the weakest channel's z for a 2% shift of the device's image mean.
double shift_z_2pct(const MeanVarianceImage& device, const MeanVarianceImage& reference, const CompareResult& r) {
  const std::array<double, 3> vd = image_mean_variance(device), vr = image_mean_variance(reference);
  double weakest = INFINITY;
  for (int c = 0; c < 3; ++c) {
    const double sigma = std::sqrt(vr[size_t(c)] + 1.02 * 1.02 * vd[size_t(c)]);
    weakest = std::min(weakest, 0.02 * std::abs(r.image_mean.mean_b[c]) / sigma);
  }
  return weakest;
}

struct Resolved {
  ReferenceMode mode = ReferenceMode::Device;
  std::vector<DeviceInfo> devices;  // under test, in --device order
  DeviceInfo reference;             // device mode
  std::string reference_dir;        // builtin and films modes
  std::set<std::string> missing_films;  // films mode: reference_film_name()s not in the directory
  std::vector<Scene> scenes;        // with size, spp, seed applied, in config.scenes order
  FaultPlan faults;                 // CLPT_INJECT_FAULT, positions of the --device list
};

const DeviceInfo* find_pocl_cpu(const std::vector<DeviceInfo>& all) {
  for (const DeviceInfo& d : all)
    if (d.is_pocl_cpu()) return &d;
  return nullptr;
}

Resolved resolve(const VerifyConfig& config, VerifyReport& report) {
  Resolved r;
  r.faults = FaultPlan::from_environment();  // a malformed value fails before any work
  if (config.scenes.empty()) throw Error(ExitCode::Usage, "--scenes: no scene given");
  for (const std::string& name : config.scenes) {
    const auto& known = verify_scene_names();
    if (std::find(known.begin(), known.end(), name) == known.end())
      throw Error(ExitCode::Usage, "--scenes: unknown scene '" + name + "' (verify knows diffuse, specular, glass)");
  }
  if (config.forms.empty()) throw Error(ExitCode::Usage, "--forms: no execution form given");
  if (config.precisions.empty()) throw Error(ExitCode::Usage, "--precisions: no precision given");
  if (config.spp && (*config.spp < 16 || *config.spp % 16 != 0))
    throw Error(ExitCode::Usage, "--spp " + std::to_string(*config.spp) +
                                     ": verify renders with the book's grid sampler, which needs a "
                                     "positive multiple of 16 samples per pixel");

  const std::vector<DeviceInfo> all = list_devices();
  r.devices = select_devices(all, config.device);
  const DeviceInfo* pocl = find_pocl_cpu(all);
  r.mode = config.reference;
  if (r.mode == ReferenceMode::Auto) r.mode = pocl ? ReferenceMode::Device : ReferenceMode::Builtin;
  if (!config.save_films_dir.empty() && r.mode != ReferenceMode::Device)
    throw Error(ExitCode::Usage, "--save-reference-films: only a PoCL reference device's renders are saved "
                                 "(--reference device)");
  if (!config.save_films_dir.empty()) check_output_directory("--save-reference-films", config.save_films_dir);
  if (r.mode == ReferenceMode::Device && !pocl)
    throw Error(ExitCode::DeviceError, "--reference device: no PoCL CPU device (platform '" +
                                           std::string(kPoclPlatformName) +
                                           "') to render the reference; use --reference builtin "
                                           "(gemspt's images)");

  const bool builtin = r.mode == ReferenceMode::Builtin;
  report.mode = r.mode;
  report.width = config.width.value_or(builtin ? kBuiltinWidth : kVerifyWidth);
  report.height = config.height.value_or(builtin ? kBuiltinHeight : kVerifyHeight);
  report.spp = config.spp.value_or(builtin ? kBuiltinSpp : kVerifySpp);
  report.seed = config.seed.value_or(1);
  if (r.mode == ReferenceMode::Films) {
    if (config.reference_dir.empty())
      throw Error(ExitCode::Usage, "--reference films: --reference-dir names the films' directory");
    const FilmsManifest m = read_films_manifest(config.reference_dir);
    const auto clash = [&](const char* option, bool given_and_differs, const std::string& films_value) {
      if (given_and_differs)
        throw Error(ExitCode::Usage, std::string(option) + ": the films in " + config.reference_dir + " were rendered with " +
                                         films_value + "; leave it out to use theirs");
    };
    clash("--width/--height", (config.width && *config.width != m.width) || (config.height && *config.height != m.height),
          std::to_string(m.width) + "x" + std::to_string(m.height));
    clash("--spp", config.spp && *config.spp != m.spp, std::to_string(m.spp) + " spp");
    clash("--seed", config.seed && *config.seed != m.seed, "seed " + std::to_string(m.seed));
    report.width = m.width;
    report.height = m.height;
    report.spp = m.spp;
    report.seed = m.seed;
    r.reference_dir = config.reference_dir;
    report.reference = m.reference + " (films in " + config.reference_dir + ")";
    report.reference_driver = m.reference_driver;
    // A bundle may hold a subset of the matrix (scripts/offline-bundle.sh --verify-args): rows
    // without a film are skipped, each with a note, and a run with no row left fails.
    for (const std::string& scene : config.scenes)
      for (ExecutionForm form : config.forms)
        for (Precision precision : config.precisions) {
          const std::string film = reference_film_name(scene, execution_form_name(form), precision_name(precision));
          if (fs::is_regular_file(fs::path(r.reference_dir) / film)) continue;
          r.missing_films.insert(film);
          report.notes.push_back("skipped: " + scene + ", " + execution_form_name(form) + ", " +
                                 precision_name(precision) + ": no reference film " + film);
        }
  }
  if (builtin && (report.width != kBuiltinWidth || report.height != kBuiltinHeight))
    throw Error(ExitCode::Usage, "--width/--height " + std::to_string(report.width) + "x" +
                                     std::to_string(report.height) + ": the builtin references are " +
                                     std::to_string(kBuiltinWidth) + "x" + std::to_string(kBuiltinHeight) +
                                     ", so verify renders at that size without a PoCL reference device");
  if (r.mode == ReferenceMode::Films) {
    // resolved above
  } else if (builtin) {
    r.reference_dir = config.reference_dir.empty() ? default_reference_dir() : config.reference_dir;
    for (const std::string& name : config.scenes) {
      const std::string path = reference_file(r.reference_dir, name);
      if (!fs::is_regular_file(path))
        throw Error(ExitCode::Usage, "reference " + path + ": no such file (the gemspt references live in "
                                     "tests/reference; --reference-dir DIR names another directory)");
    }
    report.reference = "gemspt references in " + r.reference_dir;
  } else {
    r.reference = *pocl;
    report.reference = pocl->label();
    report.reference_driver = pocl->driver_version;
  }

  const std::string scene_dir = config.scene_dir.empty() ? default_scene_dir() : config.scene_dir;
  for (const std::string& name : config.scenes) {
    const std::string path = (fs::path(scene_dir) / (name + ".toml")).string();
    if (!fs::is_regular_file(path)) throw Error(ExitCode::Usage, "scene " + path + ": no such file");
    Scene scene = load_scene_file(path);
    RenderSettings& s = scene.settings;
    s.width = report.width;
    s.height = report.height;
    s.spp = report.spp;
    s.seed = report.seed;
    // The book's sampler and estimator, as gemspt rendered the references (and the scene files say).
    s.sampler = Sampler::Grid;
    s.estimator = "book";
    s.rr_from = -1;
    r.scenes.push_back(std::move(scene));
  }
  for (size_t i = 0; i < r.devices.size(); ++i)
    report.devices.push_back(std::to_string(r.devices[i].index) + " " + r.devices[i].label());
  return r;
}

struct Rendered {
  MeanVarianceImage image;
  double paths_per_s = 0;
};

Rendered render(const Scene& scene, ExecutionForm form, Precision precision, const DeviceInfo& device,
                const FaultPlan& faults) {
  RenderRequest request;
  request.scene = scene;
  request.device = std::to_string(device.index);
  request.form = form;
  request.precision = precision;
  request.faults = faults;
  RenderReport report;
  const Film film = run_render(request, report);
  return {film.mean_variance(), double(report.paths) / std::max(1e-9, report.pass_seconds)};
}

// A rate for the table: "6.54 M", "12.3 k" or "196" (a simulator runs a few hundred paths/s).
std::string si_rate(double per_s) {
  std::string out;
  if (per_s >= 1e6)
    appendf(out, "%.2f M", per_s * 1e-6);
  else if (per_s >= 1e3)
    appendf(out, "%.1f k", per_s * 1e-3);
  else
    appendf(out, "%.0f", per_s);
  return out;
}

// The first line of an error message (a build failure carries the whole build log after it).
std::string first_line(const std::string& message) { return message.substr(0, message.find('\n')); }

}  // namespace

const std::vector<std::string>& verify_scene_names() {
  static const std::vector<std::string> names = {"diffuse", "specular", "glass"};
  return names;
}

size_t VerifyReport::passed() const {
  return size_t(std::count_if(rows.begin(), rows.end(), [](const VerifyRow& r) { return r.pass; }));
}

std::string default_scene_dir() { return data_dir("scenes", "scenes"); }
std::string default_reference_dir() { return data_dir("tests/reference", "reference"); }

void fill_row_statistics(const CompareResult& r, bool report_same_seed, VerifyRow& row) {
  struct Candidate {
    double z;
    std::string test;
    int channel;
    double critical;
    bool rejects;
  };
  // The image mean first: on a tie (a block as large as the image is the image) it is named.
  std::vector<Candidate> candidates;
  for (int c = 0; c < 3; ++c) {
    const double z = r.image_mean.z[c];
    candidates.push_back({z, "image mean", c, r.image_mean.z_critical, std::isnan(z) || std::abs(z) >= r.image_mean.z_critical});
  }
  for (const BlockScaleResult& s : r.scales) {
    const std::string name = std::to_string(s.block_size) + "x" + std::to_string(s.block_size) + " blocks";
    candidates.push_back({s.worst.z, name, s.worst.channel, s.z_critical, !s.pass});
  }
  // |z| with NaN as the worst of all.
  const auto size = [](double z) { return std::isnan(z) ? INFINITY : std::abs(z); };
  const Candidate* worst = nullptr;
  for (const Candidate& c : candidates)
    if (!worst || size(c.z) > size(worst->z)) worst = &c;
  row.worst_z = worst ? worst->z : 0;
  row.worst_test = worst ? worst->test : "";
  row.worst_channel = worst ? worst->channel : 0;
  row.worst_z_critical = worst ? worst->critical : 0;
  row.accept_fraction = r.accept_fraction;
  if (report_same_seed) row.same_seed_fraction = r.equal_fraction;
  row.pass = r.statistical_pass;
  row.failure.clear();
  if (row.pass) return;
  // Name the rejecting test furthest beyond its own critical |z| (the scales differ in theirs).
  const Candidate* named = nullptr;
  for (const Candidate& c : candidates)
    if (c.rejects && (!named || size(c.z) / c.critical > size(named->z) / named->critical)) named = &c;
  if (named)
    appendf(row.failure, "%s channel %c: z = %+.2f (rejects at |z| >= %.2f)", named->test.c_str(),
            kChannels[named->channel], named->z, named->critical);
  if (!r.pixels_pass)
    appendf(row.failure, "%spixels: %.3f%% accept (need >= %.2f%%)", named ? "; " : "",
            100 * r.accept_fraction, 100 * r.options.min_accept);
  // Only the pixel test failed: still name a channel, the worst block's or image mean's.
  if (!named && worst)
    appendf(row.failure, "; worst: %s channel %c, z = %+.2f (passes below |z| %.2f)", worst->test.c_str(),
            kChannels[worst->channel], worst->z, worst->critical);
}

VerifyReport run_verify(const VerifyConfig& config, const std::function<void(const VerifyReport&)>& on_start,
                        const std::function<void(const VerifyRow&)>& on_row) {
  VerifyReport report;
  const Resolved r = resolve(config, report);
  const bool builtin = r.mode == ReferenceMode::Builtin;
  const bool films = r.mode == ReferenceMode::Films;
  const bool device_reference = r.mode == ReferenceMode::Device;
  const FaultPlan no_faults;
  // Rows that cannot run: double precision on a device (or a reference) without fp64.
  for (const DeviceInfo& d : r.devices)
    if (!d.fp64 && std::count(config.precisions.begin(), config.precisions.end(), Precision::Double))
      report.notes.push_back("skipped: double precision on " + std::to_string(d.index) + " " + d.label() +
                             " (no cl_khr_fp64)");
  const bool reference_fp64 = !device_reference || r.reference.fp64;
  if (!reference_fp64 && std::count(config.precisions.begin(), config.precisions.end(), Precision::Double))
    report.notes.push_back("skipped: double precision everywhere: the reference " + r.reference.label() +
                           " has no cl_khr_fp64");
  if (on_start) on_start(report);

  for (size_t s = 0; s < r.scenes.size(); ++s) {
    const Scene& scene = r.scenes[s];
    const std::string& scene_name = config.scenes[s];
    std::optional<MeanVarianceImage> gemspt;
    if (builtin) gemspt = load_reference(reference_file(r.reference_dir, scene_name));
    for (ExecutionForm form : config.forms)
      for (Precision precision : config.precisions) {
        if (precision == Precision::Double && !reference_fp64) continue;
        const std::string film_name =
            reference_film_name(scene_name, execution_form_name(form), precision_name(precision));
        if (r.missing_films.count(film_name)) continue;
        // The reference render of this scene x form x precision, shared by every device.
        std::optional<MeanVarianceImage> reference = gemspt;
        std::string reference_error;
        try {
          if (films) {
            reference = read_film_pfm((fs::path(r.reference_dir) / film_name).string());
            if (reference->width != report.width || reference->height != report.height)
              throw Error(ExitCode::Usage, film_name + " is not " + std::to_string(report.width) + "x" +
                                               std::to_string(report.height) + " as films.json says");
          } else if (device_reference) {
            reference = render(scene, form, precision, r.reference, no_faults).image;
            if (!config.save_films_dir.empty())
              write_film_pfm((fs::path(config.save_films_dir) / film_name).string(), *reference);
          }
        } catch (const Error& e) {
          reference_error = "the reference " + std::string(films ? "film" : "render") + " failed: " + first_line(e.what());
        }
        for (size_t i = 0; i < r.devices.size(); ++i) {
          const DeviceInfo& d = r.devices[i];
          if (precision == Precision::Double && !d.fp64) continue;
          VerifyRow row;
          row.device_index = d.index;
          row.position = i;
          row.device = d.label();
          row.driver = d.driver_version;
          row.is_reference_device = device_reference && d.id == r.reference.id;
          row.scene = scene_name;
          row.form = execution_form_name(form);
          row.precision = precision_name(precision);
          if (!reference_error.empty()) {
            row.error = reference_error;
          } else {
            try {
              const Rendered got = render(scene, form, precision, d, r.faults.for_device(i));
              row.paths_per_s = got.paths_per_s;
              const CompareResult result = compare_renders(got.image, *reference, report.compare);
              fill_row_statistics(result, !builtin, row);  // films: the same seed too
              row.shift_z_2pct = shift_z_2pct(got.image, *reference, result);
            } catch (const Error& e) {
              row.error = first_line(e.what());
            }
          }
          if (!row.error.empty()) {
            row.pass = false;
            row.failure = row.error;
          }
          report.rows.push_back(row);
          if (on_row) on_row(report.rows.back());
        }
      }
  }
  if (!config.save_films_dir.empty())
    write_file_atomically((fs::path(config.save_films_dir) / kFilmsManifest).string(), films_manifest_json(report),
                          "--save-reference-films");
  return report;
}

const char* reference_mode_name(ReferenceMode mode) {
  switch (mode) {
    case ReferenceMode::Device: return "device";
    case ReferenceMode::Builtin: return "builtin";
    case ReferenceMode::Films: return "films";
    default: return "auto";
  }
}

std::string reference_film_name(const std::string& scene, const std::string& form, const std::string& precision) {
  return "verify_" + scene + "_" + form + "_" + precision + ".pfm";
}

std::string verify_header(const VerifyReport& rep) {
  std::string out;
  const bool builtin = rep.mode == ReferenceMode::Builtin;
  appendf(out, "clpt verify: %dx%d, %lld spp, seed %llu, grid sampler, book estimator\n", rep.width, rep.height,
          (long long)rep.spp, (unsigned long long)rep.seed);
  if (builtin)
    appendf(out, "reference: %s (gemspt, 8192 spp; no same-seed fraction)\n", rep.reference.c_str());
  else
    appendf(out, "reference: %s, driver %s, same scene, form, precision, size, spp and seed\n",
            rep.reference.c_str(), rep.reference_driver.c_str());
  const CompareOptions& o = rep.compare;
  appendf(out, "verdict: compare_renders: pixels at alpha %g (>= %.2f%% accept), blocks", o.pixel_alpha,
          100 * o.min_accept);
  for (int b : o.block_sizes) appendf(out, " %d", b);
  appendf(out, " and the image mean at family-wise alpha %g\n", o.alpha);
  for (const std::string& note : rep.notes) out += note + "\n";
  appendf(out, "%-4s %-9s %-10s %-9s %-7s %-26s %8s %9s %9s  %s\n", "dev", "scene", "form", "precision",
          "verdict", "worst |z| (test, channel)", "accept", "same-seed", "paths/s", "device, driver");
  return out;
}

std::string verify_row_line(const VerifyRow& row) {
  std::string out, worst = "-", accept = "-", same = "-", rate = "-";
  if (row.error.empty()) {
    same = "n/a";  // builtin mode: an independent reference has no same-seed fraction
    worst.clear();
    appendf(worst, "%.2f (%s, %c)", std::abs(row.worst_z), row.worst_test.c_str(), kChannels[row.worst_channel]);
    accept.clear();
    appendf(accept, "%.2f%%", 100 * row.accept_fraction);
    if (row.same_seed_fraction) {
      same.clear();
      appendf(same, "%.2f%%", 100 * *row.same_seed_fraction);
    }
    rate = si_rate(row.paths_per_s);
  }
  appendf(out, "%-4d %-9s %-10s %-9s %-7s %-26s %8s %9s %9s  %s, driver %s%s\n", row.device_index,
          row.scene.c_str(), row.form.c_str(), row.precision.c_str(), row.pass ? "PASS" : "FAIL", worst.c_str(),
          accept.c_str(), same.c_str(), rate.c_str(), row.device.c_str(), row.driver.c_str(),
          row.is_reference_device ? " (the reference device)" : "");
  return out;
}

std::string verify_footer(const VerifyReport& rep) {
  std::string out;
  for (const VerifyRow& row : rep.rows)
    if (!row.pass)
      appendf(out, "FAIL: %s, %s, %s on device %d (%s): %s\n", row.scene.c_str(), row.form.c_str(),
              row.precision.c_str(), row.device_index, row.device.c_str(), row.failure.c_str());
  appendf(out, "verify: %zu of %zu rows passed\n", rep.passed(), rep.rows.size());
  return out;
}

std::string verify_json(const VerifyReport& rep) {
  using nlohmann::json;
  // nlohmann writes NaN and infinities as null; be explicit so the contract does not hang on it.
  const auto number = [](double x) { return std::isfinite(x) ? json(x) : json(nullptr); };
  json j;
  j["reference_mode"] = reference_mode_name(rep.mode);
  j["reference"] = rep.reference;
  j["reference_driver"] = rep.reference_driver;
  j["width"] = rep.width;
  j["height"] = rep.height;
  j["spp"] = rep.spp;
  j["seed"] = rep.seed;
  j["sampler"] = "grid";
  j["estimator"] = "book";
  j["alphas"] = {{"pixel_alpha", rep.compare.pixel_alpha},
                 {"min_accept", rep.compare.min_accept},
                 {"alpha", rep.compare.alpha},
                 {"block_sizes", rep.compare.block_sizes},
                 {"same_seed_tolerance", rep.compare.tolerance}};
  j["notes"] = rep.notes;
  j["rows"] = json::array();
  for (const VerifyRow& row : rep.rows) {
    json r = {{"device_index", row.device_index},
              {"position", row.position},
              {"device", row.device},
              {"driver", row.driver},
              {"is_reference_device", row.is_reference_device},
              {"scene", row.scene},
              {"form", row.form},
              {"precision", row.precision},
              {"verdict", row.pass ? "PASS" : "FAIL"},
              {"error", row.error.empty() ? json(nullptr) : json(row.error)},
              {"failure", row.failure.empty() ? json(nullptr) : json(row.failure)}};
    if (row.error.empty()) {
      r["worst"] = {{"z", number(row.worst_z)},
                    {"test", row.worst_test},
                    {"channel", std::string(1, kChannels[row.worst_channel])},
                    {"z_critical", number(row.worst_z_critical)}};
      r["pixel_accept_fraction"] = number(row.accept_fraction);
      r["same_seed_fraction"] = row.same_seed_fraction ? number(*row.same_seed_fraction) : json(nullptr);
      r["paths_per_s"] = number(row.paths_per_s);
      r["shift_z_2pct"] = number(row.shift_z_2pct);
    }
    j["rows"].push_back(r);
  }
  j["passed"] = rep.passed();
  j["total"] = rep.rows.size();
  return j.dump(2) + "\n";
}

}  // namespace clpt
