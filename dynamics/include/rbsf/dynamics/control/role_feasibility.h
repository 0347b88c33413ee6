#pragma once
/// \file
/// \brief Can the law do this step here? Whether the contact-force law (contact_force_qp.h),
///        at a configuration q of a slow plan, finds inputs within their limits whose
///        predicted plant forces keep every contact in its planned role, with the law's own
///        margins over the cell's stated uncertainty.
///
/// The question is put to the law's QP itself, on the same force model (the plant's
/// least-norm forces within each contact's mode, free contacts held at their cone's edge)
/// and the same rows and margins, at the part at rest (v = 0) with the plan's feed-forward
/// input there as the demand (or, without one, the input whose predicted motion is the
/// planned acceleration: ContactForceQp::solveForMotion). A step of a slow plan is one of:
///   - **hold** (no slider): every S contact sticks within friction_limit mu_s with its
///     robust margin, every relied-on contact pressed above normal_floor m_o g;
///   - **breakaway** (the sliders still stuck, `sliders_loose` false): each planned slider
///     is pulled to breakaway mu_s f_n + pull_margin m_o g against its planned slip while
///     the sticking contacts keep their cones: the plant's tips give in the planned order.
///     And the plant cannot keep the slider stuck by an internal force no actuator feels
///     (W z = 0 over the touching contacts' force columns: the squeeze of two tips at one
///     height, or of three sticking tips): the plant's contact problem picks the least-norm
///     forces inside the cones, so where some lambda + alpha z keeps every contact pressed and
///     inside its cone (the slider's at breakaway mu_s, the others' at the highest drawn
///     mu_s), the slider stays stuck however the law pulls. (Two or more such directions are
///     counted as holding it.)
///   - **slide** (`sliders_loose` true): each slider slips with kinetic friction against
///     its planned slip, the others keep their roles.
/// The answer is **yes** when the QP keeps every row (its violation sigma and breakaway
/// shortfall pi at zero), keeps the robust margins (rho >= 0: to first order, the cell's
/// mass, COM and actuator-gain uncertainty leaves the rows standing; the friction
/// uncertainty is in friction_use and breakaway), and, in a hold or a slide, the motion it
/// chooses is the planned one within `motion_tolerance` (generalized force per part weight):
/// a step the law can only keep by accelerating the part away from the plan is not one it
/// can do. (At a breakaway the part starts to move as the slider gives: the pull is the
/// question there, not the motion.)
///
/// Units SI; frames: world frame B (docs/model.md). Analysis-time code (a breakaway's
/// internal forces are found by an SVD that allocates); one per thread.

#include <cstdint>

#include "rbsf/dynamics/control/contact_force_qp.h"

namespace rbsf {

/// \brief Settings of RoleFeasibility (file comment).
struct RoleFeasibilitySettings {
  /// \brief Largest error of the chosen motion, per coordinate, as a generalized force per
  ///        part weight (moments per m_o g x 0.1 m): 0.02 is 0.2 m/s^2 on the part.
  double motion_tolerance = 0.02;
  double row_tolerance = 1e-6;  ///< sigma and pi at most this (x m_o g)
  bool robust = false;          ///< require rho >= 0 (the robust margins)
};

/// \brief Why the law cannot do a step.
enum class RoleRefusal : std::uint8_t {
  kNone = 0,   ///< it can
  kRows,       ///< a row of a role is violated (a cone, a normal floor, a lifted tip)
  kBreakaway,  ///< a planned slider cannot be pulled loose
  kMargin,     ///< the robust margins do not hold (rho < 0)
  kMotion,     ///< the roles hold only with a motion off the plan
};

/// \brief "none", "rows", "breakaway", "margin" or "motion".
const char* toString(RoleRefusal r);

/// \brief The law's answer for one step, with what it found.
struct RoleVerdict {
  bool feasible = false;
  RoleRefusal refusal = RoleRefusal::kRows;
  double violation = 0.0;     ///< sigma (x m_o g)
  double shortfall = 0.0;     ///< pi (x m_o g)
  double margin = 0.0;        ///< rho (x m_o g)
  double motion_error = 0.0;  ///< ContactForceQp::motionError
  double friction_use = 0.0;  ///< the sticking contacts' largest |f_t| / (mu_s f_n)
  VecU tau;                   ///< the input the law chooses (tau order)
  VecC fn, ft;                ///< its predicted forces per finger [N]
};

/// \brief The check of the file comment; one per thread.
class RoleFeasibility {
 public:
  /// \brief For `model` (the nominal cell) and the law's force settings `forces`
  ///        (FeedbackSettings::forces of the plan's law).
  explicit RoleFeasibility(const RbsfModel& model, const ContactForceSettings& forces = {},
                           const RoleFeasibilitySettings& settings = {});

  /// \brief The law's answer at q, the part at rest, for `roles` (S, +, -, L, F; kUnplanned
  ///        is refused as kRows): a breakaway when some role slides and `sliders_loose` is
  ///        false, a slide when it is true, a hold without sliders. `feedforward` (may be
  ///        empty) the plan's input there, the law's demand; `vdot` (may be empty: zero) the
  ///        planned accelerations.
  RoleVerdict check(const VecQ& q, const ContactRoles& roles, bool sliders_loose,
                    const VecU& feedforward = VecU(), const VecQ& vdot = VecQ());

  const RoleFeasibilitySettings& settings() const { return settings_; }
  const ContactForceQp& qp() const { return qp_; }

 private:
  /// \brief Whether, at the last solve's predicted forces, an internal force no actuator
  ///        feels keeps every touching contact of `roles` pressed and inside its cone (file
  ///        comment: the plant then keeps a planned slider stuck).
  bool plantHoldsStuck(const ContactRoles& roles) const;

  const RbsfModel& model_;
  RoleFeasibilitySettings settings_;
  ContactForceQp qp_;
  ContactTick tick_;
  VecQ zero_;
};

}  // namespace rbsf
