#include "render/checkpoint.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "util/atomic_file.h"
#include "render/limits.h"
#include "util/error.h"

namespace clpt {
namespace {

constexpr char kMagic[8] = {'C', 'L', 'P', 'T', 'C', 'K', 'P', 'T'};
constexpr size_t kHashChars = 16;

// The identity of a render, as stored: what must match for a resume.
struct Header {
  uint32_t version = kCheckpointVersion;
  uint32_t width = 0, height = 0;
  uint64_t spp = 0, seed = 0;
  char scene_hash[kHashChars] = {};
  uint32_t sampler = 0, max_bounces = 0;
  uint64_t total_samples = 0, total_segments = 0, dropped = 0;
};

Header header_for(const Scene& scene, const Film::Totals& totals) {
  Header h;
  h.width = static_cast<uint32_t>(scene.settings.width);
  h.height = static_cast<uint32_t>(scene.settings.height);
  h.spp = totals.samples_per_pixel;
  h.seed = scene.settings.seed;
  std::memcpy(h.scene_hash, scene.file_hash.data(), std::min(kHashChars, scene.file_hash.size()));
  h.sampler = static_cast<uint32_t>(scene.settings.sampler);
  h.max_bounces = static_cast<uint32_t>(scene.settings.max_bounces);
  h.total_samples = totals.total_samples;
  h.total_segments = totals.total_segments;
  h.dropped = totals.dropped_samples;
  return h;
}

template <typename T>
void put(std::ostream& out, const T& value) {
  out.write(reinterpret_cast<const char*>(&value), sizeof value);
}
template <typename T>
void get(std::istream& in, T& value) {
  in.read(reinterpret_cast<char*>(&value), sizeof value);
}

void put_header(std::ostream& out, const Header& h) {
  out.write(kMagic, sizeof kMagic);
  put(out, h.version), put(out, h.width), put(out, h.height), put(out, h.spp), put(out, h.seed);
  out.write(h.scene_hash, kHashChars);
  put(out, h.sampler), put(out, h.max_bounces);
  put(out, h.total_samples), put(out, h.total_segments), put(out, h.dropped);
}

// False when the file is too short or is not a checkpoint (magic).
bool get_header(std::istream& in, Header& h) {
  char magic[sizeof kMagic] = {};
  in.read(magic, sizeof magic);
  if (!in || std::memcmp(magic, kMagic, sizeof kMagic) != 0) return false;
  get(in, h.version), get(in, h.width), get(in, h.height), get(in, h.spp), get(in, h.seed);
  in.read(h.scene_hash, kHashChars);
  get(in, h.sampler), get(in, h.max_bounces);
  get(in, h.total_samples), get(in, h.total_segments), get(in, h.dropped);
  return bool(in);
}

void put_doubles(std::ostream& out, const LargeVector<double>& values) {
  out.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(double)));
}

std::vector<double> get_doubles(std::istream& in, size_t count) {
  std::vector<double> values(count);
  in.read(reinterpret_cast<char*>(values.data()), std::streamsize(count * sizeof(double)));
  return values;
}

[[noreturn]] void fail(const std::string& path, const std::string& message) {
  throw Error(ExitCode::Usage, "--resume " + path + ": " + message);
}

template <typename T>
void expect_field(const std::string& path, const char* field, const T& stored, const T& wanted) {
  if (stored == wanted) return;
  fail(path, "the checkpoint's " + std::string(field) + " " + std::to_string(stored) +
                 " does not match this render's " + field + " " + std::to_string(wanted));
}

// Compares every identifying field of the stored header with the render's, in a fixed order.
void check_matches(const std::string& path, const Header& stored, const Header& wanted) {
  if (stored.version < kOldestCheckpointVersion || stored.version > kCheckpointVersion)
    fail(path, "checkpoint version " + std::to_string(stored.version) + " is not supported (this clpt reads " +
                   std::to_string(kOldestCheckpointVersion) + " to " + std::to_string(kCheckpointVersion) + ")");
  const std::string stored_hash(stored.scene_hash, kHashChars), wanted_hash(wanted.scene_hash, kHashChars);
  if (stored_hash != wanted_hash)
    fail(path, "the checkpoint's scene (hash " + std::string(stored_hash.c_str()) +
                   ") does not match this scene file (hash " + std::string(wanted_hash.c_str()) + ")");
  expect_field(path, "width", stored.width, wanted.width);
  expect_field(path, "height", stored.height, wanted.height);
  expect_field(path, "seed", stored.seed, wanted.seed);
  if (stored.sampler != wanted.sampler)
    fail(path, "the checkpoint's sampler " + std::string(sampler_name(Sampler(stored.sampler))) +
                   " does not match this render's sampler " + sampler_name(Sampler(wanted.sampler)));
  expect_field(path, "max_bounces", stored.max_bounces, wanted.max_bounces);
}

}  // namespace

