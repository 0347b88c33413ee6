#pragma once
/// \file
/// \brief The planner's OMPL state space: the simulator's full state.
///
/// Layout of the real vector (dimension 2 (m + 4)), the order of state_layout.h twice:
/// | entries          | meaning                                              |
/// |------------------|------------------------------------------------------|
/// | 0 .. m+3         | q = (x, y, phi, theta, l_1..l_m): object pose, base angle, strokes |
/// | m+4 .. 2m+7      | v = dq/dt, same order                                |
/// Bounds: x, y within the reach of the fingers (box around the base, from the cell's
/// strokes and finger offsets), phi within +-4 pi (angles are never wrapped), theta and
/// the strokes within the cell's limits (plus a small tolerance), rates within the
/// planner's speed bounds.
///
/// Besides the vector, every state carries the simulator's SimState (friction memory,
/// anchors, closest-point hints, solver guesses) of the step that produced it, so that
/// propagating from a tree state continues the simulation bit-exactly: re-simulating a
/// plan's tau segments from the start reproduces the planner's states. Distance,
/// interpolation, equality and samplers use the vector (q, v) only; copyState copies both.

#include <ompl/base/spaces/RealVectorStateSpace.h>

#include "rbsf/dynamics/core/simulator.h"
#include "rbsf/planner/planner_settings.h"

namespace rbsf::planner {

/// \brief RealVectorStateSpace over (q, v) whose states also hold a SimState.
class SimStateSpace : public ompl::base::RealVectorStateSpace {
 public:
  /// \brief The state: values = (q, v); `sim` the simulator state whose q, v equal them.
  class StateType : public ompl::base::RealVectorStateSpace::StateType {
   public:
    SimState* sim = nullptr;  ///< owned; allocated with the state
    /// \brief false: the propagation step into this state broke the decisive-modes rule
    ///        or the motion limits (propagator.h); the validity checker refuses it.
    bool decisive = true;
  };

  SimStateSpace(const RbsfModel& model, const SpeedBounds& speed);

  int numFingers() const { return m_; }

  ompl::base::State* allocState() const override;
  void freeState(ompl::base::State* state) const override;
  void copyState(ompl::base::State* destination, const ompl::base::State* source) const override;

  /// \brief Set the state from a SimState (vector and carried simulator state).
  void fromSim(const SimState& sim, ompl::base::State* state) const;
  /// \brief q and v of a state's vector.
  VecQ q(const ompl::base::State* state) const;
  VecQ v(const ompl::base::State* state) const;

 private:
  int m_;
};

}  // namespace rbsf::planner
