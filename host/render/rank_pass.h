// A render shared by the ranks of an MPI job (docs/mpi.md): the ranks agree on what they render,
// then trace every pass together. Rank 0 decides each pass (pass_schedule.h, plan_next_pass) and
// splits its pixels into one consecutive part per rank, sized by each rank's measured throughput
// of its last part (split_pixels_by_weight), so ranks of different speed finish a pass together.
// Each rank traces its part on its own devices (DevicePool::run_pass_part) and sends the part's
// per-pixel pass sums to rank 0, which adds them to the one film in double: each pixel receives each
// pass once, with the same pass boundaries and the same float sums as in one process, so identical
// devices give the film of one process bit for bit, whatever the number of ranks. A rank whose
// devices all fail sends its failure instead; its part goes to the ranks left, in another round of
// the same pass.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "render/fault_injection.h"
#include "render/pass_loop.h"
#include "render/rank_group.h"
#include "render/work_queue.h"
#include "util/error.h"

namespace clpt {

class DevicePool;
struct RenderPlan;
struct RenderRequest;

// An error that every rank of the job throws together, after a collective (the ranks disagree,
// every rank failed): printed by rank 0 only, and the ranks leave the job in order.
class JobError : public Error {
 public:
  using Error::Error;
};

// One rank's part in a render (RenderReport::ranks; rank 0 has every rank's).
struct RankShare {
  int rank = 0;
  std::string host;
  std::string devices;       // its devices' labels, joined with " + "
  uint64_t paths = 0;        // samples it traced
  double busy_seconds = 0;   // wall time tracing its parts of the passes
  std::string failure;       // empty: it worked to the end
};

// What must be the same on every rank, as `key: value` lines: clpt's version, the scene file's
// hash (and every mesh file's), the render settings, stopping rule, precision, and the kernel build
// options of the first device's plan without the per-device choices (the megakernel loop and scene
// loops, which --explain shows differ between a CPU and a GPU and change no image).
std::vector<std::string> render_identity(const RenderRequest& request, const RenderPlan& plan);

// Collective: rank 0 compares every rank's identity with its own. Throws JobError(Usage) on every
// rank when one differs, naming the first differing rank, its host, the key and both values.
void check_ranks_agree(RankGroup& group, const std::vector<std::string>& identity);

// `pixels` split into one consecutive part per weight, in order, each of about its weight's
// fraction of the sum (0: none; the last part with a positive weight takes the rounding). Pure.
// All weights 0: every part empty.
std::vector<PixelRange> split_pixels_by_weight(PixelRange pixels, const std::vector<double>& weights);

class RankPassTracer final : public PassTracer {
 public:
  // Collective. `pool`: this rank's devices, or null when they all failed their set-up
  // (`failure` says how); such a rank takes no part of any pass. Throws JobError(DeviceError) on
  // every rank when no rank has a working device. `image_pixels`: the image's pixel count.
  // `interrupt`: this rank's interrupt flag (sent to rank 0 with every part; may be null).
  RankPassTracer(RankGroup& group, DevicePool* pool, const std::string& failure, uint32_t image_pixels,
                 FaultPlan faults, const std::atomic<bool>* interrupt);

  bool coordinator() const override { return group_.coordinator(); }
  // Collective: rank 0's decision to every rank. Honours CLPT_INJECT_FAULT=exit:N.
  void share(PassDecision& decision) override;
  // Collective: the pass over every working rank, in rounds until every pixel is traced. An
  // adaptive pass's slots go from rank 0 to every rank first.
  void trace(const GpuRenderParams& pass, Film& film, const std::vector<GpuSampleSlot>* slots) override;
  uint32_t max_samples_per_pass(uint32_t) const override { return max_samples_per_pass_; }
  bool others_interrupted() const override { return others_interrupted_; }
  std::vector<std::string> take_notices() override;

  // Collective: every rank's part, in rank order, at rank 0 (empty on the other ranks).
  std::vector<RankShare> gather_shares();

 private:
  // What one rank sent back for its part of a round.
  struct PartResult {
    bool ok = true;
    bool interrupted = false;
    double seconds = 0;
    std::string failure;
    std::vector<GpuPixelPass> pixels;
    std::vector<float> aovs;  // the first-hit layers' sums (CLPT_AOV_CHANNELS per pixel), or none
  };
  PartResult trace_part(const GpuRenderParams& pass, PixelRange part, const std::vector<GpuSampleSlot>* slots);

  RankGroup& group_;
  DevicePool* pool_;
  FaultPlan faults_;
  const std::atomic<bool>* interrupt_;
  uint32_t max_samples_per_pass_ = UINT32_MAX;
  uint64_t passes_started_ = 0;
  bool others_interrupted_ = false;
  RankShare mine_;
  // Rank 0 only, per rank: its host, whether it still works, its last measured throughput
  // (pixel-samples/s; 0: not yet measured), and why it stopped.
  std::vector<std::string> hosts_;
  std::vector<bool> working_;
  std::vector<double> rates_;
  std::vector<std::string> failures_;  // why each rank stopped working ("" while it works)
  std::vector<std::string> notices_;
};

}  // namespace clpt
