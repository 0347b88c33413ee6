#pragma once
/// \file
/// \brief Phase-sequencing control sampler: tau from a target phase, not drawn blindly.
///
/// For a control applied at state (q, v) it draws
///   - with probability `p_random`: tau uniform within the cell's limits (exploration);
///   - else phase C with probability `p_stick / (p_stick + p_slide)`: base acceleration
///     alpha ~ U(-max_base_accel, max_base_accel) and common stroke acceleration
///     s ~ U(-max_stroke_accel, max_stroke_accel), each minus `damping` times the current
///     rate (targets relative to a damped motion, so held controls do not run away);
///     tau from PhaseTargeting::stickTau;
///   - else phase U: omega' ~ U(-max_omega_dot, max_omega_dot) - damping (phi' - theta'),
///     object accelerations -damping times the COM velocity plus a pull of `centering`
///     toward the home x (the part stays over the fingers), base acceleration as for C;
///     tau from PhaseTargeting::slideTau.
/// When the chosen phase has no solution (too few contacts) it falls back to the random
/// tau. The simulator decides the phase really taken; the plan records it.
/// Randomness from an ompl::RNG (seeded through ompl::RNG::setSeed).

#include <ompl/control/ControlSampler.h>
#include <ompl/util/RandomNumbers.h>

#include "rbsf/planner/kinodynamic/phase_targets.h"
#include "rbsf/planner/kinodynamic/state_space.h"
#include "rbsf/planner/planner_settings.h"

namespace rbsf::planner {

/// \brief OMPL ControlSampler choosing phase targets.
class PhaseControlSampler : public ompl::control::ControlSampler {
 public:
  PhaseControlSampler(const ompl::control::ControlSpace* space, const RbsfModel& model,
                      const SimStateSpace& state_space, const SamplerSettings& settings,
                      double touch_distance);

  void sample(ompl::control::Control* control) override;
  void sample(ompl::control::Control* control, const ompl::base::State* state) override;
  void sampleNext(ompl::control::Control* control, const ompl::control::Control* previous,
                  const ompl::base::State* state) override;

 private:
  void randomTau(VecU& tau);
  void write(const VecU& tau, ompl::control::Control* control) const;

  const RbsfModel& model_;
  const SimStateSpace& state_space_;
  SamplerSettings settings_;
  PhaseTargeting targeting_;
  ompl::RNG rng_;
};

}  // namespace rbsf::planner
