#include "render/fault_injection.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <optional>

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

// "R", "G" or "B" as 0, 1, 2; else -1.
int parse_channel(const std::string& s) {
  if (s == "R") return 0;
  if (s == "G") return 1;
  if (s == "B") return 2;
  return -1;
}

// A finite number > 0 written in full (strtod must consume every character), or nothing.
std::optional<double> parse_factor(const std::string& s) {
  if (s.empty() || std::isspace(static_cast<unsigned char>(s[0]))) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(s.c_str(), &end);
  if (errno != 0 || end != s.c_str() + s.size() || !std::isfinite(value) || value <= 0) return std::nullopt;
  return value;
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
    bool valid = false;
    long long device = -1;
    if (f[0] == "build" && f.size() == 2) {
      fault.kind = Kind::Build;
      device = parse_count(f[1]);
      valid = device >= 0;
    } else if (f[0] == "launch" && f.size() == 3) {
      fault.kind = Kind::Launch;
      device = parse_count(f[1]);
      const long long launch = parse_count(f[2]);
      fault.launch = uint64_t(std::max(0LL, launch));
      valid = device >= 0 && launch >= 1;
    } else if (f[0] == "perturb" && f.size() == 4) {
      fault.kind = Kind::Perturb;
      device = parse_count(f[1]);
      fault.channel = parse_channel(f[2]);
      const std::optional<double> factor = parse_factor(f[3]);
      fault.factor = factor.value_or(0);
      valid = device >= 0 && fault.channel >= 0 && factor.has_value();
    } else if (f[0] == "delay" && f.size() == 3) {
      fault.kind = Kind::Delay;
      device = parse_count(f[1]);
      const long long ms = parse_count(f[2]);
      fault.delay_ms = uint64_t(std::max(0LL, ms));
      valid = device >= 0 && ms >= 0;
    } else if (f[0] == "exit" && f.size() == 2) {
      fault.kind = Kind::Exit;
      const long long pass = parse_count(f[1]);
      fault.launch = uint64_t(std::max(0LL, pass));
      device = 0;
      valid = pass >= 1;
    }
    if (!valid)
      throw Error(ExitCode::Usage, std::string(kVariable) + "='" + spec + "': entry '" + entry +
                                       "' is none of build:DEVICE, launch:DEVICE:N (N from 1), "
                                       "perturb:DEVICE:R|G|B:FACTOR (FACTOR a finite number > 0), "
                                       "delay:DEVICE:MS and exit:PASS (PASS from 1)");
    fault.device = size_t(device);
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
    if (f.kind == Kind::Build && f.device == device) return true;
  return false;
}

bool FaultPlan::fails_launch(size_t device, uint64_t launch_number) const {
  for (const Fault& f : faults_)
    if (f.kind == Kind::Launch && f.device == device && f.launch == launch_number) return true;
  return false;
}

std::array<double, 3> FaultPlan::channel_factors(size_t device) const {
  std::array<double, 3> factors = {1, 1, 1};
  for (const Fault& f : faults_)
    if (f.kind == Kind::Perturb && f.device == device) factors[size_t(f.channel)] *= f.factor;
  return factors;
}

uint64_t FaultPlan::launch_delay_ms(size_t device) const {
  uint64_t ms = 0;
  for (const Fault& f : faults_)
    if (f.kind == Kind::Delay && f.device == device) ms += f.delay_ms;
  return ms;
}

bool FaultPlan::exits_at_pass(uint64_t pass) const {
  for (const Fault& f : faults_)
    if (f.kind == Kind::Exit && f.launch == pass) return true;
  return false;
}

FaultPlan FaultPlan::for_device(size_t position) const {
  FaultPlan plan;
  for (Fault f : faults_)
    if (f.device == position) {
      f.device = 0;
      plan.faults_.push_back(f);
    }
  return plan;
}

void FaultPlan::throw_injected(int code, const char* call, const std::string& where) {
  cl_check(code, call, where + " [injected by " + kVariable + "]");
  throw Error(ExitCode::Failure, "FaultPlan::throw_injected: CL_SUCCESS is not a fault");
}

}  // namespace clpt
