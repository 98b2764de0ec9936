// Shared host/device structs (kernels/types.h) have the same size and field offsets on both sides.
#include <gtest/gtest.h>

#include <cstddef>

#include "device_test_util.h"
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
  EXPECT_EQ(sizeof(GpuSphere), 64u);
  EXPECT_EQ(sizeof(GpuCamera), 48u);
  EXPECT_EQ(sizeof(GpuRenderParams), 112u);
  EXPECT_EQ(sizeof(GpuLight), 32u);
  EXPECT_EQ(sizeof(GpuPixelPass), 32u);
}

}  // namespace
}  // namespace clpt::test
