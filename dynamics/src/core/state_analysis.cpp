#include "rbsf/dynamics/core/state_analysis.h"

#include <cmath>
#include <cstdio>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/core/forward_dynamics.h"

namespace rbsf {

StateAnalysis analyzeState(const RbsfModel& model, const VecQ& q, const VecQ& v, const VecU& tau) {
  const int m = model.numFingers();
  ModelData data(m);
  model.updateContacts(q, data);
  for (int i = 0; i < m; ++i) {
    const double gap = data.contacts[i].gap;
    if (!(std::abs(gap) <= kContactGapTolerance)) {
      char buf[200];
      std::snprintf(buf, sizeof buf,
                    "finger %d is off the object's boundary: gap %.3g m (tolerance %.0e m)", i + 1,
                    gap, kContactGapTolerance);
      throw InputError(buf);
    }
  }
  StateAnalysis out;
  forwardDynamicsU(model, q, v, tau, data);
  out.accel = data.vdot;
  out.contacts.resize(m);
  for (int i = 0; i < m; ++i) {
    ContactReport& c = out.contacts[i];
    c.xi = data.contacts[i].xi;
    c.gap = data.contacts[i].gap;
    c.normal = data.contacts[i].normal;
    c.f_n = data.fn[i];
    c.delta_n = data.delta_n[i];
    c.arms = contactArms(data, i);
  }
  out.sigma_min = smallestSingularValueG1(data);
  out.determinate = out.sigma_min > kDeterminacyThreshold;
  out.phase_c_feasible = m >= 2 && solvePhaseC(model, q, v, tau, data).feasible;
  out.phase = classifyPhase(model, q, v, tau, data);
  out.omega_dot = omegaDotRange(model, q, v, data);

  int first = 0, last = 0;
  for (int i = 0; i < m; ++i) {
    if (model.cell().fingers[i].r < model.cell().fingers[first].r) first = i;
    if (model.cell().fingers[i].r > model.cell().fingers[last].r) last = i;
    for (int j = i + 1; j < m; ++j)
      if (comBetweenNormals(data, i, j)) out.com_regions.emplace_back(i, j);
  }
  out.com_in_end_region = first != last && comBetweenNormals(data, first, last);
  out.holding = holdingTorques(model, q, data);
  return out;
}

}  // namespace rbsf
