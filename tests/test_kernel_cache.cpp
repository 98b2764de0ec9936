// The kernel binary cache (cl/kernel_cache.h): a miss compiles and stores, a hit loads a binary
// that computes what a from-source build computes, a changed device identity never reuses an old
// entry, and a damaged entry is discarded with a notice and rebuilt. Each test has its own empty
// CLPT_CACHE_DIR.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <vector>

#include "cl/kernel_cache.h"
#include "device_test_util.h"
#include "kernels/kernel_source.h"

namespace clpt::test {
namespace {

namespace fs = std::filesystem;

const char* const kOptions = "-cl-std=CL1.2";

// probe_philox over fixed counters and key: 4 words per counter, flattened.
std::vector<cl_uint> run_philox(DeviceContext& ctx, cl_program program) {
  std::vector<cl_uint4> counters(64);
  for (size_t i = 0; i < counters.size(); ++i)
    for (cl_uint w = 0; w < 4; ++w) counters[i].s[w] = cl_uint(i) * 2654435761u + w;
  const size_t bytes = counters.size() * sizeof(cl_uint4);
  Buffer in(ctx, bytes, CL_MEM_READ_ONLY, "counters");
  Buffer out(ctx, bytes, CL_MEM_WRITE_ONLY, "out");
  ctx.write(in, counters.data(), bytes);
  Kernel kernel(program, "probe_philox", ctx.where());
  kernel.set_arg(0, in);
  kernel.set_arg(1, cl_uint(0x9e3779b9u));
  kernel.set_arg(2, cl_uint(0x7f4a7c15u));
  kernel.set_arg(3, out);
  ctx.launch(kernel, counters.size(), 0, "probe_philox");
  std::vector<cl_uint> words(counters.size() * 4);
  ctx.read(out, words.data(), bytes);
  return words;
}

class KernelCacheTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string dir = (fs::temp_directory_path() / "clpt-cache-test-XXXXXX").string();
    ASSERT_NE(::mkdtemp(dir.data()), nullptr);
    root_ = dir;
    ::setenv("CLPT_CACHE_DIR", (root_ / "kernels").c_str(), 1);
    cache_ = std::make_shared<KernelCache>(KernelCache::default_dir());
    ctx_ = std::make_unique<DeviceContext>(test_device().device());
    ctx_->set_kernel_cache(cache_);
  }
  void TearDown() override {
    ::unsetenv("CLPT_CACHE_DIR");
    std::error_code ignored;
    fs::remove_all(root_, ignored);
  }

  static const std::string& source() {
    static const std::string text = assemble_kernel_source("probe_stages.cl");
    return text;
  }
  ProgramHandle build() { return ctx_->build_program(source(), kOptions, "probe_stages.cl"); }
  std::string entry() const {
    return cache_->entry_path(DeviceIdentity::of(ctx_->device()), source(), kOptions);
  }
  size_t entry_count() const {
    size_t n = 0;
    for (const auto& e : fs::directory_iterator(cache_->dir())) n += e.path().extension() == ".bin";
    return n;
  }
  // The output of a from-source build on the shared test device: what every cached build must give.
  static const std::vector<cl_uint>& expected() {
    static const std::vector<cl_uint> words = run_philox(test_device(), test_program("probe_stages.cl", kOptions));
    return words;
  }
  // Builds with stderr captured; returns it.
  std::string build_capturing_stderr(ProgramHandle* program) {
    ::testing::internal::CaptureStderr();
    *program = build();
    return ::testing::internal::GetCapturedStderr();
  }
  void expect_discarded_and_rebuilt(const std::string& reason) {
    ProgramHandle program;
    const std::string err = build_capturing_stderr(&program);
    EXPECT_NE(err.find("clpt: kernel cache: discarding corrupt entry " + entry() + " (" + reason),
              std::string::npos) << err;
    EXPECT_NE(err.find("; rebuilding"), std::string::npos) << err;
    EXPECT_FALSE(ctx_->last_build_cache_hit());
    EXPECT_EQ(run_philox(*ctx_, program.get()), expected());
    // The bad entry was replaced by a good one.
    build();
    EXPECT_TRUE(ctx_->last_build_cache_hit());
  }

  fs::path root_;
  std::shared_ptr<KernelCache> cache_;
  std::unique_ptr<DeviceContext> ctx_;
};

TEST_F(KernelCacheTest, DefaultDirFollowsEnvironment) {
  EXPECT_EQ(KernelCache::default_dir(), (root_ / "kernels").string());
  ::unsetenv("CLPT_CACHE_DIR");
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  const std::string saved_xdg = xdg ? xdg : "";
  ::setenv("XDG_CACHE_HOME", "/xdg", 1);
  EXPECT_EQ(KernelCache::default_dir(), "/xdg/clpt/kernels");
  ::setenv("XDG_CACHE_HOME", "relative", 1);  // the XDG spec says to ignore relative paths
  const char* home = std::getenv("HOME");
  if (home) {
    EXPECT_EQ(KernelCache::default_dir(), std::string(home) + "/.cache/clpt/kernels");
  }
  if (xdg) ::setenv("XDG_CACHE_HOME", saved_xdg.c_str(), 1);
  else ::unsetenv("XDG_CACHE_HOME");
}

