#include "rbsf/dynamics/core/phase.h"

#include <cmath>

namespace rbsf {

std::string_view toString(Phase phase) {
  switch (phase) {
    case Phase::kC:
      return "C";
    case Phase::kP:
      return "P";
    case Phase::kU:
      return "U";
    case Phase::kUnsupported:
      return "unsupported";
  }
  return "?";
}

PhaseClassification classifyPhase(const RbsfModel& model, const VecQ& q, const VecQ& v,
                                  const VecU& tau, ModelData& data, const PhaseTolerances& tol) {
  const int m = model.numFingers();
  PhaseClassification out;
  bool may_stick[kMaxFingers];
  for (int i = 0; i < m; ++i) {
    may_stick[i] = std::abs(data.T.col(i).dot(v)) <= tol.slip_speed;
    out.sticking += may_stick[i] ? 1 : 0;
  }
  // Paper 2.2: two sticking contacts make every contact stick, so C needs all of them.
  if (m >= 2 && out.sticking == m) {
    out.stick = solvePhaseC(model, q, v, tau, data);
    if (out.stick.feasible) {
      out.phase = Phase::kC;
      return out;
    }
  }
  for (int i = 0; i < m; ++i) {
    if (!may_stick[i]) continue;
    StickSolution p = solvePhaseP(model, q, v, tau, i, data);
    if (p.feasible) {
      out.phase = Phase::kP;
      out.stick = std::move(p);
      return out;
    }
  }
  out.phase = Phase::kU;
  return out;
}

}  // namespace rbsf
