#pragma once
/// \file
/// \brief Whether the joints alone hold the part along a plan: at every sample, do the
///        contacts' constraint rows fix the part's pose when the joints are held
///        (contact_balance.h, joint-determined)? A cell without part sensing can run only
///        plans that are, except for short transitions (a hand-over, a touch-down).
///
/// At each sample of the plan (plan.h) a contact touches when its normal force is above
/// `touch_force` and sticks when it touches and either its slip rate |T_i^T v| is at most
/// `slip_rate`, or its point on the part moves at most `slip_rate` on average over the
/// stretches to the samples before and after (the tip keeps its material point: an
/// optimised plan's knot velocities carry slips of order h dv/dt, 1e-4 to 6e-4 m/s at the
/// 35 degree plan's 74 ms knots, where its foot points do not move); the touching and
/// sticking contacts give the sample's contact set. A
/// stretch where the set does not determine the part runs from the last determined sample
/// before it to the first one after it (or the plan's end), so a stretch is never shorter
/// than it was.

#include <string>

#include "rbsf/dynamics/core/model.h"

namespace rbsf::plan {

struct Plan;

/// \brief How the holding is judged (file comment); defaults documented.
struct HoldingSettings {
  double max_free_time = 0.1;  ///< longest stretch not joint-determined that passes [s]
  double touch_force = 1e-6;   ///< f_n above this: touching [N]
  double slip_rate = 1e-4;     ///< |T_i^T v| at most this: sticking [m/s]
};

/// \brief The plan's holding (plan file key certificate.holding).
struct PlanHolding {
  bool measured = false;          ///< false: not judged (a plan without samples, or not asked)
  double free_time = 0.0;         ///< total time of the stretches not determined [s]
  double longest_free = 0.0;      ///< the longest such stretch [s]
  double longest_free_start = 0;  ///< where it starts [s]
  double max_free_time = 0.1;     ///< what it was judged against [s]

  /// \brief Measured and no stretch longer than max_free_time.
  bool ok() const { return measured && longest_free <= max_free_time; }
};

/// \brief The holding of `plan` on `model` (file comment); not measured without samples.
PlanHolding measureHolding(const RbsfModel& model, const Plan& plan,
                           const HoldingSettings& settings = {});

/// \brief One line for reports: "holding: the joints fix the part throughout (free 0.02 s
///        in all, longest 0.01 s; allowed 0.1 s)" or "holding: NOT BY THE JOINTS ALONE: the
///        part is free for 2.3 s from t = 0.4 s (allowed 0.1 s)".
std::string holdingText(const PlanHolding& holding);

}  // namespace rbsf::plan
