// RankGroup (rank_group.h): the group of one process, and the loading of the MPI module under a launcher.
#include "render/rank_group.h"

#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <mutex>

#include "util/error.h"
#include "util/module_loader.h"

namespace clpt {
namespace {

constexpr const char* kModuleName = "libclpt_mpi.so";

class SingleProcess final : public RankGroup {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  std::string host() const override {
    char name[256] = {};
    return ::gethostname(name, sizeof name - 1) == 0 ? name : "?";
  }
  void broadcast(std::vector<uint8_t>&) override {}
  std::vector<std::vector<uint8_t>> gather(const std::vector<uint8_t>& mine) override { return {mine}; }
  void idle_barrier() override {}
  std::unique_ptr<RankGroup> first_ranks(int n) override {
    if (n != 1) throw Error(ExitCode::Failure, "first_ranks(" + std::to_string(n) + ") of a group of one");
    return single_process_group();
  }
  [[noreturn]] void abort(int exit_code) override { std::_Exit(exit_code); }
  void finish() override {}
};

std::unique_ptr<RankGroup> load_mpi_group(const std::string& launcher) {
#ifdef CLPT_MPI_MODULE_PATH
  const std::vector<std::string> candidates = module_candidates("CLPT_MPI_MODULE", kModuleName, CLPT_MPI_MODULE_PATH);
#else
  const std::vector<std::string> candidates = module_candidates("CLPT_MPI_MODULE", kModuleName, nullptr);
#endif
  const std::string started = "clpt was started by an MPI launcher (" + launcher + " is set)";
#ifndef CLPT_WITH_MPI
  if (!std::getenv("CLPT_MPI_MODULE"))
    throw Error(ExitCode::Usage, started + ", but this clpt was built without MPI (CLPT_WITH_MPI=OFF); "
                                           "rebuild with libopenmpi-dev installed, or run it without mpirun/srun");
#endif
  // RTLD_GLOBAL: Open MPI loads its own components (MCA plugins) with dlopen, and they bind to
  // libmpi's and libopen-pal's symbols.
  const LoadedModule m = load_module(candidates, "clpt_mpi_rank_group_v2", RTLD_NOW | RTLD_GLOBAL);
  if (!m.entry)
    throw Error(ExitCode::Usage, started + ", but the MPI module " + kModuleName +
                                     " cannot be loaded; set CLPT_MPI_MODULE to its path. Tried:" + m.tried);
  using Entry = RankGroup* (*)(std::string*);
  std::string error;
  RankGroup* group = reinterpret_cast<Entry>(m.entry)(&error);
  if (!group) throw Error(ExitCode::Failure, started + ", but MPI did not start: " + error);
  return std::unique_ptr<RankGroup>(group);
}

std::once_flag g_created;
std::unique_ptr<RankGroup> g_group;

}  // namespace

std::string rank_label(const RankGroup& group, int rank, const std::string& host) {
  return "rank " + std::to_string(rank) + " of " + std::to_string(group.size()) + " (host " + host + ")";
}

std::string mpi_launcher_variable() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (const char* value = std::getenv(name); value && *value) return name;
  return "";
}

RankGroup& process_rank_group() {
  std::call_once(g_created, [] {
    const std::string launcher = mpi_launcher_variable();
    g_group = launcher.empty() ? single_process_group() : load_mpi_group(launcher);
  });
  if (!g_group) throw Error(ExitCode::Failure, "the MPI group failed to start earlier in this process");
  return *g_group;
}

RankGroup* existing_rank_group() { return g_group.get(); }

std::unique_ptr<RankGroup> single_process_group() { return std::make_unique<SingleProcess>(); }

}  // namespace clpt
