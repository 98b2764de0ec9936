// A test hook: make one device of a multi-device render fail on purpose, to test that its work
// goes to the others (README, "Several devices at once"). The environment variable
// CLPT_INJECT_FAULT holds a comma list of faults:
//   build:D     the device at position D of the --device list fails its kernel build
//   launch:D:N  that device's Nth launch (N from 1: the Nth pixel-range chunk it takes) fails as
//               if clEnqueueNDRangeKernel had returned CL_OUT_OF_RESOURCES
// Unset or empty: no fault. Parsed here and nowhere else.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace clpt {

class FaultPlan {
 public:
  FaultPlan() = default;  // no faults

  // Parses `spec` (the syntax above); throws Error(Usage) naming CLPT_INJECT_FAULT and the bad entry.
  static FaultPlan parse(const std::string& spec);
  // The plan of CLPT_INJECT_FAULT in the environment.
  static FaultPlan from_environment();

  bool fails_build(size_t device) const;
  bool fails_launch(size_t device, uint64_t launch_number) const;

  // Throws the clpt::Error the CL wrapper would throw for `call` failing with `code` on `where`,
  // marked as injected.
  [[noreturn]] static void throw_injected(int code, const char* call, const std::string& where);

 private:
  struct Fault {
    bool build = false;    // else a launch
    size_t device = 0;     // position in the --device list
    uint64_t launch = 0;   // launch faults: which launch of that device, from 1
  };
  std::vector<Fault> faults_;
};

}  // namespace clpt
