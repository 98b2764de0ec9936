// Host arrays and device buffers on large pages (util/large_pages.h, cl_context.cpp): the same
// contents as plain allocations. The buffers' memory is freed by their destructor callback, and
// the vectors' by their allocator, which the ASan build of these tests (scripts/sanitize.sh)
// would report as leaks or mismatched frees if either went wrong.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>

#include "device_test_util.h"
#include "util/large_pages.h"

namespace clpt::test {
namespace {

TEST(LargePages, VectorsHoldWhatPlainOnesDo) {
  for (size_t n : {size_t(0), size_t(1), size_t(1000), 3 * kLargePageBytes / sizeof(double) + 7}) {
    LargeVector<double> v(n);
    ASSERT_EQ(v.size(), n);
    EXPECT_TRUE(std::all_of(v.begin(), v.end(), [](double x) { return x == 0.0; })) << n << " elements";
    if (n * sizeof(double) >= kLargePageBytes) {
      EXPECT_EQ(reinterpret_cast<uintptr_t>(v.data()) % kLargePageBytes, 0u) << "not on a large page";
    }
    for (size_t i = 0; i < n; ++i) v[i] = double(i) * 0.5;
    v.resize(n + kLargePageBytes / sizeof(double));  // grows across the size classes
    for (size_t i = 0; i < n; ++i) ASSERT_EQ(v[i], double(i) * 0.5) << i;
  }
}

// A kernel reads and writes buffers of several large pages (on PoCL's CPU device clpt's own
// memory, elsewhere the driver's) as it does small ones: 3 MiB of counters in one launch give the
// bits of the same counters in launches whose buffers are 16 KiB.
TEST(Buffers, LargeBuffersHoldWhatSmallOnesDo) {
  const size_t count = (kLargePageBytes + kLargePageBytes / 2) / sizeof(cl_uint4);
  std::vector<cl_uint4> counters(count);
  for (size_t i = 0; i < count; ++i) counters[i] = cl_uint4{{cl_uint(i), cl_uint(i * 7), 3u, cl_uint(count - i)}};
  const std::vector<cl_uint4> whole = run_philox(counters, 7, 11);
  const size_t batch = 1024;
  for (size_t begin = 0; begin < count; begin += batch * 37) {  // every 37th batch: a spread sample
    const size_t end = std::min(count, begin + batch);
    const std::vector<cl_uint4> part =
        run_philox(std::vector<cl_uint4>(counters.begin() + long(begin), counters.begin() + long(end)), 7, 11);
    for (size_t i = begin; i < end; ++i)
      for (int w = 0; w < 4; ++w) ASSERT_EQ(whole[i].s[w], part[i - begin].s[w]) << "counter " << i << " word " << w;
  }
}

// Buffers that replace one another, as a render's launch buffers do when a launch grows.
TEST(Buffers, ReplacedLargeBuffersKeepTheirContents) {
  Buffer b;
  for (size_t pages = 1; pages <= 3; ++pages) {
    std::vector<cl_uint> data(pages * kLargePageBytes / sizeof(cl_uint));
    for (size_t i = 0; i < data.size(); ++i) data[i] = cl_uint(i * 2654435761u + pages);
    b = Buffer(test_device(), data.size() * sizeof(cl_uint), CL_MEM_READ_WRITE, "replaced");
    test_device().write(b, data.data(), data.size() * sizeof(cl_uint));
    EXPECT_EQ(download<cl_uint>(b, data.size()), data) << pages << " pages";
  }
}

}  // namespace
}  // namespace clpt::test
