#include "render/progress.h"

#include <algorithm>
#include <cstdio>

namespace clpt {

void Progress::update(int passes, uint64_t spp_done, uint64_t spp_target, double samples_per_s,
                      double elapsed_s, double time_limit_s) {
  if (!enabled_) return;
  double eta = -1;
  if (spp_target > 0 && spp_done > 0)
    eta = elapsed_s * double(spp_target - std::min(spp_done, spp_target)) / double(spp_done);
  if (time_limit_s > 0) eta = eta < 0 ? time_limit_s - elapsed_s : std::min(eta, time_limit_s - elapsed_s);
  char target[32] = "";
  if (spp_target > 0) std::snprintf(target, sizeof target, "/%llu", (unsigned long long)spp_target);
  std::fprintf(stderr, "\r  pass %d  %llu%s spp  %.2f M samples/s  elapsed %.1f s  ETA %.1f s   ",
               passes, (unsigned long long)spp_done, target, samples_per_s * 1e-6, elapsed_s,
               std::max(0.0, eta));
  std::fflush(stderr);
  drawn_ = true;
}

void Progress::finish() {
  if (enabled_ && drawn_) std::fprintf(stderr, "\n");
  drawn_ = false;
}

}  // namespace clpt
