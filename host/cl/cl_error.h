// The one wrapper every OpenCL call goes through: a failed call becomes a clpt::Error naming the
// call, the CL error name and the device (or platform) it was made for.
#pragma once

#include <CL/cl.h>

#include <string>

#include "util/error.h"

namespace clpt {

// "CL_OUT_OF_RESOURCES" for -5, "CL error -9999" for codes it does not know.
std::string cl_error_name(cl_int code);

// Throws Error(ExitCode::DeviceError) "CALL failed with NAME on WHERE" unless code is CL_SUCCESS.
void cl_check(cl_int code, const char* call, const std::string& where);

}  // namespace clpt

// CL_CALL(where, clFoo(args...)): runs the call and checks its return code.
#define CL_CALL(where, call) ::clpt::cl_check((call), #call, (where))
// CL_CREATE(where, clCreateFoo, args...): for creators that report through a last cl_int* arg.
#define CL_CREATE(where, fn, ...)                                                                  \
  [&]() {                                                                                          \
    cl_int clpt_err_ = CL_SUCCESS;                                                                 \
    auto clpt_obj_ = fn(__VA_ARGS__, &clpt_err_);                                                  \
    ::clpt::cl_check(clpt_err_, #fn, (where));                                                     \
    return clpt_obj_;                                                                              \
  }()
