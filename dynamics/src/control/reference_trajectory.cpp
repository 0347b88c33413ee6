#include "rbsf/dynamics/control/reference_trajectory.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "rbsf/dynamics/core/errors.h"

namespace rbsf {

namespace {

template <class V>
bool allFinite(const V& x) {
  return x.allFinite();
}

/// Index k of the interval [t_k, t_k+1) holding t in a sorted array of n >= 1 starts:
/// the last start <= t, at least 0. Binary search, no allocation.
int locate(const std::vector<double>& starts, double t) {
  const auto it = std::upper_bound(starts.begin(), starts.end(), t);
  return std::max(0, static_cast<int>(it - starts.begin()) - 1);
}

}  // namespace

void ReferenceTrajectory::addKnot(double t, const VecQ& q, const VecQ& v) {
  if (!std::isfinite(t) || !allFinite(q) || !allFinite(v))
    throw InputError("reference knot at t = " + std::to_string(t) + ": non-finite value");
  if (!times_.empty() && !(t > times_.back()))
    throw InputError("reference knot times must increase (t = " + std::to_string(t) + " after " +
                     std::to_string(times_.back()) + ")");
  if (q.size() != v.size() || (!q_.empty() && q.size() != q_.front().size()))
    throw InputError("reference knot at t = " + std::to_string(t) + ": q, v of wrong size");
  times_.push_back(t);
  q_.push_back(q);
  v_.push_back(v);
}

void ReferenceTrajectory::addInputPiece(double t_begin, double duration, const VecU& tau,
                                        const VecU& tau_end, Phase phase,
                                        const ContactRoles& roles) {
  const std::string where = "reference input piece " + std::to_string(piece_start_.size());
  if (!std::isfinite(t_begin) || !std::isfinite(duration) || !(duration > 0.0))
    throw InputError(where + ": duration must be positive and finite");
  if (!allFinite(tau) || !allFinite(tau_end)) throw InputError(where + ": non-finite tau");
  if (tau_end.size() != 0 && tau_end.size() != tau.size())
    throw InputError(where + ": tau_end has another size than tau");
  if (!tau_begin_.empty() && tau.size() != tau_begin_.front().size())
    throw InputError(where + ": tau has another size than the first piece's");
  if (!piece_start_.empty()) {
    const double prev_end = piece_start_.back() + piece_duration_.back();
    if (std::abs(t_begin - prev_end) > 1e-6)
      throw InputError(where + ": starts at " + std::to_string(t_begin) +
                       " s, not where the previous piece ends (" + std::to_string(prev_end) +
                       " s)");
  }
  piece_start_.push_back(t_begin);
  piece_duration_.push_back(duration);
  tau_begin_.push_back(tau);
  tau_end_.push_back(tau_end.size() == 0 ? tau : tau_end);
  held_.push_back(tau_end.size() == 0);
  phase_.push_back(phase);
  roles_.push_back(roles);
}

void ReferenceTrajectory::sample(double t, ReferenceSample& out) const {
  // Knots: cubic Hermite on the interval holding the clamped t.
  const double tc = std::clamp(t, times_.front(), times_.back());
  out.t = tc;
  const int n = static_cast<int>(times_.size());
  const int k = std::min(locate(times_, tc), n - 1);
  if (k == n - 1) {
    out.q = q_[k];
    out.v = v_[k];
  } else {
    const double d = times_[k + 1] - times_[k];
    const double s = (tc - times_[k]) / d, s2 = s * s, s3 = s2 * s;
    const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2,
                 h11 = s3 - s2;
    const double g00 = (6 * s2 - 6 * s) / d, g10 = 3 * s2 - 4 * s + 1, g01 = (-6 * s2 + 6 * s) / d,
                 g11 = 3 * s2 - 2 * s;
    out.q = h00 * q_[k] + (d * h10) * v_[k] + h01 * q_[k + 1] + (d * h11) * v_[k + 1];
    out.v = g00 * q_[k] + g10 * v_[k] + g01 * q_[k + 1] + g11 * v_[k + 1];
  }
  // Input: the piece holding t (clamped to the pieces' span), held or ramped.
  const int j = locate(piece_start_, t);
  const double s = std::clamp((t - piece_start_[j]) / piece_duration_[j], 0.0, 1.0);
  if (held_[j])
    out.tau = tau_begin_[j];  // bit-exact: open-loop replay reproduces the planner's steps
  else
    out.tau = (1.0 - s) * tau_begin_[j] + s * tau_end_[j];
  out.phase = phase_[j];
  out.roles = roles_[j];
}

}  // namespace rbsf
