#include "device_test_util.h"

#include <cstdlib>
#include <map>
#include <memory>

#include "cl/cl_device.h"
#include "kernels/kernel_source.h"

namespace clpt::test {

DeviceContext& test_device() {
  static std::unique_ptr<DeviceContext> ctx = [] {
    const char* spec = std::getenv("CLPT_TEST_DEVICE");
    const std::vector<DeviceInfo> devices = list_devices();
    return std::make_unique<DeviceContext>(select_device(devices, spec ? spec : "cpu"));
  }();
  return *ctx;
}

cl_program test_program(const std::string& file, const std::string& options) {
  static std::map<std::string, ProgramHandle> programs;
  const std::string key = file + "|" + options;
  auto it = programs.find(key);
  if (it == programs.end())
    it = programs.emplace(key, test_device().build_program(assemble_kernel_source(file), options, file)).first;
  return it->second.get();
}

std::string source_dir() { return CLPT_SOURCE_DIR; }

}  // namespace clpt::test
