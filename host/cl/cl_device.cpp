#include "cl/cl_device.h"

#include <cstdlib>

#include <algorithm>
#include <cctype>

#include "cl/cl_error.h"

namespace clpt {
namespace {

std::string platform_string(cl_platform_id platform, cl_platform_info param) {
  size_t size = 0;
  CL_CALL("platform", clGetPlatformInfo(platform, param, 0, nullptr, &size));
  std::string value(size, '\0');
  CL_CALL("platform", clGetPlatformInfo(platform, param, size, value.data(), nullptr));
  while (!value.empty() && value.back() == '\0') value.pop_back();
  return value;
}

std::string device_string(cl_device_id device, cl_device_info param, const std::string& where) {
  size_t size = 0;
  CL_CALL(where, clGetDeviceInfo(device, param, 0, nullptr, &size));
  std::string value(size, '\0');
  CL_CALL(where, clGetDeviceInfo(device, param, size, value.data(), nullptr));
  while (!value.empty() && value.back() == '\0') value.pop_back();
  return value;
}

template <typename T>
T device_value(cl_device_id device, cl_device_info param, const std::string& where) {
  T value{};
  CL_CALL(where, clGetDeviceInfo(device, param, sizeof(T), &value, nullptr));
  return value;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

DeviceInfo describe(cl_platform_id platform, const std::string& platform_name, cl_device_id id) {
  DeviceInfo d;
  d.platform = platform;
  d.id = id;
  d.platform_name = platform_name;
  const std::string where = "a device of platform '" + platform_name + "'";
  d.name = device_string(id, CL_DEVICE_NAME, where);
  const std::string self = "device '" + d.name + "'";
  d.vendor = device_string(id, CL_DEVICE_VENDOR, self);
  const auto type = device_value<cl_device_type>(id, CL_DEVICE_TYPE, self);
  d.is_gpu = (type & CL_DEVICE_TYPE_GPU) != 0;
  d.is_cpu = (type & CL_DEVICE_TYPE_CPU) != 0;
  // Simulators known by name: Oclgrind (it reports every device-type bit).
  d.is_simulator = lower(platform_name).find("oclgrind") != std::string::npos ||
                   lower(d.name).find("oclgrind") != std::string::npos;
  d.type = d.is_gpu ? "GPU" : d.is_cpu ? "CPU" : (type & CL_DEVICE_TYPE_ACCELERATOR) ? "accelerator" : "other";
  d.compute_units = device_value<cl_uint>(id, CL_DEVICE_MAX_COMPUTE_UNITS, self);
  d.clock_mhz = device_value<cl_uint>(id, CL_DEVICE_MAX_CLOCK_FREQUENCY, self);
  d.global_mem_bytes = device_value<cl_ulong>(id, CL_DEVICE_GLOBAL_MEM_SIZE, self);
  d.local_mem_bytes = device_value<cl_ulong>(id, CL_DEVICE_LOCAL_MEM_SIZE, self);
  d.max_alloc_bytes = device_value<cl_ulong>(id, CL_DEVICE_MAX_MEM_ALLOC_SIZE, self);
  d.max_work_group_size = device_value<size_t>(id, CL_DEVICE_MAX_WORK_GROUP_SIZE, self);
  const std::string extensions = device_string(id, CL_DEVICE_EXTENSIONS, self);
  // CLPT_HIDE_FP64=1 makes every device look as if it lacked fp64: a test hook for the error
  // of --precision double on such a device, since PoCL's CPU devices all have it.
  const char* hide_fp64 = std::getenv("CLPT_HIDE_FP64");
  d.fp64 = extensions.find("cl_khr_fp64") != std::string::npos && !(hide_fp64 && std::string(hide_fp64) == "1");
  d.opencl_c_version = device_string(id, CL_DEVICE_OPENCL_C_VERSION, self);
  d.driver_version = device_string(id, CL_DRIVER_VERSION, self);
  d.device_version = device_string(id, CL_DEVICE_VERSION, self);
  return d;
}

}  // namespace

bool DeviceInfo::is_pocl_cpu() const { return is_cpu && platform_name == kPoclPlatformName; }

// PoCL's limit is USHRT_MAX work-items a dimension (its CPU drivers' grid_width_specialization_limit);
// 64512 is the largest multiple of 1024 (every work-group size clpt uses divides it) below it.
uint32_t DeviceInfo::uniform_launch_limit() const { return platform_name == kPoclPlatformName ? 64512u : 0u; }

bool DeviceInfo::keeps_own_kernel_cache() const { return platform_name == kPoclPlatformName; }

std::string DeviceInfo::label() const {
  return "device '" + name + "' (" + platform_name + (is_simulator ? ", a simulator)" : ")");
}

std::vector<DeviceInfo> list_devices() {
  cl_uint platform_count = 0;
  const cl_int err = clGetPlatformIDs(0, nullptr, &platform_count);
  if (err == -1001 /* CL_PLATFORM_NOT_FOUND_KHR */ || platform_count == 0) {
    throw Error(ExitCode::DeviceError,
                "no OpenCL platform found: install an OpenCL driver (e.g. Debian's pocl-opencl-icd "
                "for the CPU) and check /etc/OpenCL/vendors");
  }
  cl_check(err, "clGetPlatformIDs", "the OpenCL ICD loader");
  std::vector<cl_platform_id> platforms(platform_count);
  CL_CALL("the OpenCL ICD loader", clGetPlatformIDs(platform_count, platforms.data(), nullptr));

  std::vector<DeviceInfo> devices;
  for (cl_platform_id platform : platforms) {
    const std::string platform_name = platform_string(platform, CL_PLATFORM_NAME);
    cl_uint count = 0;
    const cl_int e = clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, 0, nullptr, &count);
    if (e == CL_DEVICE_NOT_FOUND || count == 0) continue;
    cl_check(e, "clGetDeviceIDs", "platform '" + platform_name + "'");
    std::vector<cl_device_id> ids(count);
    CL_CALL("platform '" + platform_name + "'",
            clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, count, ids.data(), nullptr));
    for (cl_device_id id : ids) {
      devices.push_back(describe(platform, platform_name, id));
      devices.back().index = static_cast<int>(devices.size()) - 1;
    }
  }
  if (devices.empty()) throw Error(ExitCode::DeviceError, "no OpenCL device found on any platform");
  return devices;
}

