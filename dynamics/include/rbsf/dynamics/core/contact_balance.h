#pragma once
/// \file
/// \brief The contact forces that carry a planned motion in a chosen contact set, with the
///        margins a plan needs to survive a drawn plant, and whether the joints alone then
///        fix the part's pose.
///
/// A contact set says which fingers touch and which of them stick; the others slide. No
/// sticking contact: the part slides on every tip; one: it pivots about that tip; two or
/// more: it moves rigidly with the base (paper 2.2: phases U, P, C). Given the state (q, v) and the
/// accelerations dv/dt of a motion in that set, the object rows of the dynamics (eq. 18)
///
///   M_o (dv/dt)_o + Q_o = sum_touching G1_i,o f_n,i + sum_sticking T_k,o f_t,k
///                         - sum_sliding mu_k sign(s_i) T_i,o f_n,i
///
/// (s_i = T_i^T v the slip rate; frictionless when mu_k = 0, eq. 8) are 3 equations on the
/// unknown forces. Among the solutions, the one chosen **maximises the margin** sigma:
///
///   f_n,i >= (normal_margin + sigma) m_o g0                 every touching contact
///   friction_use mu_s f_n,k -+ f_t,k >= sigma m_o g0        every sticking contact
///   |tau_j| <= limit_j,  tau = M_R (dv/dt)_R + Q_R - [G1 T]_R lambda   (mechanism rows)
///
/// an exact linear program (solveLp), over the forces the plant can make (least_norm): its
/// rule picks the least-norm forces among the statically indeterminate ones, so a force
/// combination N z = 0 (N the force columns over all coordinates: one that no actuator and
/// not the part feel, such as the lateral squeeze of three sticking tips) stays at zero:
/// z^T lambda = 0. The set is **balanced** when sigma >= 0: every
/// touching contact pressed by at least normal_margin of the part's weight and the sticking
/// forces inside cones shrunk to friction_use mu_s, so a plant with 20 % less friction or a
/// few per cent more mass keeps the same contact modes. The default 0.45 leaves more than
/// the 0.8 a 20 % draw needs: with three tips touching the split of the forces is not the
/// LP's but the plant's (statically indeterminate), and at 0.6 the support plans of the
/// default cell lost 3-8 of 32 trials to low-friction draws, at 0.45 none.
///
/// **Joint-determined**: the rows of the set (2 per sticking contact, 1 per sliding one)
/// fix the part's 3 degrees of freedom when the finger joints are held, i.e. their object
/// blocks [f; c x f] (moment rows divided by the part's bounding radius) have rank 3 with a
/// smallest singular value at least determined_ratio of the largest. A part on two
/// frictionless tips (2 rows) is not: it balances like an inverted pendulum that only part
/// feedback can hold.
///
/// Units SI (N, N m, m, rad); frames: world frame B (docs/model.md). Analysis-time code: it
/// allocates; one ContactBalancer per thread.

#include <cstdint>

#include <Eigen/Core>

#include "rbsf/dynamics/core/model.h"
#include "rbsf/dynamics/core/model_data.h"
#include "rbsf/dynamics/core/phase.h"

namespace rbsf {

/// \brief Which fingers touch and which of them stick (the others slide).
struct ContactSet {
  std::uint32_t touching = 0;  ///< bit i set: finger i touches
  std::uint32_t sticking = 0;  ///< bit i set: finger i sticks (a subset of touching)

