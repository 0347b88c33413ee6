#include "rbsf/planner/kinodynamic/propagator.h"

#include <array>
#include <cmath>
#include <string>

#include <ompl/control/spaces/RealVectorControlSpace.h>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/core/rollout.h"
#include "rbsf/dynamics/core/state_layout.h"

namespace rbsf::planner {

namespace oc = ompl::control;

SimPropagator::SimPropagator(const oc::SpaceInformationPtr& si, const Simulator& simulator,
                             const SimStateSpace& space, const DecisiveModes& rule,
                             const MotionLimits* limits)
    : oc::StatePropagator(si),
      simulator_(simulator),
      space_(space),
      m_(simulator.model().numFingers()),
      rule_(rule),
      limits_(limits != nullptr ? std::optional<MotionLimits>(*limits) : std::nullopt),
      ws_(simulator.model().numFingers()) {
  checkSettings(rule);
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
  bool decisive = true, slow = true;
  const bool rule = rule_.enabled;
  const long k = rollout(
      simulator_, sim, n, ws_,
      [&](const SimState&, long, VecU& in) {
        in = tau;
        return true;
      },
      [&](const SimState& now, const StepReport& report, const VecU&, long step) {
        if (!now.q.allFinite() || !now.v.allFinite()) return false;  // the checker refuses it
        if (limits_ && (std::hypot(now.v[layout::kX], now.v[layout::kY]) > limits_->part_speed ||
                        std::abs(now.v[layout::kPhi]) > limits_->angular_speed)) {
          slow = false;
          return false;
        }
        const long done = step + 1;
        if (!rule || done < rule_.settle_steps) return true;
        if (done == rule_.settle_steps) {
          held = now.mode;
          return true;
        }
        for (int i = 0; i < m_ && decisive; ++i) {
          const ContactStepReport& c = report.contacts[i];
          decisive = c.mode == held[i] && (c.mode != ContactMode::kStick ||
                                           std::abs(c.f_t) <= rule_.cone_margin * mu * c.f_n);
        }
        return decisive;
      });
  space_.fromSim(sim, result);
  // A refused step ends where the rule broke: its state is never used.
  static_cast<SimStateSpace::StateType*>(result)->decisive = decisive && slow;
  indecisive_ += decisive ? 0 : 1;
  ++propagations_;
  steps_ += static_cast<std::uint64_t>(k);
}

}  // namespace rbsf::planner
