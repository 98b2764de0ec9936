#include "oclgrind_test_util.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cl/cl_device.h"
#include "render_test_util.h"
#include "util/error.h"

namespace clpt::test {
namespace {

size_t count_of(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

}  // namespace

bool oclgrind_present(std::string& why) {
  std::vector<DeviceInfo> devices;
  try {
    devices = list_devices();
  } catch (const Error& e) {
    why = std::string(e.what()) + "; ";
  }
  for (const DeviceInfo& d : devices)
    if (d.is_simulator) return true;  // cl_device.cpp knows Oclgrind as the simulator by name
  const char* vendors = std::getenv("OCL_ICD_VENDORS");
  why += "no Oclgrind device: install the Debian package `oclgrind` (scripts/test.sh installs it) and "
         "re-run cmake, which writes oclgrind.icd into the vendors directory ctest gives these tests "
         "as OCL_ICD_VENDORS (here: " +
         std::string(vendors ? vendors : "unset; run the test through ctest") + ")";
  return false;
}

std::string OclgrindFindings::summary() const {
  std::ostringstream s;
  s << invalid_access << " invalid accesses, " << data_race << " data races, " << divergence
    << " divergences, " << api_error << " API errors; stderr began:\n"
    << text.substr(0, 3000);
  return s.str();
}

StderrCapture::StderrCapture(const std::string& tag) {
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = test ? std::string(test->test_suite_name()) + "." + test->name() : "outside-a-test";
  name += "." + tag + ".stderr";
  for (char& c : name)
    if (c == '/') c = '_';
  const std::filesystem::path dir = std::filesystem::path(CLPT_OCLGRIND_CAPTURE_DIR);
  std::filesystem::create_directories(dir);
  path_ = (dir / name).string();
  // Oclgrind's logger would write its findings to OCLGRIND_LOG instead, where each later context
  // truncates them (seen: three probes in one process left an empty log): read at each context's
  // creation, so unsetting it here keeps everything on stderr.
  unsetenv("OCLGRIND_LOG");
  std::fflush(stderr);
  std::cerr.flush();
  const int fd = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) throw std::runtime_error("cannot create " + path_);
  saved_fd_ = ::dup(2);
  ::dup2(fd, 2);
  ::close(fd);
}

StderrCapture::~StderrCapture() {
  if (saved_fd_ < 0) return;
  std::fflush(stderr);
  ::dup2(saved_fd_, 2);
  ::close(saved_fd_);
}

OclgrindFindings StderrCapture::finish() {
  std::fflush(stderr);
  std::cerr.flush();
  ::dup2(saved_fd_, 2);
  ::close(saved_fd_);
  saved_fd_ = -1;
  OclgrindFindings f;
  std::ifstream in(path_, std::ios::binary);
  f.text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  f.invalid_access = int(count_of(f.text, "Invalid read of size") + count_of(f.text, "Invalid write of size"));
  f.data_race = int(count_of(f.text, "data race at"));
  f.divergence = int(count_of(f.text, "Work-group divergence") + count_of(f.text, "Work-item divergence"));
  f.api_error = int(count_of(f.text, "OpenCL runtime error detected"));
  return f;
}

double SameSeedAgreement::worst_mean_difference() const {
  return *std::max_element(mean_relative_difference, mean_relative_difference + 3);
}

std::string SameSeedAgreement::describe() const {
  char line[160];
  std::snprintf(line, sizeof line, "%.2f%% of values within 1e-4 relative, image means within %.2g relative",
                100 * close_fraction, worst_mean_difference());
  return line;
}

SameSeedAgreement same_seed_agreement(const std::vector<float>& a, const std::vector<float>& b) {
  SameSeedAgreement r;
  if (a.size() != b.size() || a.empty()) {
    ADD_FAILURE() << "images of " << a.size() << " and " << b.size() << " values";
    return r;
  }
  size_t close = 0;
  double sum_a[3] = {0, 0, 0}, sum_b[3] = {0, 0, 0};
  for (size_t i = 0; i < a.size(); ++i) {
    close += same_value(a[i], b[i]);
    sum_a[i % 3] += a[i];
    sum_b[i % 3] += b[i];
  }
  r.close_fraction = double(close) / double(a.size());
  for (int c = 0; c < 3; ++c)
    r.mean_relative_difference[c] = std::abs(sum_a[c] - sum_b[c]) / std::max(std::abs(sum_b[c]), 1e-30);
  return r;
}

}  // namespace clpt::test
