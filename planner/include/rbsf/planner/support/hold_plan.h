#pragma once
/// \file
/// \brief The part held at rest where it is: the contact set that holds it best, the other
///        fingers lifted clear.
///
/// Candidates: every set of two or more fingers touching the part at q0, all sticking (at
/// rest every tip sticks). Each is balanced by ContactBalancer::statics (contact_balance.h:
/// the plant's least-norm forces, friction use and normal margins); the set kept is the one
/// with the largest margin among those the joints alone hold (determined). Three sticking
/// tips are often worse than two: the lateral squeeze no actuator steers loads a tilted tip
/// towards its cone's edge.
///
/// The reference keeps the part at q0; each finger outside the set retracts by `lift` over
/// `lift_time` (quintic, rest to rest) and stays there. Its roles (contact_roles.h): S for the
/// set, L for the others; its input: the set's balance (a lifted finger carries its weight).
/// The plan is that reference run once closed loop on the nominal cell
/// (support_trajectory.h closedLoopPlan): exact, held by the joints alone.

#include "rbsf/dynamics/control/feedback_schedule.h"
#include "rbsf/dynamics/core/contact_balance.h"
#include "rbsf/plan/plan.h"

namespace rbsf::planner {

/// \brief Settings of holdPlan() (file comment).
struct HoldSettings {
  double duration = 3.0;    ///< of the rest [s]
  double lift = 0.005;      ///< a lifted finger's retraction [m]
  double lift_time = 0.3;   ///< [s]
  BalanceSettings balance;  ///< the candidates' margins
  FeedbackSettings feedback;
  SimulatorSettings simulator;
};

/// \brief The contact set holdPlan() holds the part on at q0 (bit i: finger i), 0 when none
///        of the candidates is balanced and determined.
std::uint32_t bestHoldingSet(const RbsfModel& model, const VecQ& q0,
                             const BalanceSettings& balance);

/// \brief The rest of the file comment. \throws InputError when no set holds the part at q0.
plan::Plan holdPlan(const RbsfModel& model, const VecQ& q0, const HoldSettings& settings = {});

}  // namespace rbsf::planner
