#include "rbsf/planner/kinodynamic/validity.h"

#include <ompl/base/SpaceInformation.h>

#include "rbsf/dynamics/core/state_layout.h"

namespace rbsf::planner {

SupportValidityChecker::SupportValidityChecker(const ompl::base::SpaceInformationPtr& si,
                                               const RbsfModel& model,
                                               const ValiditySettings& settings)
    : ompl::base::StateValidityChecker(si),
      model_(model),
      settings_(settings),
      data_(model.numFingers()) {}

int SupportValidityChecker::touching(const VecQ& q, const VecC& hint) const {
  data_.xi_hint = hint;
  model_.updateContacts(q, data_);
  int k = 0;
  for (int i = 0; i < model_.numFingers(); ++i)
    if (data_.contacts[i].gap <= settings_.touch_distance) ++k;
  return k;
}

bool SupportValidityChecker::supported(const VecQ& q, const VecC& hint) const {
  if (q[layout::kY] < settings_.min_height) return false;
  if (touching(q, hint) < settings_.min_touching) return false;
  for (int i = 0; i < model_.numFingers(); ++i)
    if (data_.contacts[i].gap < -settings_.penetration_tolerance) return false;
  return true;
}

bool SupportValidityChecker::isValid(const ompl::base::State* state) const {
  const auto* s = static_cast<const SimStateSpace::StateType*>(state);
  const SimState& sim = *s->sim;
  if (!s->decisive) return false;
  if (!sim.q.allFinite() || !sim.v.allFinite()) return false;
  if (!si_->satisfiesBounds(state)) return false;
  return supported(sim.q, sim.xi_hint);
}

}  // namespace rbsf::planner
