// A test hook: make one device of a multi-device render fail on purpose, to test that its work
// goes to the others (README, "Several devices at once"), or return wrong results, to test that
// `clpt verify` catches them. The environment variable CLPT_INJECT_FAULT holds a comma list of
// faults:
//   build:D        the device at position D of the --device list fails its kernel build
//   launch:D:N     that device's Nth launch (N from 1: the Nth pixel-range chunk it takes) fails
//                  as if clEnqueueNDRangeKernel had returned CL_OUT_OF_RESOURCES
//   perturb:D:C:F  that device's sample radiance in channel C (R, G or B) is multiplied by F (a
//                  finite number > 0) before it reaches the film: the pass sums by F, the sums of
//                  squares by F^2, as if every sample had been F times brighter
//   delay:D:MS     each launch of that device takes MS milliseconds longer (a slower device or
//                  MPI rank: how work is shared by measured speed)
//   exit:N         the process ends at once with exit status 1 when it starts its Nth pass (N
//                  from 1), as a crashed MPI rank would (docs/mpi.md)
// Unset or empty: no fault. Parsed here and nowhere else.
#pragma once

#include <array>
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
  // Per channel (R, G, B), the product of the perturb factors of `device`; 1 where none.
  std::array<double, 3> channel_factors(size_t device) const;
  // Milliseconds added to each launch of `device` (the sum of its delay faults; 0: none).
  uint64_t launch_delay_ms(size_t device) const;
  // Whether the process must end when it starts its pass number `pass` (from 1).
  bool exits_at_pass(uint64_t pass) const;
  bool empty() const { return faults_.empty(); }

  // The faults of the device at `position`, renumbered as device 0: for a harness that renders
  // each device of its own --device list alone (`clpt verify`), so that D keeps meaning the
  // position in the list the user wrote.
  FaultPlan for_device(size_t position) const;

  // Throws the clpt::Error the CL wrapper would throw for `call` failing with `code` on `where`,
  // marked as injected.
  [[noreturn]] static void throw_injected(int code, const char* call, const std::string& where);

 private:
  enum class Kind { Build, Launch, Perturb, Delay, Exit };
  struct Fault {
    Kind kind = Kind::Build;
    size_t device = 0;     // position in the --device list
    uint64_t launch = 0;   // launch faults: which launch of that device, from 1; exit: which pass
    uint64_t delay_ms = 0; // delay: milliseconds added to each launch
    int channel = 0;       // perturb: 0 = R, 1 = G, 2 = B
    double factor = 1;     // perturb: multiplies that channel's sample radiance
  };
  std::vector<Fault> faults_;
};

}  // namespace clpt
