// Shared host/device structs (kernels/types.h) have the same size and field offsets on both sides.
#include <gtest/gtest.h>

#include <cstddef>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "device_test_util.h"
#include "kernels/path_state.h"
#include "kernels/types.h"

namespace clpt::test {
namespace {

TEST(StructLayout, HostMatchesDevice) {
  std::vector<cl_uint> host;
  std::vector<std::string> names;
#define HOST_SIZE(T)              \
  host.push_back(sizeof(T));      \
  names.push_back("sizeof(" #T ")");
#define HOST_FIELD(T, f)            \
  host.push_back(offsetof(T, f));   \
  names.push_back("offsetof(" #T ", " #f ")");
  CLPT_LAYOUT_STRUCTS(HOST_SIZE)
  CLPT_LAYOUT_FIELDS(HOST_FIELD)
#undef HOST_SIZE
#undef HOST_FIELD
  Kernel kernel(test_program("probe_layout.cl"), "probe_layout", test_device().where());
  Buffer out(test_device(), host.size() * sizeof(cl_uint), CL_MEM_WRITE_ONLY, "layout");
  kernel.set_arg(0, out);
  test_device().launch(kernel, 1, 1, "probe_layout");
  const auto device = download<cl_uint>(out, host.size());
  for (size_t i = 0; i < host.size(); ++i) EXPECT_EQ(host[i], device[i]) << names[i];
  // The sizes the comments in types.h promise.
  EXPECT_EQ(sizeof(GpuSphere), 128u);
  EXPECT_EQ(sizeof(GpuCamera), 48u);
  EXPECT_EQ(sizeof(GpuRenderParams), 120u);
  EXPECT_EQ(sizeof(GpuSampleSlot), 8u);
  EXPECT_EQ(sizeof(GpuLight), 80u);
  EXPECT_EQ(sizeof(GpuMaterial), 64u);
  EXPECT_EQ(sizeof(GpuTriangleShading), 112u);
  EXPECT_EQ(sizeof(GpuPixelPass), 32u);
}

// The one field list of kernels/path_state.h, expanded by the host (buffer sizes, as the wavefront
// renderer allocates them) and by a kernel through the wavefront's own parameter list and its
// path_load / path_store: the same buffers, the same element sizes, and every stored field carried
// from one slot to another, for float and for the double preset's `real`.
// With the first-hit layers (CLPT_AOVS, kernels/aov.cl) the list has their fields too, on both
// sides; without them neither side has them.
TEST(StructLayout, PathStateBuffersMatchTheHost) {
  for (const bool aovs : {false, true})
  for (const bool double_preset : {false, true}) {
    if (double_preset && !test_device().device().fp64) continue;  // PoCL, the CI device, has it
    const size_t real_bytes = double_preset ? 8 : 4;
    std::vector<size_t> host_bytes;
    std::vector<std::string> names;
#define CLPT_REAL_BYTES real_bytes
#define CLPT_HOST_AOVS aovs
#define HOST_BUFFER(type, name, bytes, doc) \
  host_bytes.push_back(bytes);               \
  names.push_back(#name);
    CLPT_PATH_STATE_FIELDS(HOST_BUFFER)
#undef HOST_BUFFER
#undef CLPT_HOST_AOVS
#undef CLPT_REAL_BYTES
    const bool has_aov_field = std::find(names.begin(), names.end(), "aov_depth") != names.end();
    EXPECT_EQ(has_aov_field, aovs);
    const std::string options = std::string("-cl-std=CL1.2 -DCLPT_ESTIMATOR=1 -DCLPT_PRECISION=") +
                                (double_preset ? "2" : "1") + (aovs ? " -DCLPT_AOVS=1" : "");
    Kernel kernel(test_program("probe_path_state.cl", options), "probe_path_state", test_device().where());
    Buffer sizes(test_device(), host_bytes.size() * sizeof(cl_uint), CL_MEM_WRITE_ONLY, "element sizes");
    GpuRenderParams params{};
    params.pixel_count = 1;
    kernel.set_arg(0, sizes);
    kernel.set_arg(1, params);
    const Buffer sample_slots = upload(std::vector<unsigned char>(sizeof(GpuSampleSlot), 0));  // unread: not slotted
    kernel.set_arg(2, sample_slots);
    // Two slots per buffer: slot 0 holds a distinct non-zero pattern, slot 1 zeros.
    std::vector<Buffer> buffers;
    std::vector<std::vector<unsigned char>> slot0;
    for (size_t b = 0; b < host_bytes.size(); ++b) {
      std::vector<unsigned char> bytes(2 * host_bytes[b], 0);
      for (size_t k = 0; k < host_bytes[b]; ++k) bytes[k] = static_cast<unsigned char>(17 * b + 3 * k + 1);
      // Keep float patterns away from NaN (a canonicalising copy could change them).
      bytes[host_bytes[b] - 1] = 0x3f;
      slot0.emplace_back(bytes.begin(), bytes.begin() + long(host_bytes[b]));
      buffers.push_back(upload(bytes));
      kernel.set_arg(cl_uint(3 + b), buffers.back());
    }
    test_device().launch(kernel, 1, 1, "probe_path_state");
    const auto device_bytes = download<cl_uint>(sizes, host_bytes.size());
    for (size_t b = 0; b < host_bytes.size(); ++b) {
      EXPECT_EQ(device_bytes[b], host_bytes[b]) << names[b] << (double_preset ? " (double)" : " (float)")
                                                 << (aovs ? " (aovs)" : "");
      const auto both = download<unsigned char>(buffers[b], 2 * host_bytes[b]);
      EXPECT_EQ(std::vector<unsigned char>(both.begin() + long(host_bytes[b]), both.end()), slot0[b])
          << names[b] << ": slot 0 did not survive path_load and path_store"
          << (double_preset ? " (double)" : " (float)");
    }
  }
}

}  // namespace
}  // namespace clpt::test
