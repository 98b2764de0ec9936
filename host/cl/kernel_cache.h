// clpt's kernel binary cache: programs built once are stored as device binaries and loaded on the
// next run instead of compiling from source again.
//
// Never stale by construction: an entry's file name is a hash of everything the binary depends on
// (platform, device, driver version, device and OpenCL C versions, the exact build options and the
// fully assembled source, which already holds every included file), so any change is a miss, not
// a wrong hit. Entries are written atomically (temporary file, then rename), so concurrent runs
// never read a half-written one; an entry that fails to load for any reason is deleted with a
// one-line notice on stderr and the program is rebuilt from source. Failing to write an entry is
// a notice, never an error: the cache can only make a build faster.
//
// Entry file, DIR/KEY.bin: a text header, then the binary bytes.
//   CLPTBIN1 / key KEY / platform .. / device .. / driver .. / device_version .. / opencl_c .. /
//   options .. / source_hash .. / binary_size N / binary_hash H / an empty line / N bytes
// The clear-text fields are for people debugging the cache; only the key, size and hash are read.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "cl/cl_context.h"

namespace clpt {

// What identifies the compiler that produced a binary (fields of DeviceInfo).
struct DeviceIdentity {
  std::string platform_name;
  std::string name;
  std::string driver_version;
  std::string device_version;
  std::string opencl_c_version;

  static DeviceIdentity of(const DeviceInfo& device);
};

class KernelCache {
 public:
  // `dir` is created on the first store. An empty `dir` disables the cache (every build compiles).
  explicit KernelCache(std::string dir);

  // CLPT_CACHE_DIR if set, else $XDG_CACHE_HOME/clpt/kernels (when absolute, as the XDG spec
  // asks), else $HOME/.cache/clpt/kernels; "" when none of these can be found.
  static std::string default_dir();

  const std::string& dir() const { return dir_; }

  // The program for `source` built with `options` on ctx's device: loaded from the cache when an
  // entry exists and loads, else compiled from source (ctx.build_program_from_source) and stored.
  // *hit (when given) says which. Throws only what compiling from source throws.
  ProgramHandle build(DeviceContext& ctx, const std::string& source, const std::string& options,
                      const std::string& label, bool* hit = nullptr);

  // The entry file for this build: DIR/KEY.bin.
  std::string entry_path(const DeviceIdentity& identity, const std::string& source,
                         const std::string& options) const;

  // Removes every *.bin in the directory (entries and leftover temporary files) and returns how
  // many; 0 when the directory does not exist. Throws Error(OutputError) when it cannot be read.
  size_t clear();

  // Test hook: key entries by this identity instead of the device's own, to simulate a driver
  // update without one. The binary still comes from (and is loaded on) the real device.
  void set_identity_override(std::optional<DeviceIdentity> identity) { override_ = std::move(identity); }

  // Builds served from the cache and compiled from source since construction.
  uint64_t hits() const { return hits_; }
  uint64_t misses() const { return misses_; }

 private:
  ProgramHandle load(DeviceContext& ctx, const std::string& path, const std::string& key,
                     const std::string& options);
  void store(DeviceContext& ctx, cl_program program, const std::string& path,
             const DeviceIdentity& identity, const std::string& key, const std::string& source,
             const std::string& options);

  std::string dir_;
  std::optional<DeviceIdentity> override_;
  uint64_t hits_ = 0;
  uint64_t misses_ = 0;
};

// 32 hex digits: two 64-bit FNV-1a hashes of `bytes` with different seeds.
std::string hash128_hex(const std::string& bytes);

}  // namespace clpt
