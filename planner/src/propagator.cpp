#include "rbsf/planner/propagator.h"

#include <array>
#include <cmath>
#include <string>

#include <ompl/control/spaces/RealVectorControlSpace.h>

#include "rbsf/dynamics/errors.h"

namespace rbsf::planner {

namespace oc = ompl::control;

SimPropagator::SimPropagator(const oc::SpaceInformationPtr& si, const Simulator& simulator,
                             const SimStateSpace& space, const DecisiveModes& rule)
    : oc::StatePropagator(si),
      simulator_(simulator),
      space_(space),
      m_(simulator.model().numFingers()),
      rule_(rule),
      ws_(simulator.model().numFingers()) {
  if (rule.settle_steps < 0)
    throw InputError("decisive modes: settle_steps must be >= 0 (got " +
                     std::to_string(rule.settle_steps) + ")");
  if (!(rule.cone_margin > 0.0 && rule.cone_margin <= 1.0))
    throw InputError("decisive modes: cone_margin must be in (0, 1] (got " +
                     std::to_string(rule.cone_margin) + ")");
}

void SimPropagator::propagate(const ompl::base::State* state, const oc::Control* control,
                              double duration, ompl::base::State* result) const {
  const auto* from = static_cast<const SimStateSpace::StateType*>(state);
  const double* u = control->as<oc::RealVectorControlSpace::ControlType>()->values;
  VecU tau(m_ + 1);
  for (int j = 0; j <= m_; ++j) tau[j] = u[j];
  SimState sim = *from->sim;  // state and result may be the same object
  const long n = std::lround(duration / simulator_.settings().time_step);
  const double mu = simulator_.model().cell().friction.mu_static;
  std::array<ContactMode, kMaxFingers> held = sim.mode;  // what settle_steps = 0 keeps
  bool decisive = true;
  long k = 0;
  while (k < n && decisive) {
    simulator_.step(sim, tau, ws_, rule_.enabled ? &report_ : nullptr);
    ++k;
    if (!sim.q.allFinite() || !sim.v.allFinite()) break;  // the validity checker refuses it
    if (!rule_.enabled || k < rule_.settle_steps) continue;
    if (k == rule_.settle_steps) {
      held = sim.mode;
      continue;
    }
    for (int i = 0; i < m_ && decisive; ++i) {
      const ContactStepReport& c = report_.contacts[i];
      decisive = c.mode == held[i] && (c.mode != ContactMode::kStick ||
                                       std::abs(c.f_t) <= rule_.cone_margin * mu * c.f_n);
    }
  }
  space_.fromSim(sim, result);
  // A refused step ends where the rule broke: its state is never used.
  static_cast<SimStateSpace::StateType*>(result)->decisive = decisive;
  indecisive_ += decisive ? 0 : 1;
  ++propagations_;
  steps_ += static_cast<std::uint64_t>(k);
}

}  // namespace rbsf::planner
