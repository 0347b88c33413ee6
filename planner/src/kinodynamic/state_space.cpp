#include "rbsf/planner/kinodynamic/state_space.h"

#include <algorithm>
#include <cmath>

#include "rbsf/dynamics/core/state_layout.h"

namespace rbsf::planner {

namespace ob = ompl::base;

SimStateSpace::SimStateSpace(const RbsfModel& model, const SpeedBounds& speed)
    : ob::RealVectorStateSpace(2 * model.configDim()), m_(model.numFingers()) {
  setName("RbsfSimState");
  const Cell& cell = model.cell();
  const int n = model.configDim();
  double reach = 0.0;  // farthest fingertip from the base axis
  for (const FingerParams& f : cell.fingers) reach = std::max(reach, std::hypot(f.r, f.stroke_max));
  const double object_extent = cell.object.shape->boundingRadius();
  const double box = reach + 2.0 * object_extent;
  ob::RealVectorBounds b(2 * n);
  const double tol = 1e-3;
  b.setLow(layout::kX, -box);
  b.setHigh(layout::kX, box);
  b.setLow(layout::kY, -box);
  b.setHigh(layout::kY, box);
  b.setLow(layout::kPhi, -4.0 * M_PI);
  b.setHigh(layout::kPhi, 4.0 * M_PI);
  b.setLow(layout::kTheta, cell.base.theta_min - tol);
  b.setHigh(layout::kTheta, cell.base.theta_max + tol);
  for (int i = 0; i < m_; ++i) {
    b.setLow(layout::stroke(i), cell.fingers[i].stroke_min - tol);
    b.setHigh(layout::stroke(i), cell.fingers[i].stroke_max + tol);
  }
  for (int k = 0; k < n; ++k) {
    const bool angular = k == layout::kPhi || k == layout::kTheta;
    const double s = angular ? speed.angular : speed.linear;
    b.setLow(n + k, -s);
    b.setHigh(n + k, s);
  }
  setBounds(b);
}

ob::State* SimStateSpace::allocState() const {
  auto* state = new StateType();
  state->values = new double[dimension_]();
  const VecQ zero = VecQ::Zero(m_ + 4);
  state->sim = new SimState(zero, zero);
  return state;
}

void SimStateSpace::freeState(ob::State* state) const {
  auto* s = static_cast<StateType*>(state);
  delete s->sim;
  delete[] s->values;
  delete s;
}

void SimStateSpace::copyState(ob::State* destination, const ob::State* source) const {
  auto* d = static_cast<StateType*>(destination);
  const auto* s = static_cast<const StateType*>(source);
  std::copy(s->values, s->values + dimension_, d->values);
  *d->sim = *s->sim;
  d->decisive = s->decisive;
}

void SimStateSpace::fromSim(const SimState& sim, ob::State* state) const {
  auto* s = static_cast<StateType*>(state);
  const int n = m_ + 4;
  for (int k = 0; k < n; ++k) {
    s->values[k] = sim.q[k];
    s->values[n + k] = sim.v[k];
  }
  *s->sim = sim;
  s->decisive = true;
}

VecQ SimStateSpace::q(const ob::State* state) const {
  const auto* s = static_cast<const StateType*>(state);
  return Eigen::Map<const Eigen::VectorXd>(s->values, m_ + 4);
}

VecQ SimStateSpace::v(const ob::State* state) const {
  const auto* s = static_cast<const StateType*>(state);
  return Eigen::Map<const Eigen::VectorXd>(s->values + m_ + 4, m_ + 4);
}

}  // namespace rbsf::planner
