#include "cl/kernel_cache.h"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <vector>

#include "cl/cl_error.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/hash.h"

namespace clpt {
namespace {

namespace fs = std::filesystem;

constexpr const char* kMagic = "CLPTBIN1";
// A different offset basis gives a second, independent 64-bit FNV-1a hash.
constexpr uint64_t kSecondSeed = 0x84222325cbf29ce4ull;

void notice(const std::string& text) {
  std::fprintf(stderr, "clpt: kernel cache: %s\n", text.c_str());
}

std::string env_or_empty(const char* name) {
  const char* value = std::getenv(name);
  return value ? value : "";
}

// Header values are single lines: a newline in a (debug-only) value would break the format.
std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  return s;
}

// Length-prefixed, so no two different field lists can produce the same hashed text.
void append_field(std::string& out, const std::string& field) {
  out += std::to_string(field.size());
  out += ':';
  out += field;
  out += '\n';
}

std::string key_of(const DeviceIdentity& id, const std::string& source, const std::string& options) {
  std::string text;
  for (const std::string* f : {&id.platform_name, &id.name, &id.driver_version, &id.device_version,
                               &id.opencl_c_version, &options, &source})
    append_field(text, *f);
  append_field(text, kMagic);  // a new entry format is a new key
  return hash128_hex(text);
}

// Reads the entry at `path` and checks it against `key`. Returns "" and the binary in *binary
// when it is valid, else the reason it is not; *missing is set when there is no such file (a plain
// miss, not corruption).
std::string read_entry(const std::string& path, const std::string& key, std::string* binary,
                       bool* missing) {
  *missing = false;
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) {
    *missing = errno == ENOENT || errno == ENOTDIR;
    return std::string("cannot open: ") + std::strerror(errno);
  }
  std::string data;
  char chunk[65536];
  size_t n = 0;
  while ((n = std::fread(chunk, 1, sizeof chunk, file)) > 0) data.append(chunk, n);
  const bool read_error = std::ferror(file) != 0;
  std::fclose(file);
  if (read_error) return "read error";

  // Header: "name value" lines up to an empty line; the first line is the magic alone.
  const size_t end = data.find("\n\n");
  if (data.compare(0, 9, std::string(kMagic) + "\n") != 0 || end == std::string::npos)
    return "bad magic or header";
  std::map<std::string, std::string> fields;
  for (size_t at = data.find('\n') + 1; at < end + 1;) {
    const size_t eol = data.find('\n', at);
    const std::string line = data.substr(at, eol - at);
    const size_t space = line.find(' ');
    if (space != std::string::npos) fields[line.substr(0, space)] = line.substr(space + 1);
    at = eol + 1;
  }
  *binary = data.substr(end + 2);
  if (fields["key"] != key) return "key mismatch";
  if (fields["binary_size"] != std::to_string(binary->size())) return "truncated";
  if (fields["binary_hash"] != hash128_hex(*binary)) return "checksum mismatch";
  return "";
}

// A program from a device binary, built (OpenCL requires clBuildProgram before kernels can be made
// from it). Returns an empty handle and the reason when the driver rejects the binary.
ProgramHandle program_from_binary(DeviceContext& ctx, const std::string& binary,
                                  const std::string& options, std::string* reason) {
  const cl_device_id device = ctx.device().id;
  const size_t size = binary.size();
  const auto* bytes = reinterpret_cast<const unsigned char*>(binary.data());
  cl_int status = CL_SUCCESS;
  try {
    ProgramHandle program(CL_CREATE(ctx.where(), clCreateProgramWithBinary, ctx.context(), 1,
                                    &device, &size, &bytes, &status));
    if (status != CL_SUCCESS)
      throw Error(ExitCode::DeviceError, "the binary's status is " + cl_error_name(status));
    CL_CALL(ctx.where(), clBuildProgram(program.get(), 1, &device, options.c_str(), nullptr, nullptr));
    return program;
  } catch (const Error& e) {
    *reason = e.what();
    return {};
  }
}

// The device binary of a program built for ctx's device alone.
std::string program_binary(DeviceContext& ctx, cl_program program) {
  cl_uint devices = 0;
  CL_CALL(ctx.where(), clGetProgramInfo(program, CL_PROGRAM_NUM_DEVICES, sizeof devices, &devices, nullptr));
  if (devices != 1)
    throw Error(ExitCode::Failure, "program has " + std::to_string(devices) + " devices, not 1");
  size_t size = 0;
  CL_CALL(ctx.where(), clGetProgramInfo(program, CL_PROGRAM_BINARY_SIZES, sizeof size, &size, nullptr));
  if (size == 0) throw Error(ExitCode::Failure, "the driver returned no binary");
  std::string binary(size, '\0');
  auto* data = reinterpret_cast<unsigned char*>(binary.data());
  CL_CALL(ctx.where(), clGetProgramInfo(program, CL_PROGRAM_BINARIES, sizeof data, &data, nullptr));
  return binary;
}

}  // namespace

