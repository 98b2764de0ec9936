#include "render/fault_injection.h"

#include <cstdlib>

#include "cl/cl_error.h"
#include "util/error.h"

namespace clpt {
namespace {

constexpr const char* kVariable = "CLPT_INJECT_FAULT";

// A decimal number of at most 9 digits (no sign), or -1.
long long parse_count(const std::string& s) {
  if (s.empty() || s.size() > 9) return -1;
  for (char c : s)
    if (c < '0' || c > '9') return -1;
  return std::stoll(s);
}

std::vector<std::string> split(const std::string& s, char separator) {
  std::vector<std::string> parts;
  size_t start = 0;
  for (size_t at; (at = s.find(separator, start)) != std::string::npos; start = at + 1)
    parts.push_back(s.substr(start, at - start));
  parts.push_back(s.substr(start));
  return parts;
}

}  // namespace

FaultPlan FaultPlan::parse(const std::string& spec) {
  FaultPlan plan;
  if (spec.empty()) return plan;
  for (const std::string& entry : split(spec, ',')) {
    const std::vector<std::string> f = split(entry, ':');
    Fault fault;
    fault.build = f[0] == "build";
    const bool valid_kind = (fault.build && f.size() == 2) || (f[0] == "launch" && f.size() == 3);
    const long long device = valid_kind ? parse_count(f[1]) : -1;
    const long long launch = valid_kind && !fault.build ? parse_count(f[2]) : 1;
    if (device < 0 || launch < 1)
      throw Error(ExitCode::Usage, std::string(kVariable) + "='" + spec + "': entry '" + entry +
                                       "' is neither build:DEVICE nor launch:DEVICE:N (N from 1)");
    fault.device = size_t(device);
    fault.launch = uint64_t(launch);
    plan.faults_.push_back(fault);
  }
  return plan;
}

FaultPlan FaultPlan::from_environment() {
  const char* spec = std::getenv(kVariable);
  return parse(spec ? spec : "");
}

bool FaultPlan::fails_build(size_t device) const {
  for (const Fault& f : faults_)
    if (f.build && f.device == device) return true;
  return false;
}

bool FaultPlan::fails_launch(size_t device, uint64_t launch_number) const {
  for (const Fault& f : faults_)
    if (!f.build && f.device == device && f.launch == launch_number) return true;
  return false;
}

void FaultPlan::throw_injected(int code, const char* call, const std::string& where) {
  cl_check(code, call, where + " [injected by " + kVariable + "]");
  throw Error(ExitCode::Failure, "FaultPlan::throw_injected: CL_SUCCESS is not a fault");
}

}  // namespace clpt