  /// \brief True when finger i touches.
  bool touches(int i) const { return (touching >> i) & 1u; }
  /// \brief True when finger i sticks.
  bool sticks(int i) const { return (sticking >> i) & 1u; }
  /// \brief Number of touching fingers.
  int count() const { return bitCount(touching); }
  /// \brief Number of sticking fingers.
  int stickingCount() const { return bitCount(sticking); }
  /// \brief The one sticking finger of a pivot, -1 unless exactly one sticks.
  int pivot() const;
  /// \brief The planned phase (paper 2.2): U none sticks, P one, C two or more.
  Phase phase() const;
  /// \brief Constraint rows: 2 for each sticking contact, 1 for each sliding one.
  int rows() const { return count() + stickingCount(); }
  static int bitCount(std::uint32_t bits);
  bool operator==(const ContactSet& o) const {
    return touching == o.touching && sticking == o.sticking;
  }
  bool operator!=(const ContactSet& o) const { return !(*this == o); }
};

/// \brief Margins of contactBalance() (file comment).
struct BalanceSettings {
  double normal_margin = 0.08;     ///< every touching f_n >= this x m_o g0 [N/N]
  double friction_use = 0.45;      ///< sticking |f_t| <= this x mu_s f_n
  double determined_ratio = 0.05;  ///< smallest / largest singular value of the object rows
  double slip_rate = 1e-4;         ///< |T_i^T v| above this picks the kinetic friction sign [m/s]
  /// \brief A slider starting from rest must be able to pull this x mu_s f_n (breakaway())
  ///        while the sticking contacts keep friction_use: 1.2 (the certificate's +20 % mu_s
  ///        draws) refuses the certified 30 degree plan's pivot, which holds those draws.
  double breakaway = 1.0;
  /// \brief Only forces the plant's rule makes (docs/model.md: the least-norm forces among
  ///        the statically indeterminate ones): no internal force that no actuator feels.
  ///        Three sticking tips hold with the squeeze the plant gives them, not any squeeze.
  bool least_norm = true;
};

/// \brief Forces, input and margins of one contact set at one state.
struct ContactBalance {
  bool solvable = false;    ///< forces meeting the equations and the input limits exist
  bool balanced = false;    ///< solvable and margin >= 0
  bool determined = false;  ///< the set's rows fix the part when the joints are held
  double margin = 0.0;      ///< sigma of the file comment (fraction of m_o g0); -inf if unsolvable
  VecC fn;                  ///< normal forces per finger (0 where not touching) [N]
  VecC ft;                  ///< tangential forces per finger along t_i [N]
  VecU tau;                 ///< the input that applies them (order of state_layout.h)
};

/// \brief Solves the margin LP of the file comment; one per thread.
class ContactBalancer {
 public:
  explicit ContactBalancer(const RbsfModel& model, BalanceSettings settings = {});

  /// \brief The forces of `set` carrying (q, v, dv/dt). Updates `data` (contacts and
  ///        velocity products at q, v).
  ContactBalance solve(const VecQ& q, const VecQ& v, const VecQ& vdot, const ContactSet& set,
                       ModelData& data) const;

  /// \brief The static case: v = 0, dv/dt = 0, with `slip` (may be empty) the direction of
  ///        each sliding contact's planned slip (its sign picks the kinetic friction).
  ContactBalance statics(const VecQ& q, const ContactSet& set, ModelData& data,
                         const VecC& slip = VecC()) const;

  /// \brief The static case at the instant a motion in `set` starts from rest: each sliding
  ///        contact with a planned slip (`slip`, as in statics()) is still held by static
  ///        friction and must break away first, so its tangential force is at
  ///        `breakaway` mu_s f_n against its slip (however small) while the sticking
  ///        contacts stay inside their cones. Balanced: the sliders break away before any
  ///        sticking contact does.
  ContactBalance breakaway(const VecQ& q, const ContactSet& set, ModelData& data,
                           const VecC& slip) const;

  /// \brief Whether the rows of `set` fix the part with the joints held (file comment), at
  ///        the contacts in `data`.
  bool determined(const ContactSet& set, const ModelData& data) const;

  const BalanceSettings& settings() const { return settings_; }

 private:
  /// statics() and breakaway(): v = 0, dv/dt = 0, an empty `slip` read as no slip.
  ContactBalance atRest(const VecQ& q, const ContactSet& set, ModelData& data, const VecC& slip,
                        double mu_slide, double min_slip) const;
  /// `mu_slide`: the friction coefficient of the sliding contacts whose |slip| exceeds
  /// `min_slip` (mu_k in motion, breakaway x mu_s at a run's start).
  ContactBalance solveWith(const VecQ& q, const VecQ& vdot, const ContactSet& set,
                           const ModelData& data, const VecC& slip, double mu_slide,
                           double min_slip) const;

  const RbsfModel& model_;
  BalanceSettings settings_;
  double weight_;
};

}  // namespace rbsf
