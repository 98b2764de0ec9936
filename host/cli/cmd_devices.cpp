// `clpt devices`: every OpenCL platform and device, with what decides where clpt runs.
#include <cstdio>

#include "cl/cl_device.h"
#include "cli/commands.h"

namespace clpt {

std::function<int()> add_devices_command(CLI::App& app) {
  app.add_subcommand("devices", "List OpenCL platforms and devices (index, type, capabilities)");
  return [] {
    const std::vector<DeviceInfo> devices = list_devices();
    const DeviceInfo& best = best_device(devices);
    std::string platform;
    for (const DeviceInfo& d : devices) {
      if (d.platform_name != platform) {
        platform = d.platform_name;
        std::printf("platform: %s\n", platform.c_str());
      }
      // A simulator is marked: it is used only when named or when nothing else exists.
      std::printf("  [%d] %s %s%s%s\n", d.index, d.type.c_str(), d.name.c_str(),
                  d.is_simulator ? "   (simulator: used when named, or when no real device exists)" : "",
                  d.index == best.index ? "   (default)" : "");
      std::printf("      vendor %s, %u compute units at %u MHz\n", d.vendor.c_str(), d.compute_units,
                  d.clock_mhz);
      std::printf("      global memory %.1f GiB (max allocation %.1f GiB), local memory %.0f KiB\n",
                  double(d.global_mem_bytes) / 1073741824.0, double(d.max_alloc_bytes) / 1073741824.0,
                  double(d.local_mem_bytes) / 1024.0);
      std::printf("      fp64 %s, %s, device %s, driver %s\n", d.fp64 ? "yes" : "no",
                  d.opencl_c_version.c_str(), d.device_version.c_str(), d.driver_version.c_str());
    }
    return 0;
  };
}

}  // namespace clpt