DeviceIdentity DeviceIdentity::of(const DeviceInfo& d) {
  return {d.platform_name, d.name, d.driver_version, d.device_version, d.opencl_c_version};
}

std::string hash128_hex(const std::string& bytes) {
  return hex64(fnv1a64(bytes)) + hex64(fnv1a64(bytes, kSecondSeed));
}

KernelCache::KernelCache(std::string dir) : dir_(std::move(dir)) {}

std::string KernelCache::default_dir() {
  const std::string own = env_or_empty("CLPT_CACHE_DIR");
  if (!own.empty()) return own;
  const std::string xdg = env_or_empty("XDG_CACHE_HOME");
  if (!xdg.empty() && xdg.front() == '/') return xdg + "/clpt/kernels";
  const std::string home = env_or_empty("HOME");
  return home.empty() ? "" : home + "/.cache/clpt/kernels";
}

std::string KernelCache::entry_path(const DeviceIdentity& identity, const std::string& source,
                                    const std::string& options) const {
  return (fs::path(dir_) / (key_of(identity, source, options) + ".bin")).string();
}

ProgramHandle KernelCache::build(DeviceContext& ctx, const std::string& source,
                                 const std::string& options, const std::string& label, bool* hit) {
  if (hit) *hit = false;
  if (dir_.empty()) {
    ++misses_;
    return ctx.build_program_from_source(source, options, label);
  }
  const DeviceIdentity identity = override_.value_or(DeviceIdentity::of(ctx.device()));
  const std::string key = key_of(identity, source, options);
  const std::string path = (fs::path(dir_) / (key + ".bin")).string();
  ProgramHandle program = load(ctx, path, key, options);
  if (program.get()) {
    ++hits_;
    if (hit) *hit = true;
    return program;
  }
  ++misses_;
  program = ctx.build_program_from_source(source, options, label);
  store(ctx, program.get(), path, identity, key, source, options);
  return program;
}

ProgramHandle KernelCache::load(DeviceContext& ctx, const std::string& path, const std::string& key,
                                const std::string& options) {
  std::string binary;
  bool missing = false;
  std::string reason = read_entry(path, key, &binary, &missing);
  if (missing) return {};
  ProgramHandle program;
  if (reason.empty()) program = program_from_binary(ctx, binary, options, &reason);
  if (program.get()) return program;
  notice("discarding corrupt entry " + path + " (" + reason + "); rebuilding");
  std::error_code ignored;  // another run may have removed or replaced it already
  fs::remove(path, ignored);
  return {};
}

void KernelCache::store(DeviceContext& ctx, cl_program program, const std::string& path,
                        const DeviceIdentity& identity, const std::string& key,
                        const std::string& source, const std::string& options) {
  try {
    const std::string binary = program_binary(ctx, program);
    std::error_code ec;
    fs::create_directories(dir_, ec);
    if (ec) throw Error(ExitCode::OutputError, "cannot create " + dir_ + ": " + ec.message());
    // Written whole to a temporary name, then renamed: readers see no entry or a complete one.
    const std::string tmp = temporary_path_for(path);
    {
      std::ofstream out(tmp, std::ios::binary);
      out << kMagic << "\nkey " << key << "\nplatform " << one_line(identity.platform_name)
          << "\ndevice " << one_line(identity.name) << "\ndriver " << one_line(identity.driver_version)
          << "\ndevice_version " << one_line(identity.device_version) << "\nopencl_c "
          << one_line(identity.opencl_c_version) << "\noptions " << one_line(options)
          << "\nsource_hash " << hash128_hex(source) << "\nbinary_size " << binary.size()
          << "\nbinary_hash " << hash128_hex(binary) << "\n\n";
      out.write(binary.data(), std::streamsize(binary.size()));
      if (!out.flush()) {
        std::remove(tmp.c_str());
        throw Error(ExitCode::OutputError, std::string("write failed: ") + std::strerror(errno));
      }
    }
    commit_temporary(tmp, path);
  } catch (const Error& e) {
    notice("cannot store " + path + " (" + e.what() + ")");
  }
}

size_t KernelCache::clear() {
  if (dir_.empty()) return 0;
  std::error_code ec;
  std::vector<fs::path> entries;
  for (fs::directory_iterator it(dir_, ec), end; !ec && it != end; it.increment(ec))
    if (it->path().extension() == ".bin") entries.push_back(it->path());
  if (ec == std::errc::no_such_file_or_directory) return 0;
  if (ec) throw Error(ExitCode::OutputError, dir_ + ": cannot read the kernel cache: " + ec.message());
  size_t removed = 0;
  for (const fs::path& entry : entries) {
    if (fs::remove(entry, ec)) ++removed;
    // Gone already is fine (a concurrent clear); anything else is the user's to know.
    if (ec && ec != std::errc::no_such_file_or_directory)
      throw Error(ExitCode::OutputError, entry.string() + ": cannot remove: " + ec.message());
  }
  return removed;
}

}  // namespace clpt
