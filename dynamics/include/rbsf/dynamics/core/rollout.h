#pragma once
/// \file
/// \brief The one loop that runs the simulator: the planner's segments, the optimiser's
///        schedule, a certificate's trials and rbsf-simulate all step through rollout().
///
/// From `state`, at most `steps` steps of the simulator. Before step n (n = 0, 1, ...)
/// `input(state, n, tau)` writes the input held over the step (return false to stop
/// before it); after it `observe(state, report, tau, n)` sees the new state, the step's
/// report and the input (return false to stop). Inputs are either held segments
/// (HeldInputs, below) or a control law (control_law.h) behind a lambda. Allocation-free
/// whenever the callables are.

#include <vector>

#include "rbsf/dynamics/core/simulator.h"
#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/dynamics/core/trajectory_sample.h"

namespace rbsf {

/// \brief Run the simulator (file comment). \return the number of steps taken.
template <class Input, class Observer>
long rollout(const Simulator& simulator, SimState& state, long steps, SimulatorWorkspace& ws,
             Input&& input, Observer&& observe) {
  StepReport report;
  VecU tau(simulator.model().controlDim());
  long n = 0;
  while (n < steps) {
    if (!input(static_cast<const SimState&>(state), n, tau)) break;
    simulator.step(state, tau, ws, &report);
    ++n;
    if (!observe(static_cast<const SimState&>(state), static_cast<const StepReport&>(report),
                 static_cast<const VecU&>(tau), n - 1))
      break;
  }
  return n;
}

/// \brief Depth below its start at which a part has surely left the fingers [m].
inline constexpr double kFallDepth = 1.0;

/// \brief True when the part (configuration q) is more than kFallDepth below where it
///        started (configuration start): what follows is a free fall, so runs stop there.
inline bool fellOff(const VecQ& q, const VecQ& start) {
  return q[layout::kY] < start[layout::kY] - kFallDepth;
}

/// \brief The sample of a step (trajectory_sample.h): the state after it, the input held
///        over it, its contacts' normal forces and its phase.
inline TrajectorySample trajectorySample(const SimState& state, const StepReport& report,
                                         const VecU& tau) {
  const int m = static_cast<int>(state.q.size()) - layout::configDim(0);
  TrajectorySample s;
  s.t = state.t;
  s.q = state.q;
  s.v = state.v;
  s.tau = tau;
  s.f_n.resize(m);
  for (int i = 0; i < m; ++i) s.f_n[i] = report.contacts[i].f_n;
  s.phase = report.phase;
  return s;
}

/// \brief Inputs held over whole numbers of steps, one segment after the other: the
///        form of the planner's plans and of rbsf-simulate's controls file.
class HeldInputs {
 public:
  /// \brief Segment j holds `tau[j]` for `steps[j]` steps (sizes must agree).
  HeldInputs(const std::vector<long>& steps, const std::vector<VecU>& tau)
      : steps_(steps), tau_(tau) {}

  /// \brief Total number of steps.
  long totalSteps() const {
    long total = 0;
    for (long s : steps_) total += s;
    return total;
  }
  /// \brief Segment of the step last asked for.
  std::size_t segment() const { return segment_; }
  /// \brief True when step n is the last of its segment (after operator() for n).
  bool endsSegment(long n) const {
    return segment_ < steps_.size() && n + 1 == start_ + steps_[segment_];
  }

  /// \brief The rollout input: the tau of the segment holding step n (n increasing).
  bool operator()(const SimState&, long n, VecU& tau) {
    while (segment_ < steps_.size() && n >= start_ + steps_[segment_]) start_ += steps_[segment_++];
    if (segment_ >= steps_.size()) return false;
    tau = tau_[segment_];
    return true;
  }

 private:
  const std::vector<long>& steps_;
  const std::vector<VecU>& tau_;
  std::size_t segment_ = 0;
  long start_ = 0;  ///< first step of segment_
};

}  // namespace rbsf
