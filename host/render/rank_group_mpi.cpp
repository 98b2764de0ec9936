// The MPI implementation of RankGroup (render/rank_group.h), built as the module libclpt_mpi.so:
// the only file that includes mpi.h or calls MPI. clpt loads it only when an MPI launcher started
// the process. MPI_COMM_WORLD is the process group; first_ranks splits sub-groups from it. Every
// rank calls each collective in the same order.
#include <mpi.h>

#include <chrono>
#include <climits>
#include <cstdlib>
#include <thread>

#include "render/rank_group.h"

namespace clpt {
namespace {

class MpiGroup final : public RankGroup {
 public:
  // `comm`: MPI_COMM_WORLD (the process group, which leaves the job in finish()) or a
  // communicator of this group's own, freed with it.
  MpiGroup(MPI_Comm comm, std::string host) : comm_(comm), host_(std::move(host)) {
    MPI_Comm_rank(comm_, &rank_);
    MPI_Comm_size(comm_, &size_);
  }
  ~MpiGroup() override {
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (comm_ != MPI_COMM_WORLD && !finalized) MPI_Comm_free(&comm_);
  }

  int rank() const override { return rank_; }
  int size() const override { return size_; }
  std::string host() const override { return host_; }

  void broadcast(std::vector<uint8_t>& bytes) override {
    unsigned long long n = bytes.size();
    MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, comm_);
    bytes.resize(size_t(n));
    for (size_t at = 0; at < bytes.size(); at += kChunk)
      MPI_Bcast(bytes.data() + at, int(std::min(kChunk, bytes.size() - at)), MPI_BYTE, 0, comm_);
  }

  // Sizes first (MPI_Gather), then each rank's bytes to rank 0 in chunks of at most kChunk
  // (MPI counts are int; a pass of a large image exceeds 2 GiB only in theory, but chunking is
  // cheap and keeps every count in range).
  std::vector<std::vector<uint8_t>> gather(const std::vector<uint8_t>& mine) override {
    unsigned long long n = mine.size();
    std::vector<unsigned long long> sizes(rank_ == 0 ? size_t(size_) : 0);
    MPI_Gather(&n, 1, MPI_UNSIGNED_LONG_LONG, sizes.data(), 1, MPI_UNSIGNED_LONG_LONG, 0, comm_);
    std::vector<std::vector<uint8_t>> all;
    if (rank_ != 0) {
      for (size_t at = 0; at < mine.size(); at += kChunk)
        MPI_Send(mine.data() + at, int(std::min(kChunk, mine.size() - at)), MPI_BYTE, 0, kTag, comm_);
      return all;
    }
    all.resize(size_t(size_));
    all[0] = mine;
    for (int r = 1; r < size_; ++r) {
      std::vector<uint8_t>& bytes = all[size_t(r)];
      bytes.resize(size_t(sizes[size_t(r)]));
      for (size_t at = 0; at < bytes.size(); at += kChunk)
        MPI_Recv(bytes.data() + at, int(std::min(kChunk, bytes.size() - at)), MPI_BYTE, r, kTag, comm_,
                 MPI_STATUS_IGNORE);
    }
    return all;
  }

  // MPI_Ibarrier, then MPI_Test every millisecond.
  void idle_barrier() override {
    MPI_Request request;
    MPI_Ibarrier(comm_, &request);
    for (int done = 0; MPI_Test(&request, &done, MPI_STATUS_IGNORE), !done;)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }

  std::unique_ptr<RankGroup> first_ranks(int n) override {
    MPI_Comm sub = MPI_COMM_NULL;
    MPI_Comm_split(comm_, rank_ < n ? 0 : MPI_UNDEFINED, rank_, &sub);
    if (sub == MPI_COMM_NULL) return nullptr;
    return std::make_unique<MpiGroup>(sub, host_);
  }

  [[noreturn]] void abort(int exit_code) override {
    MPI_Abort(MPI_COMM_WORLD, exit_code);
    std::_Exit(exit_code);  // MPI_Abort does not return; this keeps [[noreturn]] honest
  }

  void finish() override {
    if (comm_ != MPI_COMM_WORLD) return;
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized) MPI_Finalize();
  }

 private:
  static constexpr size_t kChunk = size_t(1) << 30;
  static constexpr int kTag = 17;
  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  std::string host_;
};

}  // namespace
}  // namespace clpt

extern "C" __attribute__((visibility("default"))) clpt::RankGroup* clpt_mpi_rank_group_v2(std::string* error) {
  int initialized = 0;
  MPI_Initialized(&initialized);
  // MPI_THREAD_FUNNELED: only the main thread calls MPI (the device pool's threads never do).
  int provided = 0;
  if (!initialized && MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
    *error = "MPI_Init_thread failed";
    return nullptr;
  }
  int length = 0;
  char host[MPI_MAX_PROCESSOR_NAME] = {};
  MPI_Get_processor_name(host, &length);
  return new clpt::MpiGroup(MPI_COMM_WORLD, std::string(host, size_t(length)));
}
