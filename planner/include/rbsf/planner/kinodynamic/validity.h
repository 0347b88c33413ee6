#pragma once
/// \file
/// \brief State validity: the part is supported, the mechanism within its limits.
///
/// A state (q, v) is valid when
///   - every entry is finite and within the state space's bounds (base angle and strokes
///     within the cell's limits plus 1e-3, speeds within SpeedBounds);
///   - the part is supported: at least `min_touching` contacts have gap <= touch_distance
///     (the closest points are searched from the state's own SimState hints, so the test is
///     a pure function of the state), and the COM is above the base axis by `min_height`;
///   - no fingertip penetrates the part by more than `penetration_tolerance`;
///   - the propagation step into it counted (propagator.h: decisive contact modes and, by
///     default, the cell's motion limits at every simulator step).
/// Contact forces cannot exceed what the limited tau and gravity produce; the simulator's
/// forces are reported in the plan (f_n per sample).

#include <ompl/base/StateValidityChecker.h>

#include "rbsf/dynamics/core/model.h"
#include "rbsf/planner/kinodynamic/state_space.h"
#include "rbsf/planner/planner_settings.h"

namespace rbsf::planner {

/// \brief Validity checker of the planner (single-threaded: holds a ModelData).
class SupportValidityChecker : public ompl::base::StateValidityChecker {
 public:
  SupportValidityChecker(const ompl::base::SpaceInformationPtr& si, const RbsfModel& model,
                         const ValiditySettings& settings);

  bool isValid(const ompl::base::State* state) const override;
  /// \brief Contacts touching at configuration q (hints from `hint`, may be NaN).
  int touching(const VecQ& q, const VecC& hint) const;
  /// \brief The supported part of the test alone (touching, height, penetration).
  bool supported(const VecQ& q, const VecC& hint) const;

 private:
  const RbsfModel& model_;
  ValiditySettings settings_;
  mutable ModelData data_;
};

}  // namespace rbsf::planner
