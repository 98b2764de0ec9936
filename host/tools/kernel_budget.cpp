#include "tools/kernel_budget.h"

#include <cctype>
#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <sstream>

#include "cl/cl_context.h"
#include "kernels/kernel_options.h"
#include "kernels/kernel_source.h"
#include "tools/kernel_variants.h"
#include "util/appendf.h"

namespace clpt {
namespace {

bool is_nvidia(const DeviceInfo& device) {
  return device.platform_name.find("NVIDIA") != std::string::npos ||
         device.vendor.find("NVIDIA") != std::string::npos;
}

// The text between the first pair of single quotes after `from`, or "".
std::string quoted_after(const std::string& line, size_t from) {
  const size_t a = line.find('\'', from);
  const size_t b = a == std::string::npos ? a : line.find('\'', a + 1);
  return b == std::string::npos ? "" : line.substr(a + 1, b - a - 1);
}

// The integer just before `words` on the line ("Used 230 registers" -> 230), or -1.
int number_before(const std::string& line, const char* words) {
  size_t at = line.find(words);
  if (at == std::string::npos) return -1;
  while (at > 0 && line[at - 1] == ' ') --at;
  size_t begin = at;
  while (begin > 0 && std::isdigit(static_cast<unsigned char>(line[begin - 1]))) --begin;
  return begin == at ? -1 : std::atoi(line.c_str() + begin);
}

}  // namespace

void parse_nvidia_build_log(const std::string& log, std::vector<KernelBudgetRow>& rows) {
  std::istringstream in(log);
  std::string line, current;
  const auto row_of = [&rows](const std::string& kernel) -> KernelBudgetRow* {
    for (KernelBudgetRow& r : rows)
      if (r.kernel == kernel) return &r;
    return nullptr;
  };
  while (std::getline(in, line)) {
    size_t at;
    if ((at = line.find("Compiling entry function")) != std::string::npos) {
      current = quoted_after(line, at);
    } else if ((at = line.find("Function properties for ")) != std::string::npos) {
      current = line.substr(at + 24);
      while (!current.empty() && (current.back() == ' ' || current.back() == '\r')) current.pop_back();
    } else if (KernelBudgetRow* r = row_of(current)) {
      // The figures are read by their words, wherever they sit on the line (a driver may indent
      // or prefix them differently from ptxas's own -v output).
      if (line.find("stack frame") != std::string::npos) {
        r->stack_bytes = number_before(line, "bytes stack frame");
        r->spill_store_bytes = number_before(line, "bytes spill stores");
        r->spill_load_bytes = number_before(line, "bytes spill loads");
      } else if (line.find("registers") != std::string::npos) {
        r->registers = number_before(line, "registers");
      }
    }
  }
}

std::vector<KernelBudgetRow> measure_kernel_budget(const DeviceInfo& device, const Scene& diffuse,
                                                   const std::vector<KernelVariant>& variants,
                                                   void (*on_variant)(const std::string&),
                                                   void (*on_log)(const std::string&)) {
  DeviceContext ctx(device);  // no kernel cache: every program is compiled, so the log is fresh
  std::vector<KernelBudgetRow> all;
  for (const KernelVariant& v : variants) {
    if (v.precision() == Precision::Double && !device.fp64) continue;
    if (on_variant) on_variant(v.name());
    const VariantProgram program = variant_program(variant_scene(diffuse, v), v);
    std::string options = kernel_build_options(program.features);
    if (is_nvidia(device)) options += " -cl-nv-verbose";
    const auto start = std::chrono::steady_clock::now();
    const ProgramHandle built = ctx.build_program_from_source(assemble_kernel_source(program.entry_file), options,
                                                              v.name());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::vector<KernelBudgetRow> rows;
    for (const std::string& name : Kernel::names_in(built, ctx.where())) {
      const Kernel kernel(built.get(), name, ctx.where());
      const Kernel::Resources res = kernel.resources(device.id);
      KernelBudgetRow row;
      row.variant = v.name();
      row.kernel = name;
      row.build_seconds = seconds;
      row.private_bytes = res.private_bytes;
      row.local_bytes = res.local_bytes;
      row.max_work_group = res.max_work_group;
      row.preferred_multiple = res.preferred_multiple;
      rows.push_back(row);
    }
    if (is_nvidia(device)) {
      const std::string log = ctx.build_log(built);
      parse_nvidia_build_log(log, rows);
      if (on_log && all.empty()) on_log(log);
    }
    all.insert(all.end(), rows.begin(), rows.end());
  }
  return all;
}

std::string kernel_budget_tsv(const std::vector<KernelBudgetRow>& rows) {
  std::string out =
      "variant\tkernel\tbuild_s\tregisters\tstack_bytes\tspill_store_bytes\tspill_load_bytes\t"
      "private_bytes\tlocal_bytes\tmax_work_group\tpreferred_multiple\n";
  const auto known = [](int v) { return v < 0 ? std::string() : std::to_string(v); };
  for (const KernelBudgetRow& r : rows)
    appendf(out, "%s\t%s\t%.2f\t%s\t%s\t%s\t%s\t%llu\t%llu\t%zu\t%zu\n", r.variant.c_str(), r.kernel.c_str(),
            r.build_seconds, known(r.registers).c_str(), known(r.stack_bytes).c_str(),
            known(r.spill_store_bytes).c_str(), known(r.spill_load_bytes).c_str(),
            (unsigned long long)r.private_bytes, (unsigned long long)r.local_bytes, r.max_work_group,
            r.preferred_multiple);
  return out;
}

}  // namespace clpt
