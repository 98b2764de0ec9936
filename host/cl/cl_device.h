// OpenCL platform and device discovery: what `clpt devices` prints and what `--device` picks.
#pragma once

#include <CL/cl.h>

#include <cstdint>
#include <string>
#include <vector>

namespace clpt {

// The platform name PoCL reports (CL_PLATFORM_NAME).
inline constexpr const char* kPoclPlatformName = "Portable Computing Language";

struct DeviceInfo {
  int index = 0;  // position in list_devices(), as `clpt devices` shows it
  cl_platform_id platform = nullptr;
  cl_device_id id = nullptr;
  std::string platform_name;
  std::string name;
  std::string vendor;
  std::string type;  // "GPU", "CPU", "accelerator", "other"
  bool is_gpu = false;
  bool is_cpu = false;
  // A simulator (Oclgrind) rather than hardware: it may claim every device type and runs about
  // 1000x slower, so selection prefers real devices (see best_device and select_device).
  bool is_simulator = false;
  cl_uint compute_units = 0;
  cl_uint clock_mhz = 0;
  cl_ulong global_mem_bytes = 0;
  cl_ulong local_mem_bytes = 0;
  cl_ulong max_alloc_bytes = 0;
  size_t max_work_group_size = 0;
  bool fp64 = false;  // cl_khr_fp64
  std::string opencl_c_version;
  std::string driver_version;
  std::string device_version;

  // "device 'NAME' (PLATFORM)" for messages; "(PLATFORM, a simulator)" for a simulator.
  std::string label() const;
  // PoCL's CPU device (the platform clpt's tests and CI run on): the one whose compiler clpt can
  // read (vectoriser remarks) and whose vectoriser width it can set (cl/pocl_vectoriser.h).
  bool is_pocl_cpu() const;
  // Work-items a launch may have and still run the kernel the first launch compiled; 0: any.
  // PoCL compiles a separate kernel for launches of 65535 or more work-items a dimension (it
  // specialises its work-group functions on the grid's width, `-smallgrid` in its cache), so a
  // render whose small first launch and large later launches straddle that width compiled every
  // kernel twice; clpt keeps PoCL's launches under it (docs/performance.md "One compile a kernel").
  uint32_t uniform_launch_limit() const;
  // The driver keeps its own on-disk cache of built programs and compiled kernels (PoCL), so clpt
  // stores none of its binaries: fetching one made PoCL compile every kernel once more (a generic
  // copy for the binary), and a program made from it compiled its launches' kernels again.
  bool keeps_own_kernel_cache() const;
};

// Every device of every platform, in platform order. Throws when there is no platform at all.
std::vector<DeviceInfo> list_devices();

// The default device: the real GPU with the largest compute_units * clock, else the first real
// CPU, else the first real device; a simulator only when there is nothing else (then the first).
const DeviceInfo& best_device(const std::vector<DeviceInfo>& devices);

// Resolves a --device value: an index from `clpt devices`, "cpu" or "gpu" (the first of that type,
// "gpu" meaning the best GPU), "cpu:N" or "gpu:N" (the Nth device of that type, from 0: real
// devices in `clpt devices` order, then simulators), "best", or a case-insensitive substring of
// the device or platform name (e.g. "oclgrind"). "cpu" and "gpu" pick a simulator only when no
// real device of that type exists.
// Throws Error(Usage) naming the option and listing the devices when nothing matches.
const DeviceInfo& select_device(const std::vector<DeviceInfo>& devices, const std::string& spec);

// Resolves a --device value that may name several devices: "all" (every real device; every
// simulator too only when there is no real device), or a comma list
// of select_device entries ("0,1", "gpu:0,cpu"). A single entry resolves exactly as
// select_device. Throws Error(Usage) naming --device and the bad entry, and listing the devices,
// for an entry that matches nothing, an empty entry, or a device listed twice.
std::vector<DeviceInfo> select_devices(const std::vector<DeviceInfo>& devices, const std::string& spec);

}  // namespace clpt
