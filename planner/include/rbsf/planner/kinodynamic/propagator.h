#pragma once
/// \file
/// \brief The state propagator: the hybrid contact simulator (simulator.h).
///
/// A control is tau (order of state_layout.h), held constant. OMPL's propagation step is
/// an integer number k of simulator steps h (SpaceInformation::setPropagationStepSize(k h));
/// propagate() runs round(duration / h) steps from the state's carried SimState, so chained
/// propagations are the same computation as one long simulation. The result's SimState and
/// vector are set together. Counts simulator steps and propagate() calls (single-threaded
/// planners; the counters are plain integers).
///
/// Decisive contact modes (DecisiveModes, on by default). A plan is run by a cell under
/// feedback (control_law.h), never exactly its open-loop torques. Where the plan has a
/// contact creep from sticking into sliding, stick at the edge of its cone, or change mode
/// in the middle of a held torque, the feedback's corrections of a few micrometres decide
/// that contact's mode differently, and the part leaves the planned path (measured under
/// joint tracking: a one-phase pivot fails within 0.1 s with a 10 um reference error).
/// So a propagation step counts only if,
/// after its first `settle_steps` simulator steps (where a new torque may switch modes at once),
///   - every contact keeps the mode (stick, slide, separated) it has then, and
///   - every sticking contact keeps |f_t| <= cone_margin mu_s f_n.
/// A step that breaks either marks its result state (StateType::decisive = false), which
/// the validity checker refuses, so OMPL's propagateWhileValid ends the control before it.
///
/// Motion limits (when given, as the planner does by default): a heavy part is handled
/// slowly, so a propagation step counts only if at every simulator step the part's speed
/// |(x', y')| is at most MotionLimits::part_speed and |phi'| at most angular_speed. A step
/// that breaks them ends there and is refused the same way, so every state of a plan built
/// from counted steps is within the limits.

#include <cstdint>
#include <optional>

#include <ompl/control/StatePropagator.h>

#include "rbsf/dynamics/core/motion_limits.h"
#include "rbsf/dynamics/core/simulator.h"
#include "rbsf/planner/kinodynamic/state_space.h"
#include "rbsf/planner/planner_settings.h"

namespace rbsf::planner {

/// \brief OMPL StatePropagator stepping the simulator.
class SimPropagator : public ompl::control::StatePropagator {
 public:
  /// \throws InputError for settle_steps < 0 or a cone_margin outside (0, 1].
  SimPropagator(const ompl::control::SpaceInformationPtr& si, const Simulator& simulator,
                const SimStateSpace& space, const DecisiveModes& rule = {},
                const MotionLimits* limits = nullptr);

  void propagate(const ompl::base::State* state, const ompl::control::Control* control,
                 double duration, ompl::base::State* result) const override;
  bool canPropagateBackward() const override { return false; }

  /// \brief Number of propagate() calls so far.
  std::uint64_t propagations() const { return propagations_; }
  /// \brief Number of simulator steps so far.
  std::uint64_t steps() const { return steps_; }
  /// \brief Number of propagation steps refused by the decisive-modes rule so far.
  std::uint64_t indecisive() const { return indecisive_; }
  /// \brief The decisive-modes rule it applies.
  const DecisiveModes& rule() const { return rule_; }

 private:
  const Simulator& simulator_;
  const SimStateSpace& space_;
  int m_;
  DecisiveModes rule_;
  std::optional<MotionLimits> limits_;  ///< none: only the decisive-modes rule
  mutable SimulatorWorkspace ws_;
  mutable std::uint64_t propagations_ = 0;
  mutable std::uint64_t steps_ = 0;
  mutable std::uint64_t indecisive_ = 0;
};

}  // namespace rbsf::planner
