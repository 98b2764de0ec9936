// Helpers for tests that run the renderer's own kernel code on an OpenCL device: by default the
// first CPU device (PoCL in CI); CLPT_TEST_DEVICE selects another like `--device` does.
#pragma once

#include <string>
#include <vector>

#include "cl/cl_context.h"

namespace clpt::test {

DeviceContext& test_device();

// Program built from an embedded kernel file (e.g. "probe_stages.cl"), built once per run.
cl_program test_program(const std::string& file, const std::string& options = "-cl-std=CL1.2");

// Uploads a vector to a new read-write buffer.
template <typename T>
Buffer upload(const std::vector<T>& data) {
  Buffer b(test_device(), std::max<size_t>(1, data.size()) * sizeof(T), CL_MEM_READ_WRITE, "test input");
  if (!data.empty()) test_device().write(b, data.data(), data.size() * sizeof(T));
  return b;
}

template <typename T>
std::vector<T> download(const Buffer& b, size_t count) {
  std::vector<T> out(count);
  test_device().read(b, out.data(), count * sizeof(T));
  return out;
}

// Runs `kernel_name` of probe_stages.cl, built with `options`, over `count` work-items with `args`
// as its first arguments and a new buffer of `count` Out values as its last; returns that buffer.
template <typename Out, typename... Args>
std::vector<Out> run_probe_built(const std::string& options, const char* kernel_name, size_t count,
                                 const Args&... args) {
  Kernel kernel(test_program("probe_stages.cl", options), kernel_name, test_device().where());
  Buffer out(test_device(), count * sizeof(Out), CL_MEM_WRITE_ONLY, kernel_name);
  cl_uint index = 0;
  (kernel.set_arg(index++, args), ...);
  kernel.set_arg(index, out);
  test_device().launch(kernel, count, 0, kernel_name);
  return download<Out>(out, count);
}

// run_probe_built with the default options.
template <typename Out, typename... Args>
std::vector<Out> run_probe(const char* kernel_name, size_t count, const Args&... args) {
  return run_probe_built<Out>("-cl-std=CL1.2", kernel_name, count, args...);
}

// Philox4x32-10 of each counter with key (k0, k1) on the test device (probe_philox).
inline std::vector<cl_uint4> run_philox(const std::vector<cl_uint4>& counters, cl_uint k0, cl_uint k1) {
  return run_probe<cl_uint4>("probe_philox", counters.size(), upload(counters), k0, k1);
}

// Directory of the source tree (for scenes and references).
std::string source_dir();

}  // namespace clpt::test
