// The processes of one render: a plain process (a group of one), or the ranks of a job started by
// an MPI launcher (`mpirun -n K clpt render ...`, `srun --mpi=pmix ...`). The render core talks to
// other ranks only through this interface (docs/mpi.md): a few collectives on byte buffers,
// called by every rank in the same order. The MPI implementation lives in a module of its own,
// libclpt_mpi.so (rank_group_mpi.cpp), built beside clpt when CLPT_WITH_MPI is on and loaded by
// process_rank_group() only when the environment shows that a launcher started this process: a
// plain `clpt render` maps no MPI library and calls no MPI function.
//
// Contract of the module: built from this tree by the same compiler as clpt (like the image I/O
// module), so this C++ class crosses the boundary; it reports errors as text, never as exceptions.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace clpt {

class RankGroup {
 public:
  virtual ~RankGroup() = default;

  virtual int rank() const = 0;  // 0 .. size() - 1; rank 0 coordinates and writes the outputs
  virtual int size() const = 0;
  bool coordinator() const { return rank() == 0; }
  // This rank's host name (messages and the summary name rank and host).
  virtual std::string host() const = 0;

  // Collectives: every rank calls each of them, in the same order.
  // Rank 0's `bytes` on every rank (resized on the others).
  virtual void broadcast(std::vector<uint8_t>& bytes) = 0;
  // Every rank's `mine`, in rank order, at rank 0; an empty list on the other ranks.
  virtual std::vector<std::vector<uint8_t>> gather(const std::vector<uint8_t>& mine) = 0;
  // Returns when every rank has called it. A rank waiting here sleeps between checks instead of
  // spinning as MPI's blocking collectives do, so idle ranks leave the cores to working ones.
  virtual void idle_barrier() = 0;

  // Collective: the group of this group's ranks 0 .. n-1 (1 <= n <= size()), rank r here being
  // rank r there, returned on those ranks; null on the others. `clpt bench` measures a render on
  // the first 1, 2, .. K ranks of a job with it. The group of one process returns a group of one
  // for n = 1. A sub-group's abort() ends the whole job; its finish() does nothing (the job is
  // left through the process group).
  virtual std::unique_ptr<RankGroup> first_ranks(int n) = 0;

  // Ends the whole job at once with `exit_code` (an error on one rank that the others cannot
  // know of would leave them waiting in a collective). Does not return.
  [[noreturn]] virtual void abort(int exit_code) = 0;
  // Leaves the job (MPI_Finalize); called once, at the end of a successful or orderly run.
  virtual void finish() = 0;
};

// "rank R of K (host H)": how messages name a rank.
std::string rank_label(const RankGroup& group, int rank, const std::string& host);

// Which launcher, if any, started this process, from the variables launchers set: Open MPI's
// mpirun (OMPI_COMM_WORLD_SIZE), a PMIx server such as `srun --mpi=pmix` (PMIX_RANK), or a PMI-2
// one such as `srun --mpi=pmi2` (PMI_RANK). Empty: a plain process. Plain `srun` without --mpi and
// an sbatch script set SLURM_PROCID only, and are plain processes here.
std::string mpi_launcher_variable();

// The group of this process, created on the first call: the single process, or (started by a
// launcher) the MPI module's group. Throws Error(Usage) when a launcher started clpt but this clpt
// has no MPI module (built with CLPT_WITH_MPI=OFF) or the module cannot be loaded.
RankGroup& process_rank_group();
// The group when process_rank_group() has created one, else null (main.cpp: whether an error
// must end the other ranks too).
RankGroup* existing_rank_group();

// The group of one process, without MPI (every collective returns its own argument).
std::unique_ptr<RankGroup> single_process_group();

}  // namespace clpt

// The MPI module's one entry point (the version in the name changes with RankGroup). Returns a
// group that has called MPI_Init, or null with the reason in `error`.
extern "C" clpt::RankGroup* clpt_mpi_rank_group_v2(std::string* error);
