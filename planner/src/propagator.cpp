#include "rbsf/planner/propagator.h"

#include <cmath>

#include <ompl/control/spaces/RealVectorControlSpace.h>

namespace rbsf::planner {

namespace oc = ompl::control;

SimPropagator::SimPropagator(const oc::SpaceInformationPtr& si, const Simulator& simulator,
                             const SimStateSpace& space)
    : oc::StatePropagator(si),
      simulator_(simulator),
      space_(space),
      m_(simulator.model().numFingers()),
      ws_(simulator.model().numFingers()) {}

void SimPropagator::propagate(const ompl::base::State* state, const oc::Control* control,
                              double duration, ompl::base::State* result) const {
  const auto* from = static_cast<const SimStateSpace::StateType*>(state);
  const double* u = control->as<oc::RealVectorControlSpace::ControlType>()->values;
  VecU tau(m_ + 1);
  for (int j = 0; j <= m_; ++j) tau[j] = u[j];
  SimState sim = *from->sim;  // state and result may be the same object
  const long n = std::lround(duration / simulator_.settings().time_step);
  for (long k = 0; k < n; ++k) {
    simulator_.step(sim, tau, ws_);
    if (!sim.q.allFinite() || !sim.v.allFinite()) break;  // the validity checker refuses it
  }
  space_.fromSim(sim, result);
  ++propagations_;
  steps_ += static_cast<std::uint64_t>(n);
}

}  // namespace rbsf::planner
