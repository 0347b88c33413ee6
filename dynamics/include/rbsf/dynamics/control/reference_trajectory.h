#pragma once
/// \file
/// \brief A reference trajectory for tracking: joint and object positions q_ref(t) and
///        velocities v_ref(t) interpolated between knots, the feed-forward input tau(t)
///        and the planned phase, sampled without allocation in O(log n).
///
/// Knots (t_k, q_k, v_k), t strictly increasing. On [t_k, t_k+1], with d = t_k+1 - t_k and
/// s = (t - t_k) / d, q_ref is the cubic Hermite interpolant
///
///   q_ref(t) = h00(s) q_k + d h10(s) v_k + h01(s) q_k+1 + d h11(s) v_k+1,
///   h00 = 2s^3 - 3s^2 + 1, h10 = s^3 - 2s^2 + s, h01 = -2s^3 + 3s^2, h11 = s^3 - s^2,
///
/// which passes through q_k with slope v_k at every knot (C^1), and v_ref = d q_ref / dt
/// exactly (so v_ref is continuous too, but it is not v interpolated linearly).
///
/// Input pieces [t_j, t_j + T_j) in time order, contiguous: tau(t) = tau_j held, or
/// ramped linearly from tau_j to tau_end_j over the piece (PlanSegment's two forms), with
/// the piece's planned phase and, when the plan states them, its contacts' roles
/// (contact_roles.h). Outside [front, back] t is clamped: before the start the
/// reference is the first knot and the first tau; after the end the last knot (its
/// velocity) and the last piece's final tau.
///
/// A reference is built once (from a plan by plan/plan_reference.h) and then only read:
/// one reference may serve many threads.

#include <vector>

#include "rbsf/dynamics/core/contact_roles.h"
#include "rbsf/dynamics/core/phase.h"
#include "rbsf/dynamics/core/types.h"

namespace rbsf {

/// \brief The reference at one instant (sized by ReferenceTrajectory::sample).
struct ReferenceSample {
  double t = 0.0;           ///< the (clamped) time sampled [s]
  VecQ q;                   ///< q_ref, order of state_layout.h
  VecQ v;                   ///< v_ref = d q_ref / dt
  VecU tau;                 ///< feed-forward input, order of state_layout.h
  Phase phase = Phase::kC;  ///< planned phase of the input piece containing t
  ContactRoles roles{};     ///< its contacts' planned roles (kUnplanned when not stated)
};

/// \brief Knots of (q, v) and pieces of tau(t); see the file comment for the equations.
class ReferenceTrajectory {
 public:
  /// \brief Append a knot. \throws InputError when t does not increase, a value is not
  ///        finite, or q, v differ in size from the first knot.
  void addKnot(double t, const VecQ& q, const VecQ& v);

  /// \brief Append an input piece starting at the end of the previous one (the first at
  ///        `t_begin`; later `t_begin` must equal the previous end within 1e-6 s).
  ///        `tau_end` empty: tau held; otherwise a linear ramp from `tau` to `tau_end`.
  ///        `roles`: the contacts' planned roles over the piece, when stated.
  /// \throws InputError for a non-positive duration, a gap or overlap, non-finite values
  ///         or sizes that differ from the first piece.
  void addInputPiece(double t_begin, double duration, const VecU& tau, const VecU& tau_end,
                     Phase phase, const ContactRoles& roles = ContactRoles{});

  /// \brief Fill `out` with the reference at t (clamped to [startTime(), endTime()]).
  ///        Allocation-free after `out` has once been sized (its vectors are fixed-capacity
  ///        anyway). \pre at least one knot and one input piece.
  void sample(double t, ReferenceSample& out) const;

  /// \brief First and last knot time [s] (0 when empty).
  double startTime() const { return times_.empty() ? 0.0 : times_.front(); }
  double endTime() const { return times_.empty() ? 0.0 : times_.back(); }
  /// \brief Number of knots and of input pieces.
  int numKnots() const { return static_cast<int>(times_.size()); }
  int numPieces() const { return static_cast<int>(piece_start_.size()); }
  /// \brief True when both knots and input pieces are present.
  bool ready() const { return !times_.empty() && !piece_start_.empty(); }

 private:
  std::vector<double> times_;
  std::vector<VecQ> q_, v_;
  std::vector<double> piece_start_, piece_duration_;
  std::vector<VecU> tau_begin_, tau_end_;  // tau_end_ == tau_begin_ for held pieces
  std::vector<char> held_;                 // 1: tau_begin_ returned as is
  std::vector<Phase> phase_;
  std::vector<ContactRoles> roles_;
};

}  // namespace rbsf