TEST_F(KernelCacheTest, MissThenHitRunsLikeSourceBuild) {
  ProgramHandle first = build();
  EXPECT_FALSE(ctx_->last_build_cache_hit());
  ASSERT_TRUE(fs::exists(entry()));
  EXPECT_EQ(entry_count(), 1u);
  ProgramHandle second = build();
  EXPECT_TRUE(ctx_->last_build_cache_hit());
  EXPECT_EQ(cache_->hits(), 1u);
  EXPECT_EQ(cache_->misses(), 1u);
  EXPECT_EQ(run_philox(*ctx_, second.get()), expected());
  EXPECT_EQ(run_philox(*ctx_, first.get()), expected());
  // A fresh context (a later run) hits too.
  DeviceContext later(test_device().device());
  later.set_kernel_cache(std::make_shared<KernelCache>(cache_->dir()));
  ProgramHandle third = later.build_program(source(), kOptions, "probe_stages.cl");
  EXPECT_TRUE(later.last_build_cache_hit());
  EXPECT_EQ(run_philox(later, third.get()), expected());
}

TEST_F(KernelCacheTest, OptionsAndSourceAreInTheKey) {
  build();
  ctx_->build_program(source(), std::string(kOptions) + " -DCLPT_CACHE_TEST=1", "probe_stages.cl");
  EXPECT_FALSE(ctx_->last_build_cache_hit());
  ctx_->build_program(source() + "\n/* edited */\n", kOptions, "probe_stages.cl");
  EXPECT_FALSE(ctx_->last_build_cache_hit());
  EXPECT_EQ(entry_count(), 3u);
}

TEST_F(KernelCacheTest, ChangedDriverVersionIsAMiss) {
  build();
  const std::string old_entry = entry();
  DeviceIdentity updated = DeviceIdentity::of(ctx_->device());
  updated.driver_version += " (updated)";
  cache_->set_identity_override(updated);
  ProgramHandle program = build();
  EXPECT_FALSE(ctx_->last_build_cache_hit());  // the old entry was not used
  const std::string new_entry = cache_->entry_path(updated, source(), kOptions);
  EXPECT_NE(new_entry, old_entry);
  EXPECT_TRUE(fs::exists(new_entry));
  EXPECT_TRUE(fs::exists(old_entry));  // left for the old driver; `clpt cache clear` reclaims it
  EXPECT_EQ(run_philox(*ctx_, program.get()), expected());
  build();
  EXPECT_TRUE(ctx_->last_build_cache_hit());
}

TEST_F(KernelCacheTest, FlippedByteIsDiscardedAndRebuilt) {
  build();
  {
    std::fstream f(entry(), std::ios::in | std::ios::out | std::ios::binary);
    f.seekg(-16, std::ios::end);
    const char c = char(f.get() ^ 0x5a);
    f.seekp(-16, std::ios::end);
    f.put(c);
  }
  expect_discarded_and_rebuilt("checksum mismatch");
}

TEST_F(KernelCacheTest, TruncatedEntryIsDiscardedAndRebuilt) {
  build();
  fs::resize_file(entry(), fs::file_size(entry()) / 2);
  expect_discarded_and_rebuilt("truncated");
}

TEST_F(KernelCacheTest, BadMagicIsDiscardedAndRebuilt) {
  build();
  std::ofstream(entry(), std::ios::binary) << "not a clpt kernel cache entry";
  expect_discarded_and_rebuilt("bad magic or header");
}

// An entry whose checks pass but whose binary the driver rejects (clCreateProgramWithBinary or
// clBuildProgram fails): discarded like any other damage.
TEST_F(KernelCacheTest, BinaryRejectedByDriverIsDiscardedAndRebuilt) {
  build();
  const std::string binary = "this is not a device binary";
  std::ofstream(entry(), std::ios::binary)
      << "CLPTBIN1\nkey " << fs::path(entry()).stem().string() << "\nbinary_size " << binary.size()
      << "\nbinary_hash " << hash128_hex(binary) << "\n\n"
      << binary;
  // The reason names the OpenCL call and error, e.g. "clCreateProgramWithBinary failed with
  // CL_INVALID_BINARY on ..." (PoCL); which call rejects it is the driver's choice.
  expect_discarded_and_rebuilt("cl");
}

TEST_F(KernelCacheTest, UnwritableCacheIsOnlyANotice) {
  std::ofstream(cache_->dir()) << "a file where the cache directory should be";
  ProgramHandle program;
  const std::string err = build_capturing_stderr(&program);
  EXPECT_NE(err.find("clpt: kernel cache: cannot store"), std::string::npos) << err;
  EXPECT_EQ(run_philox(*ctx_, program.get()), expected());
}

TEST_F(KernelCacheTest, ClearRemovesEveryEntry) {
  EXPECT_EQ(cache_->clear(), 0u);  // no directory yet
  build();
  ctx_->build_program(source(), std::string(kOptions) + " -DCLPT_CACHE_TEST=2", "probe_stages.cl");
  std::ofstream(fs::path(cache_->dir()) / "unrelated.txt") << "kept";
  EXPECT_EQ(cache_->clear(), 2u);
  EXPECT_EQ(entry_count(), 0u);
  EXPECT_TRUE(fs::exists(fs::path(cache_->dir()) / "unrelated.txt"));
  build();
  EXPECT_FALSE(ctx_->last_build_cache_hit());
}

TEST_F(KernelCacheTest, NoCacheAttachedCompilesFromSource) {
  DeviceContext plain(test_device().device());
  ProgramHandle program = plain.build_program(source(), kOptions, "probe_stages.cl");
  EXPECT_FALSE(plain.last_build_cache_hit());
  EXPECT_FALSE(fs::exists(cache_->dir()));
  EXPECT_EQ(run_philox(plain, program.get()), expected());
}

}  // namespace
}  // namespace clpt::test