namespace {

// The devices of a type ("gpu" or "cpu"), real ones first in `clpt devices` order, then
// simulators: what "gpu:N" / "cpu:N" count in.
std::vector<const DeviceInfo*> of_type(const std::vector<DeviceInfo>& devices, bool gpu) {
  std::vector<const DeviceInfo*> found;
  for (bool simulators : {false, true})
    for (const DeviceInfo& d : devices)
      if ((gpu ? d.is_gpu : d.is_cpu) && d.is_simulator == simulators) found.push_back(&d);
  return found;
}

// The best GPU: the largest compute_units * clock among real GPUs; null when there is none.
const DeviceInfo* best_real_gpu(const std::vector<DeviceInfo>& devices) {
  const DeviceInfo* best = nullptr;
  for (const DeviceInfo& d : devices) {
    if (!d.is_gpu || d.is_simulator) continue;
    const double score = double(d.compute_units) * d.clock_mhz;
    if (!best || score > double(best->compute_units) * best->clock_mhz) best = &d;
  }
  return best;
}

// The Nth device (from 0) of a type, for "gpu:N" / "cpu:N"; null when there are fewer.
const DeviceInfo* nth_of_type(const std::vector<DeviceInfo>& devices, bool gpu, const std::string& n) {
  if (n.empty() || n.size() > 6 || !std::all_of(n.begin(), n.end(), [](unsigned char c) { return std::isdigit(c); }))
    return nullptr;
  const size_t wanted = std::stoul(n);
  const std::vector<const DeviceInfo*> found = of_type(devices, gpu);
  return wanted < found.size() ? found[wanted] : nullptr;
}

}  // namespace

