// Helpers for the tests that run on Oclgrind (label `oclgrind`, docs/oclgrind.md): finding its
// device, and capturing what its checkers report.
//
// Oclgrind 21.10 reports every finding as text on stderr: its kernel checks ("Invalid read of
// size 4 at global memory address ...", "Read-write data race at ...", "Work-group divergence
// detected ...") through its logger, and with OCLGRIND_CHECK_API=1 every OpenCL call that fails
// ("Oclgrind - OpenCL runtime error detected") straight to std::cerr. Nothing is made fatal and
// no count can be queried: a render with findings still returns its image. OCLGRIND_LOG would send
// the logger's part to a file, but not the API errors, and each new context would truncate that
// file; so the tests capture file descriptor 2 itself around each Oclgrind render and treat any
// text written there as a finding.
#pragma once

#include <string>
#include <vector>

namespace clpt::test {

// Whether list_devices() has an Oclgrind device; when not, `why` says how to get one (the Debian
// package `oclgrind`, and the vendors directory cmake writes for ctest).
bool oclgrind_present(std::string& why);

// What was written on stderr during a capture, with Oclgrind's findings counted by kind.
struct OclgrindFindings {
  std::string text;  // everything written on file descriptor 2 meanwhile
  int invalid_access = 0;  // "Invalid read of size" / "Invalid write of size"
  int data_race = 0;       // "... data race at ..."
  int divergence = 0;      // "Work-group divergence" / "Work-item divergence"
  int api_error = 0;       // "OpenCL runtime error detected" (OCLGRIND_CHECK_API)
  bool clean() const { return text.empty(); }
  // The counts and the first lines of the text, for a failure message.
  std::string summary() const;
};

// Redirects file descriptor 2 (std::cerr and stderr, whichever thread writes) into a file named
// after the running test under the build tree's oclgrind/ directory, kept for inspection, until
// finish(). Process-wide, so one at a time; the destructor restores stderr if finish() was not
// called.
class StderrCapture {
 public:
  explicit StderrCapture(const std::string& tag);
  ~StderrCapture();
  StderrCapture(const StderrCapture&) = delete;
  StderrCapture& operator=(const StderrCapture&) = delete;

  OclgrindFindings finish();
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int saved_fd_ = -1;
};

// Same-seed agreement of two mean images (RGB interleaved, same size): the fraction of values
// within 1e-4 relative of each other (as expect_same_image counts them) and, per channel, the
// relative difference of the image means.
struct SameSeedAgreement {
  double close_fraction = 0;
  double mean_relative_difference[3] = {0, 0, 0};
  double worst_mean_difference() const;
  std::string describe() const;  // "99.48% of values within 1e-4, means within 3.1e-05 relative"
};
SameSeedAgreement same_seed_agreement(const std::vector<float>& a, const std::vector<float>& b);

}  // namespace clpt::test
