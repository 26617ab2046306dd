#pragma once
// What one fit may still spend: the user's time budget (FitOptions::time_budget_ms: wall
// time, so where it runs out depends on the machine's load) and a limit of work, counted
// in the Jacobian entries the chain fits evaluate, where the fit gives a path a share of
// what another took. Work, unlike time, gives the same curve for the same stroke on a
// loaded machine as on an idle one (a noisy stroke's curve had 9, 8 or 3 segments from
// run to run while its chain path's share was a multiple of the time its one segment took).

#include <chrono>
#include <cstdint>
#include <limits>

namespace la {

using Clock = std::chrono::steady_clock;

/// The work a fit has done: one per fit, shared by all its budgets.
struct WorkMeter {
  std::int64_t done = 0;
};

struct Budget {
  static constexpr std::int64_t kNoLimit = std::numeric_limits<std::int64_t>::max();

  Clock::time_point deadline = Clock::time_point::max();  // max(): no time budget
  WorkMeter* meter = nullptr;                              // null: work is not counted
  std::int64_t work_limit = kNoLimit;                      // on meter->done

  bool spent() const {
    if (meter && meter->done >= work_limit) return true;
    return deadline != Clock::time_point::max() && Clock::now() >= deadline;
  }
  void charge(std::int64_t work) const {
    if (meter) meter->done += work;
  }
  /// The work done so far (0 where it is not counted).
  std::int64_t done() const { return meter ? meter->done : 0; }
};

}  // namespace la