const DeviceInfo& best_device(const std::vector<DeviceInfo>& devices) {
  if (const DeviceInfo* gpu = best_real_gpu(devices)) return *gpu;
  for (const DeviceInfo& d : devices)
    if (d.is_cpu && !d.is_simulator) return d;
  for (const DeviceInfo& d : devices)
    if (!d.is_simulator) return d;
  return devices.front();
}

namespace {

// One --device entry, or null when it names no device.
const DeviceInfo* find_device(const std::vector<DeviceInfo>& devices, const std::string& spec) {
  const std::string s = lower(spec);
  if (s.empty() || s == "best") return &best_device(devices);
  if (std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); })) {
    if (s.size() <= 9 && std::stoul(s) < devices.size()) return &devices[std::stoul(s)];
  } else if (s == "gpu") {
    if (const DeviceInfo* gpu = best_real_gpu(devices)) return gpu;
    return nth_of_type(devices, true, "0");  // a simulator, when no real GPU exists
  } else if (s == "cpu") {
    return nth_of_type(devices, false, "0");
  } else if (s.rfind("gpu:", 0) == 0 || s.rfind("cpu:", 0) == 0) {
    return nth_of_type(devices, s[0] == 'g', s.substr(4));
  } else {
    for (const DeviceInfo& d : devices)
      if (lower(d.name).find(s) != std::string::npos) return &d;
    for (const DeviceInfo& d : devices)
      if (lower(d.platform_name).find(s) != std::string::npos) return &d;
  }
  return nullptr;
}

std::string device_listing(const std::vector<DeviceInfo>& devices) {
  std::string listing = "available:";
  for (const DeviceInfo& d : devices)
    listing += "\n  " + std::to_string(d.index) + ": " + d.type + " " + d.label();
  return listing;
}

}  // namespace

const DeviceInfo& select_device(const std::vector<DeviceInfo>& devices, const std::string& spec) {
  if (const DeviceInfo* d = find_device(devices, spec)) return *d;
  throw Error(ExitCode::Usage, "--device '" + spec + "': no such device; " + device_listing(devices));
}

std::vector<DeviceInfo> select_devices(const std::vector<DeviceInfo>& devices, const std::string& spec) {
  if (spec.find(',') == std::string::npos && lower(spec) != "all") return {select_device(devices, spec)};
  std::vector<DeviceInfo> chosen;
  auto add = [&](const DeviceInfo& d, const std::string& entry) {
    for (const DeviceInfo& c : chosen)
      if (c.index == d.index)
        throw Error(ExitCode::Usage, "--device '" + spec + "': entry '" + entry + "' names device " +
                                         std::to_string(d.index) + " a second time; " +
                                         device_listing(devices));
    chosen.push_back(d);
  };
  size_t start = 0;
  for (;;) {
    const size_t comma = spec.find(',', start);
    const std::string entry = spec.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (entry.empty())
      throw Error(ExitCode::Usage, "--device '" + spec + "': empty entry in the list; " + device_listing(devices));
    if (lower(entry) == "all") {
      // Every real device; simulators are named to be used beside them ("all,oclgrind").
      const bool any_real = std::any_of(devices.begin(), devices.end(), [](const DeviceInfo& d) { return !d.is_simulator; });
      for (const DeviceInfo& d : devices)
        if (!d.is_simulator || !any_real) add(d, entry);
    } else if (const DeviceInfo* d = find_device(devices, entry)) {
      add(*d, entry);
    } else {
      throw Error(ExitCode::Usage, "--device '" + spec + "': entry '" + entry + "': no such device; " +
                                       device_listing(devices));
    }
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return chosen;
}

}  // namespace clpt
