#include "cl/cl_context.h"

#include <cstdlib>

#include "cl/cl_error.h"
#include "cl/kernel_cache.h"
#include "cl/pocl_vectoriser.h"
#include "util/error.h"
#include "util/large_pages.h"

namespace clpt {
namespace {

// PoCL's CPU device keeps buffers in the process's own memory, as plain allocations.
bool host_memory_is_device_memory(const DeviceInfo& device) { return device.is_pocl_cpu(); }

void CL_CALLBACK free_host_memory(cl_mem, void* memory) { std::free(memory); }

// A buffer whose memory clpt allocates on 2 MiB pages (util/large_pages.h) and hands to the
// device with CL_MEM_USE_HOST_PTR, on a device whose buffers are host memory anyway. Why: every
// first touch of a 4 KiB page is a fault (about 10 us in the VMs clpt is measured on), and a
// render's launch buffers are touched afresh each time they grow; with these buffers on large
// pages the W1 render took 0.957 of the wall time (docs/performance.md, "Fixed costs"). The
// memory is freed by the buffer's destructor callback, when the driver has let go of it, not
// when clpt releases it.
cl_mem create_on_large_pages(DeviceContext& ctx, size_t bytes, cl_mem_flags flags) {
  void* memory = allocate_on_large_pages(bytes);
  if (!memory) throw Error(ExitCode::DeviceError, ctx.where() + ": out of host memory for a buffer of " +
                                                      std::to_string(bytes) + " bytes");
  cl_mem mem = nullptr;
  try {
    mem = CL_CREATE(ctx.where(), clCreateBuffer, ctx.context(), flags | CL_MEM_USE_HOST_PTR, bytes, memory);
  } catch (...) {
    std::free(memory);
    throw;
  }
  try {
    CL_CALL(ctx.where(), clSetMemObjectDestructorCallback(mem, free_host_memory, memory));
  } catch (...) {
    clReleaseMemObject(mem);  // never used: the driver holds the memory no more
    std::free(memory);
    throw;
  }
  return mem;
}

}  // namespace

Buffer::Buffer(DeviceContext& ctx, size_t bytes, cl_mem_flags flags, const std::string& label)
    : bytes_(bytes) {
  if (bytes > ctx.device().max_alloc_bytes) {
    throw Error(ExitCode::DeviceError,
                "buffer '" + label + "' needs " + std::to_string(bytes) + " bytes but " +
                    ctx.where() + " allows at most " + std::to_string(ctx.device().max_alloc_bytes) +
                    " per allocation");
  }
  mem_ = MemHandle(host_memory_is_device_memory(ctx.device()) && bytes >= kLargePageBytes
                       ? create_on_large_pages(ctx, bytes, flags)
                       : CL_CREATE(ctx.where(), clCreateBuffer, ctx.context(), flags, bytes, nullptr));
}

Kernel::Kernel(cl_program program, const std::string& name, const std::string& where, uint32_t pocl_vector_lanes,
               bool pocl_slp)
    : kernel_(CL_CREATE(where, clCreateKernel, program, name.c_str())),
      name_(name),
      where_(where),
      pocl_vector_lanes_(pocl_vector_lanes),
      pocl_slp_(pocl_slp) {}

Kernel::Resources Kernel::resources(cl_device_id device) const {
  Resources r;
  cl_ulong bytes = 0;
  const std::string where = where_ + " (kernel " + name_ + ")";
  CL_CALL(where, clGetKernelWorkGroupInfo(kernel_.get(), device, CL_KERNEL_PRIVATE_MEM_SIZE, sizeof bytes, &bytes, nullptr));
  r.private_bytes = bytes;
  CL_CALL(where, clGetKernelWorkGroupInfo(kernel_.get(), device, CL_KERNEL_LOCAL_MEM_SIZE, sizeof bytes, &bytes, nullptr));
  r.local_bytes = bytes;
  CL_CALL(where, clGetKernelWorkGroupInfo(kernel_.get(), device, CL_KERNEL_WORK_GROUP_SIZE, sizeof r.max_work_group,
                                          &r.max_work_group, nullptr));
  CL_CALL(where, clGetKernelWorkGroupInfo(kernel_.get(), device, CL_KERNEL_PREFERRED_WORK_GROUP_SIZE_MULTIPLE,
                                          sizeof r.preferred_multiple, &r.preferred_multiple, nullptr));
  return r;
}

std::vector<std::string> Kernel::names_in(const ProgramHandle& program, const std::string& where) {
  cl_uint count = 0;
  CL_CALL(where, clCreateKernelsInProgram(program.get(), 0, nullptr, &count));
  std::vector<cl_kernel> kernels(count);
  CL_CALL(where, clCreateKernelsInProgram(program.get(), count, kernels.data(), nullptr));
  std::vector<std::string> names;
  for (cl_kernel k : kernels) {
    const KernelHandle owned(k);
    size_t size = 0;
    CL_CALL(where, clGetKernelInfo(k, CL_KERNEL_FUNCTION_NAME, 0, nullptr, &size));
    std::string name(size, '\0');
    CL_CALL(where, clGetKernelInfo(k, CL_KERNEL_FUNCTION_NAME, size, name.data(), nullptr));
    while (!name.empty() && name.back() == '\0') name.pop_back();
    names.push_back(name);
  }
  return names;
}

void Kernel::set_arg_bytes(cl_uint index, size_t size, const void* value) {
  CL_CALL(where_ + " (kernel " + name_ + ", argument " + std::to_string(index) + ")",
          clSetKernelArg(kernel_.get(), index, size, value));
}

DeviceContext::DeviceContext(const DeviceInfo& device) : device_(device), where_(device.label()) {
  const cl_context_properties props[] = {
      CL_CONTEXT_PLATFORM, reinterpret_cast<cl_context_properties>(device.platform), 0};
  context_ = ContextHandle(
      CL_CREATE(where_, clCreateContext, props, 1, &device_.id, nullptr, nullptr));
  // clCreateCommandQueue is deprecated in OpenCL 2.0 but is the one call every 1.2+ driver has.
  queue_ = QueueHandle(CL_CREATE(where_, clCreateCommandQueue, context_.get(), device_.id,
                                 CL_QUEUE_PROFILING_ENABLE));
}

ProgramHandle DeviceContext::build_program(const std::string& source, const std::string& options,
                                           const std::string& label) {
  last_build_cache_hit_ = false;
  if (cache_) return cache_->build(*this, source, options, label, &last_build_cache_hit_);
  return build_program_from_source(source, options, label);
}

std::shared_ptr<KernelCache> DeviceContext::use_default_kernel_cache() {
  cache_ = std::make_shared<KernelCache>(KernelCache::default_dir());
  return cache_;
}

ProgramHandle DeviceContext::build_program_from_source(const std::string& source,
                                                       const std::string& options,
                                                       const std::string& label) {
  const char* text = source.c_str();
  const size_t length = source.size();
  ProgramHandle program(
      CL_CREATE(where_, clCreateProgramWithSource, context_.get(), 1, &text, &length));
  const cl_int err = clBuildProgram(program.get(), 1, &device_.id, options.c_str(), nullptr, nullptr);
  if (err != CL_SUCCESS)
    throw Error(ExitCode::DeviceError, "clBuildProgram failed with " + cl_error_name(err) + " on " +
                                           where_ + " for program '" + label + "' (options: " +
                                           options + "); build log:\n" + build_log(program));
  return program;
}

std::string DeviceContext::build_log(const ProgramHandle& program) const {
  // Unchecked on purpose: it also serves a failed build's error message, which must not be lost
  // to a second failure; a log that cannot be read is an empty one.
  size_t size = 0;
  if (clGetProgramBuildInfo(program.get(), device_.id, CL_PROGRAM_BUILD_LOG, 0, nullptr, &size) != CL_SUCCESS)
    return "";
  std::string log(size, '\0');
  if (clGetProgramBuildInfo(program.get(), device_.id, CL_PROGRAM_BUILD_LOG, size, log.data(), nullptr) != CL_SUCCESS)
    return "";
  while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
  return log;
}

cl_event DeviceContext::enqueue(const Kernel& kernel, size_t global_size, size_t local_size,
                                const char* label, bool want_event) {
  if (global_size == 0) return nullptr;
  if (local_size) global_size = (global_size + local_size - 1) / local_size * local_size;
  // PoCL compiles the kernel's work-group function at its first launch, with the width set now.
  if (device_.is_pocl_cpu()) {
    set_pocl_vectoriser_lanes(kernel.pocl_vector_lanes());
    set_pocl_slp(kernel.pocl_slp());
  }
  cl_event event = nullptr;
  CL_CALL(where_ + " (" + label + ")",
          clEnqueueNDRangeKernel(queue_.get(), kernel.get(), 1, nullptr, &global_size,
                                 local_size ? &local_size : nullptr, 0, nullptr,
                                 want_event ? &event : nullptr));
  return event;
}

void DeviceContext::launch(const Kernel& kernel, size_t global_size, size_t local_size,
                           const char* label) {
  enqueue(kernel, global_size, local_size, label, false);
}

EventHandle DeviceContext::launch_profiled(const Kernel& kernel, size_t global_size,
                                           size_t local_size, const char* label) {
  return EventHandle(enqueue(kernel, global_size, local_size, label, true));
}

double DeviceContext::event_seconds(const EventHandle& event) const {
  if (!event.get()) return 0;
  cl_ulong start = 0, end = 0;
  CL_CALL(where_, clGetEventProfilingInfo(event.get(), CL_PROFILING_COMMAND_START, sizeof start,
                                          &start, nullptr));
  CL_CALL(where_, clGetEventProfilingInfo(event.get(), CL_PROFILING_COMMAND_END, sizeof end, &end,
                                          nullptr));
  return double(end - start) * 1e-9;
}

void DeviceContext::write(const Buffer& buffer, const void* data, size_t bytes) {
  CL_CALL(where_, clEnqueueWriteBuffer(queue_.get(), buffer.get(), CL_TRUE, 0, bytes, data, 0,
                                       nullptr, nullptr));
}

void DeviceContext::write_async(const Buffer& buffer, const void* data, size_t bytes) {
  CL_CALL(where_, clEnqueueWriteBuffer(queue_.get(), buffer.get(), CL_FALSE, 0, bytes, data, 0,
                                       nullptr, nullptr));
}

void DeviceContext::read(const Buffer& buffer, void* data, size_t bytes) {
  CL_CALL(where_, clEnqueueReadBuffer(queue_.get(), buffer.get(), CL_TRUE, 0, bytes, data, 0,
                                      nullptr, nullptr));
}

void DeviceContext::finish() { CL_CALL(where_, clFinish(queue_.get())); }

}  // namespace clpt