void save_checkpoint(const std::string& path, const Scene& scene, const Film& film, bool adaptive) {
  const std::string tmp = temporary_path_for(path);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw Error(ExitCode::OutputError, path + ": cannot write checkpoint: " + std::strerror(errno));
    put_header(out, header_for(scene, film.totals()));
    put_doubles(out, film.sums());
    put_doubles(out, film.sums_of_squares());
    put_doubles(out, film.valid_counts());
    put(out, film.half_samples_per_pixel(1));
    put_doubles(out, film.half1_sums());
    put_doubles(out, film.half1_valid_counts());
    put(out, uint8_t(adaptive));
    put_doubles(out, film.half1_sums_of_squares());
    out.write(reinterpret_cast<const char*>(film.half1_samples().data()),
              std::streamsize(film.half1_samples().size() * sizeof(uint32_t)));
    if (!out.flush()) {
      std::remove(tmp.c_str());
      throw Error(ExitCode::OutputError, path + ": cannot write checkpoint: write failed");
    }
  }
  commit_temporary(tmp, path);
}

Film load_checkpoint(const std::string& path, const Scene& scene, bool adaptive) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, std::string("cannot open checkpoint: ") + std::strerror(errno));
  Header stored;
  if (!get_header(in, stored)) fail(path, "not a clpt checkpoint (bad magic or truncated header)");
  check_matches(path, stored, header_for(scene, Film::Totals{}));
  // Width and height now equal the (limit-checked) settings, so the allocations below are bounded.
  const size_t pixels = size_t(stored.width) * stored.height;
  std::vector<double> sum = get_doubles(in, pixels * 3);
  std::vector<double> sum_sq = get_doubles(in, pixels * 3);
  std::vector<double> valid = get_doubles(in, pixels);
  uint64_t half1_spp = 0;
  std::vector<double> half1_sum, half1_valid, half1_sum_sq;
  std::vector<uint32_t> half1_samples;
  uint8_t stored_adaptive = 0;
  if (stored.version >= 2) {
    get(in, half1_spp);
    half1_sum = get_doubles(in, pixels * 3);
    half1_valid = get_doubles(in, pixels);
  }
  if (stored.version >= 3) {
    get(in, stored_adaptive);
    half1_sum_sq = get_doubles(in, pixels * 3);
    half1_samples.resize(pixels);
    in.read(reinterpret_cast<char*>(half1_samples.data()), std::streamsize(pixels * sizeof(uint32_t)));
  }
  if (!in || in.peek() != std::char_traits<char>::eof())
    fail(path, "the checkpoint is truncated or has trailing bytes");
  if (bool(stored_adaptive) != adaptive)
    fail(path, std::string("the checkpoint's render ") + (stored_adaptive ? "samples" : "does not sample") +
                   " adaptively and this one " + (adaptive ? "does" : "does not") + " (--adaptive)");
  if (stored.spp > kMaxSpp) fail(path, "the checkpoint's spp " + std::to_string(stored.spp) + " is out of range");
  const Film::Totals totals{stored.spp, stored.total_samples, stored.total_segments, stored.dropped};
  Film film = Film::restore(int(stored.width), int(stored.height), std::move(sum), std::move(sum_sq),
                            std::move(valid), totals);
  if (stored.version < 2) return film;
  if (half1_spp > stored.spp)
    fail(path, "the checkpoint's half-film spp " + std::to_string(half1_spp) + " exceeds its spp " +
                   std::to_string(stored.spp));
  try {
    film.restore_halves(std::move(half1_sum), std::move(half1_valid), half1_spp, std::move(half1_sum_sq),
                        std::move(half1_samples));
  } catch (const std::invalid_argument&) {
    fail(path, "the checkpoint's half-film does not add up to its samples per pixel");
  }
  return film;
}

}  // namespace clpt
