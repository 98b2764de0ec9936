// RAII over the OpenCL objects clpt uses: one context and in-order queue per device, programs
// built from source with their log, buffers and kernels. Every call goes through CL_CALL, so
// failures name the call, the CL error and the device.
#pragma once

#include <CL/cl.h>

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cl/cl_device.h"

namespace clpt {

// Owns one reference to a cl_* handle, released with `Release` on destruction.
template <typename Handle, cl_int (*Release)(Handle)>
class ClHandle {
 public:
  ClHandle() = default;
  explicit ClHandle(Handle h) : h_(h) {}
  ClHandle(ClHandle&& o) noexcept : h_(std::exchange(o.h_, nullptr)) {}
  ClHandle& operator=(ClHandle&& o) noexcept {
    if (this != &o) {
      reset();
      h_ = std::exchange(o.h_, nullptr);
    }
    return *this;
  }
  ClHandle(const ClHandle&) = delete;
  ClHandle& operator=(const ClHandle&) = delete;
  ~ClHandle() { reset(); }
  Handle get() const { return h_; }
  void reset() {
    if (h_) Release(h_);
    h_ = nullptr;
  }

 private:
  Handle h_ = nullptr;
};

using ContextHandle = ClHandle<cl_context, clReleaseContext>;
using QueueHandle = ClHandle<cl_command_queue, clReleaseCommandQueue>;
using ProgramHandle = ClHandle<cl_program, clReleaseProgram>;
using KernelHandle = ClHandle<cl_kernel, clReleaseKernel>;
using MemHandle = ClHandle<cl_mem, clReleaseMemObject>;
using EventHandle = ClHandle<cl_event, clReleaseEvent>;

class DeviceContext;
class KernelCache;

// A device buffer of `bytes` bytes. On PoCL's CPU device one of 2 MiB or more lives in memory clpt
// allocates on large pages (util/large_pages.h), freed when the driver releases the buffer.
class Buffer {
 public:
  Buffer() = default;
  Buffer(DeviceContext& ctx, size_t bytes, cl_mem_flags flags, const std::string& label);
  cl_mem get() const { return mem_.get(); }
  size_t bytes() const { return bytes_; }

 private:
  MemHandle mem_;
  size_t bytes_ = 0;
};

// A kernel entry point of a built program; arguments set by index.
class Kernel {
 public:
  Kernel() = default;
  // `pocl_vector_lanes`: the work-items per vectorised loop iteration PoCL's CPU device compiles
  // this kernel with (0: LLVM's cost model decides); set before each of its launches there, since
  // PoCL compiles at the first launch (cl/pocl_vectoriser.h). The program's build options must
  // carry it: renderers take their kernels from Renderer::entry_point, which passes the lanes of
  // the features the program was built with (kernel_options.cpp puts them in its options).
  // `pocl_slp`: whether LLVM's SLP vectoriser runs when PoCL compiles it (set_pocl_slp), likewise.
  Kernel(cl_program program, const std::string& name, const std::string& where, uint32_t pocl_vector_lanes = 0,
         bool pocl_slp = true);
  template <typename T>
  void set_arg(cl_uint index, const T& value) {
    set_arg_bytes(index, sizeof(T), &value);
  }
  void set_arg(cl_uint index, const Buffer& buffer) {
    cl_mem m = buffer.get();
    set_arg_bytes(index, sizeof(cl_mem), &m);
  }
  const std::string& name() const { return name_; }
  cl_kernel get() const { return kernel_.get(); }
  // What the driver says this kernel needs on `device` (clGetKernelWorkGroupInfo): private memory
  // per work-item (registers spilled or arrays placed off-chip), local memory per work-group, the
  // largest work-group it can launch with and the preferred multiple of the work-group size.
  struct Resources {
    uint64_t private_bytes = 0, local_bytes = 0;
    size_t max_work_group = 0, preferred_multiple = 0;
  };
  Resources resources(cl_device_id device) const;
  // The names of every kernel of a built program, in the driver's order.
  static std::vector<std::string> names_in(const ProgramHandle& program, const std::string& where);
  uint32_t pocl_vector_lanes() const { return pocl_vector_lanes_; }
  bool pocl_slp() const { return pocl_slp_; }

 private:
  void set_arg_bytes(cl_uint index, size_t size, const void* value);
  KernelHandle kernel_;
  std::string name_;
  std::string where_;
  uint32_t pocl_vector_lanes_ = 0;
  bool pocl_slp_ = true;
};

// One device with its context and in-order, profiling-enabled queue.
class DeviceContext {
 public:
  explicit DeviceContext(const DeviceInfo& device);
  const DeviceInfo& device() const { return device_; }
  const std::string& where() const { return where_; }
  cl_context context() const { return context_.get(); }
  cl_command_queue queue() const { return queue_.get(); }

  // Builds a program from full source text with the given options: through the kernel cache when
  // one is attached (a cached binary when it loads, else compiled and stored), else from source.
  // On failure throws Error(DeviceError) whose message holds the device's build log.
  ProgramHandle build_program(const std::string& source, const std::string& options,
                              const std::string& label);
  // Always compiles from source; the cache's own fallback.
  ProgramHandle build_program_from_source(const std::string& source, const std::string& options,
                                          const std::string& label);
  // A built program's build log on this device ("" when the driver wrote none).
  std::string build_log(const ProgramHandle& program) const;

  // The kernel binary cache build_program goes through (null: none, the default, so tests and
  // `clpt bench` always compile). use_default_kernel_cache attaches one at
  // KernelCache::default_dir() and returns it, for its hit counts.
  void set_kernel_cache(std::shared_ptr<KernelCache> cache) { cache_ = std::move(cache); }
  const std::shared_ptr<KernelCache>& kernel_cache() const { return cache_; }
  std::shared_ptr<KernelCache> use_default_kernel_cache();
  // Whether the last build_program loaded a cached binary instead of compiling.
  bool last_build_cache_hit() const { return last_build_cache_hit_; }

  // 1-D launch over global_size work-items (rounded up to a multiple of local_size when given;
  // 0 lets the driver choose). `label` names the launch in errors.
  void launch(const Kernel& kernel, size_t global_size, size_t local_size, const char* label);
  // Same, returning the launch's event for profiling (empty when global_size is 0).
  EventHandle launch_profiled(const Kernel& kernel, size_t global_size, size_t local_size,
                              const char* label);
  // Device time between a finished event's start and end, in seconds.
  double event_seconds(const EventHandle& event) const;

  void write(const Buffer& buffer, const void* data, size_t bytes);
  // Non-blocking write: `data` must stay valid until the next blocking call on this queue.
  void write_async(const Buffer& buffer, const void* data, size_t bytes);
  void read(const Buffer& buffer, void* data, size_t bytes);
  void finish();

 private:
  cl_event enqueue(const Kernel& kernel, size_t global_size, size_t local_size, const char* label,
                   bool want_event);
  DeviceInfo device_;
  std::string where_;
  ContextHandle context_;
  QueueHandle queue_;
  std::shared_ptr<KernelCache> cache_;
  bool last_build_cache_hit_ = false;
};

}  // namespace clpt
