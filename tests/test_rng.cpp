// Philox4x32-10 on the device against known answers.
#include <gtest/gtest.h>

#include "device_test_util.h"

namespace clpt::test {
namespace {

cl_uint4 u4(cl_uint a, cl_uint b, cl_uint c, cl_uint d) {
  cl_uint4 v;
  v.s[0] = a, v.s[1] = b, v.s[2] = c, v.s[3] = d;
  return v;
}

// The known answer of C++26 std::philox4x32 (and of the Random123 reference): default-seeded
// (seed 20111115 as key word 0), the engine's 10 000th output is 1955073260. The engine emits the
// four words of counter 0, then of counter 1, ...: output 10 000 is word 3 of counter 2499.
TEST(Philox, StandardKnownAnswer) {
  const auto out = run_philox({u4(2499, 0, 0, 0)}, 20111115u, 0u);
  EXPECT_EQ(out[0].s[3], 1955073260u);
}

// Random123's published known-answer vectors for philox4x32-10.
TEST(Philox, Random123KnownAnswers) {
  const auto out = run_philox({u4(0, 0, 0, 0), u4(0xffffffffu, 0xffffffffu, 0xffffffffu, 0xffffffffu),
                               u4(0x243f6a88u, 0x85a308d3u, 0x13198a2eu, 0x03707344u)},
                              0, 0);
  EXPECT_EQ(out[0].s[0], 0x6627e8d5u);
  EXPECT_EQ(out[0].s[1], 0xe169c58du);
  EXPECT_EQ(out[0].s[2], 0xbc57ac4cu);
  EXPECT_EQ(out[0].s[3], 0x9b00dbd8u);
  const auto ones = run_philox({u4(0xffffffffu, 0xffffffffu, 0xffffffffu, 0xffffffffu)}, 0xffffffffu,
                               0xffffffffu);
  EXPECT_EQ(ones[0].s[0], 0x408f276du);
  EXPECT_EQ(ones[0].s[1], 0x41c83b0eu);
  EXPECT_EQ(ones[0].s[2], 0xa20bc7c6u);
  EXPECT_EQ(ones[0].s[3], 0x6d5451fdu);
  const auto pi = run_philox({u4(0x243f6a88u, 0x85a308d3u, 0x13198a2eu, 0x03707344u)}, 0xa4093822u,
                             0x299f31d0u);
  EXPECT_EQ(pi[0].s[0], 0xd16cfe09u);
  EXPECT_EQ(pi[0].s[1], 0x94fdccebu);
  EXPECT_EQ(pi[0].s[2], 0x5001e420u);
  EXPECT_EQ(pi[0].s[3], 0x24126ea1u);
}

// The same counter gives the same bits whatever the launch shape: a counter-based generator has
// no state, so work-group size and batch composition cannot matter.
TEST(Philox, IndependentOfBatch) {
  std::vector<cl_uint4> counters;
  for (cl_uint i = 0; i < 1000; ++i) counters.push_back(u4(i * 7919u, i, 3, 0));
  const auto all = run_philox(counters, 1, 2);
  const auto one = run_philox({counters[613]}, 1, 2);
  for (int w = 0; w < 4; ++w) EXPECT_EQ(all[613].s[w], one[0].s[w]);
}

}  // namespace
}  // namespace clpt::test
