#pragma once

// Runs one render phase's independent tasks on the thread pool, times the phase, and turns
// its finished tasks into the progress fraction the caller's callback sees.

#include <chrono>
#include <cstddef>
#include <functional>
#include <utility>

#include "FunctionRef.h"
#include "ThreadPool.h"
#include "facet/RenderPlan.h"

namespace facet::detail {

enum class Phase { Validate, Measure, Transform, Sort, Setup, Raster, Shade, Resolve };
inline constexpr int kPhaseCount = 8;

// Each phase's share of a full render, for the progress fractions: roughly its share of the
// time of a 2M-triangle sphere at 1920 × 1080 (validate 5 %, transform 15 %, set-up 40 %,
// raster 20 %, shade 10 %, resolve 5 %; the painter's sort, when it runs, about 5 %; a new
// version's measurement about as long as its validation).
inline constexpr double kPhaseWeights[kPhaseCount] = {0.05, 0.05, 0.15, 0.05,
                                                      0.40, 0.20, 0.10, 0.05};

// The phases one render runs: the incremental paths run only the last ones.
class PhaseSet {
 public:
  constexpr PhaseSet() = default;
  constexpr PhaseSet(std::initializer_list<Phase> phases) {
    for (Phase phase : phases)
      bits_ |= bit(phase);
  }
  constexpr bool has(Phase phase) const { return (bits_ & bit(phase)) != 0; }

 private:
  static constexpr unsigned bit(Phase phase) { return 1u << static_cast<int>(phase); }
  unsigned bits_ = 0;
};

// The phases each path runs (RenderPath): the incremental paths run only the last ones.
constexpr PhaseSet phasesOf(RenderPath path) {
  switch (path) {
    case RenderPath::Full:
      return {Phase::Validate, Phase::Measure, Phase::Transform, Phase::Sort,
              Phase::Setup,    Phase::Raster,  Phase::Shade,     Phase::Resolve};
    case RenderPath::Reshade:
      return {Phase::Shade, Phase::Resolve};
    case RenderPath::Resolve:
      break;
  }
  return {Phase::Resolve};
}

class PhaseRunner {
 public:
  using Clock = std::chrono::steady_clock;
  using ProgressCallback = std::function<bool(double fraction)>;

  PhaseRunner(ThreadPool& pool, const ProgressCallback& callback, PhaseSet phases)
      : pool_(pool), callback_(callback), phases_(phases) {
    for (int p = 0; p < kPhaseCount; ++p)
      total_ += phases.has(static_cast<Phase>(p)) ? kPhaseWeights[p] : 0.0;
  }

  // Runs task(i) for i in [0, tasks) on every thread. False when the callback asked to stop
  // (then no further task starts). The phase's start is always reported: workers may take
  // every task, leaving the caller none to report after.
  // `first`: tasks that all finish before any of `task`'s starts (FirstStage), in the
  // same job: no wake-up of the workers of their own.
  template <class Task>
  bool run(Phase phase, std::size_t tasks, Task&& task, FirstStage first = {}) {
    const double begin = fractionBefore(phase);
    const double end = begin + share(phase);
    const std::size_t count = tasks == 0 ? 1 : tasks;
    // Exactly the end when all are done, so fractions never step back at the next phase.
    auto report = [&](std::size_t done) {
      return !callback_ ||
             callback_(done >= count ? end : begin + (end - begin) * double(done) / double(count));
    };
    if (!report(0)) return false;
    FunctionRef<void(std::size_t)> taskRef(task);
    return pool_.run(tasks, taskRef, FunctionRef<bool(std::size_t)>(report), first);
  }

  // Runs task(i) for i in [0, tasks) on every thread as part of the phase that follows
  // (no progress of its own, so the fractions never step back; not cancellable: the work
  // is short).
  template <class Task>
  void runUnreported(std::size_t tasks, Task&& task, FirstStage first = {}) {
    FunctionRef<void(std::size_t)> taskRef(task);
    pool_.run(tasks, taskRef, {}, first);
  }

  // Seconds since the previous lap (or since the runner was made), for the phase timings.
  double lap() {
    const Clock::time_point now = Clock::now();
    return std::chrono::duration<double>(now - std::exchange(lapStart_, now)).count();
  }
  double secondsSinceStart() const {
    return std::chrono::duration<double>(Clock::now() - start_).count();
  }
  // Reports the end of a render that completed.
  void finish() const {
    if (callback_) callback_(1.0);
  }

 private:
  double share(Phase phase) const {
    return phases_.has(phase) ? kPhaseWeights[static_cast<int>(phase)] / total_ : 0.0;
  }
  double fractionBefore(Phase phase) const {
    double sum = 0.0;
    for (int p = 0; p < static_cast<int>(phase); ++p)
      sum += share(static_cast<Phase>(p));
    return sum;
  }

  ThreadPool& pool_;
  const ProgressCallback& callback_;
  PhaseSet phases_;
  double total_ = 0.0;
  Clock::time_point start_ = Clock::now();
  Clock::time_point lapStart_ = start_;
};

}  // namespace facet::detail
