// One exception type for every user-facing failure, carrying the process exit code it maps to.
// Messages are complete sentences for the user: they name the file:line:column and key, the
// option, or the OpenCL call, error name and device.
#pragma once

#include <stdexcept>
#include <string>

namespace clpt {

// Process exit codes (documented in the README).
enum class ExitCode : int {
  Ok = 0,
  Failure = 1,      // unexpected internal failure
  Usage = 2,        // bad command line option or value
  BadScene = 3,     // scene file unreadable or invalid
  DeviceError = 4,  // no usable OpenCL device, build or launch failure
  OutputError = 5,  // an output file could not be written
  Interrupted = 130,  // SIGINT/SIGTERM: stopped early (128 + SIGINT, the shell's convention)
};

class Error : public std::runtime_error {
 public:
  Error(ExitCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
  ExitCode code() const { return code_; }

 private:
  ExitCode code_;
};

}  // namespace clpt
