#include "cl/pocl_vectoriser.h"

#include <dlfcn.h>
#include <link.h>

#include <cstdlib>
#include <cstring>
#include <mutex>
#include <stdexcept>

namespace clpt {
namespace {

// LLVM's C entry point to its command-line parser (llvm-c/Support.h); stable since LLVM 3.
using ParseOptions = void (*)(int argc, const char* const* argv, const char* overview);

// The oldest LLVM whose options may occur more than once (LLVM 15 made that every option's
// default); with an older one a second setting would be a parse error, which LLVM answers by
// exiting the process.
constexpr int kOldestLlvm = 15;

struct Vectoriser {
  std::mutex mutex;
  ParseOptions parse = nullptr;  // found once, then kept: PoCL stays loaded until exit
  uint32_t lanes = 0;            // the width last set; 0: never set, LLVM's default
  bool slp_on = true;            // SLP as last set; LLVM's default until set
};

Vectoriser& vectoriser() {
  static Vectoriser v;
  return v;
}

// The path of the loaded libpocl, or "" when PoCL is not in this process. The ICD loader opens
// drivers privately (RTLD_LOCAL), so neither PoCL's symbols nor its LLVM's are in the global scope.
std::string loaded_pocl_path() {
  std::string path;
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void* out) {
        const char* name = info->dlpi_name;
        const char* base = name ? std::strrchr(name, '/') : nullptr;
        base = base ? base + 1 : name;
        if (base && std::strncmp(base, "libpocl.so", 10) == 0) {
          *static_cast<std::string*>(out) = name;
          return 1;
        }
        return 0;
      },
      &path);
  return path;
}

// The major version in a shared LLVM's file name ("libLLVM-15.so.1", "libLLVM.so.19.1"), or 0.
int llvm_major_of(const char* path) {
  const char* base = std::strrchr(path, '/');
  base = base ? base + 1 : path;
  for (const char* prefix : {"libLLVM-", "libLLVM.so."}) {
    const size_t n = std::strlen(prefix);
    if (std::strncmp(base, prefix, n) == 0) return std::atoi(base + n);
  }
  return 0;
}

// Finds LLVM's parser among libpocl's dependencies (dlsym on a library's handle searches it and
// what it links, in load order), or says why not. Caller holds the mutex.
ParseOptions find_parser(Vectoriser& v, std::string* why_not) {
  if (v.parse) return v.parse;
  auto fail = [&](const std::string& why) -> ParseOptions {
    if (why_not) *why_not = why;
    return nullptr;
  };
  const std::string pocl = loaded_pocl_path();
  if (pocl.empty()) return fail("PoCL is not loaded in this process");
  // Deliberately never closed: it pins PoCL, and with it the parser, for the process's life.
  void* handle = dlopen(pocl.c_str(), RTLD_LAZY | RTLD_NOLOAD);
  if (!handle) return fail("PoCL (" + pocl + ") could not be opened again");
  void* symbol = dlsym(handle, "LLVMParseCommandLineOptions");
  if (!symbol) return fail("PoCL (" + pocl + ") exposes no LLVM command-line parser (a static LLVM?)");
  Dl_info info{};
  if (!dladdr(symbol, &info) || !info.dli_fname) return fail("PoCL's LLVM could not be located");
  const int major = llvm_major_of(info.dli_fname);
  if (major < kOldestLlvm)
    return fail(std::string("PoCL's LLVM (") + info.dli_fname + ") is not a shared LLVM " +
                std::to_string(kOldestLlvm) + " or later");
  v.parse = reinterpret_cast<ParseOptions>(symbol);
  return v.parse;
}

}  // namespace

bool pocl_vectoriser_reachable(std::string* why_not) {
  Vectoriser& v = vectoriser();
  std::lock_guard<std::mutex> lock(v.mutex);
  return find_parser(v, why_not) != nullptr;
}

void set_pocl_vectoriser_lanes(uint32_t lanes) {
  Vectoriser& v = vectoriser();
  std::lock_guard<std::mutex> lock(v.mutex);
  if (lanes == v.lanes) return;
  std::string why;
  const ParseOptions parse = find_parser(v, &why);
  if (!parse) throw std::logic_error("set_pocl_vectoriser_lanes(" + std::to_string(lanes) + "): " + why);
  // 0 is LLVM's own default: the cost model picks the width again.
  const std::string option = "-force-vector-width=" + std::to_string(lanes);
  const char* argv[] = {"clpt", option.c_str()};
  parse(2, argv, "");
  v.lanes = lanes;
}

void set_pocl_slp(bool on) {
  Vectoriser& v = vectoriser();
  std::lock_guard<std::mutex> lock(v.mutex);
  if (on == v.slp_on) return;
  std::string why;
  const ParseOptions parse = find_parser(v, &why);
  if (!parse) throw std::logic_error(std::string("set_pocl_slp(") + (on ? "true" : "false") + "): " + why);
  // LLVM 15's default threshold is 0 (vectorise when the cost model gains anything).
  const char* option = on ? "-slp-threshold=0" : "-slp-threshold=1000000";
  const char* argv[] = {"clpt", option};
  parse(2, argv, "");
  v.slp_on = on;
}

}  // namespace clpt
