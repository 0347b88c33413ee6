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

#include <cstdint>

#include <ompl/control/StatePropagator.h>

#include "rbsf/dynamics/simulator.h"
#include "rbsf/planner/state_space.h"

namespace rbsf::planner {

/// \brief OMPL StatePropagator stepping the simulator.
class SimPropagator : public ompl::control::StatePropagator {
 public:
  SimPropagator(const ompl::control::SpaceInformationPtr& si, const Simulator& simulator,
                const SimStateSpace& space);

  void propagate(const ompl::base::State* state, const ompl::control::Control* control,
                 double duration, ompl::base::State* result) const override;
  bool canPropagateBackward() const override { return false; }

  /// \brief Number of propagate() calls so far.
  std::uint64_t propagations() const { return propagations_; }
  /// \brief Number of simulator steps so far.
  std::uint64_t steps() const { return steps_; }

 private:
  const Simulator& simulator_;
  const SimStateSpace& space_;
  int m_;
  mutable SimulatorWorkspace ws_;
  mutable std::uint64_t propagations_ = 0;
  mutable std::uint64_t steps_ = 0;
};

}  // namespace rbsf::planner
