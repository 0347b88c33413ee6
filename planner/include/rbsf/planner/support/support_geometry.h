#pragma once
/// \file
/// \brief Quasi-static support configurations: the part's pose seen from the base, the
///        finger strokes that make a chosen contact set touch it, and whether that support
///        carries the part with margins (contact_balance.h).
///
/// A JigPose is the part's pose (X, Y, psi) in the base frame plus the base angle theta;
/// the world pose is (x, y) = R(theta) (X, Y), phi = psi + theta. For a contact set, each
/// touching finger's tip is where its line x_base = r_i enters the part from below (the
/// placement rule), and every other finger is retracted to its lower stroke limit, at
/// least `clearance` below the part. A pivot keeps the sticking finger's tip on one point
/// xi_k of the boundary at stroke l_k: then (X, Y) = (r_k, l_k) - R(psi) c(xi_k).
///
/// A support is **valid** when: theta is inside its limits by `theta_margin`; each touching
/// finger's line meets the part's underside with the inward normal at most
/// acos(min_normal_cosine) (sliding) or acos(min_sticking_cosine) (sticking: friction
/// carries what the normal does not) from the finger's axis and a stroke inside its limits by
/// `stroke_margin`; the retracted fingers clear the part; the contact set is balanced
/// (margin >= 0) and, when `require_determined`, joint-determined; and, when `law_check`,
/// the contact-force law keeps its roles there (role_feasibility.h): the sticking contacts
/// S, the sliders + or - the way the move slips them (F at rest), the others L.

#include <optional>

#include "rbsf/dynamics/control/role_feasibility.h"
#include "rbsf/dynamics/core/contact_balance.h"
#include "rbsf/dynamics/core/model.h"
#include "rbsf/dynamics/core/placement.h"
#include "rbsf/planner/support/support_reach.h"

namespace rbsf::planner {

/// \brief The part's pose in the base frame and the base angle (file comment).
struct JigPose {
  double X = 0.0;      ///< [m], base frame
  double Y = 0.0;      ///< [m], base frame
  double psi = 0.0;    ///< part angle relative to the base [rad]
  double theta = 0.0;  ///< base angle [rad]

  /// \brief The world pose of the part.
  Pose world() const;
  /// \brief The JigPose of world pose `p` seen from base angle theta.
  static JigPose fromWorld(const Pose& p, double theta);
};

/// \brief The pose a fraction `s` of the way from `a` to `b`, coordinate by coordinate.
inline JigPose lerpPose(const JigPose& a, const JigPose& b, double s) {
  return JigPose{a.X + s * (b.X - a.X), a.Y + s * (b.Y - a.Y), a.psi + s * (b.psi - a.psi),
                 a.theta + s * (b.theta - a.theta)};
}

/// \brief The support searches' metric between two poses: sqrt(dX^2 + dY^2) / length_scale
///        and the angles in radians, as one Euclidean norm.
double poseDistance(const JigPose& a, const JigPose& b, double length_scale);

/// \brief A sliding contact slips in a move when it moves more than this along its tip;
///        less leaves it stuck (SupportStep::rest) [m].
constexpr double kSlipStep = 1e-4;

/// \brief The roles (contact_roles.h) of `set` for m fingers in a move with slip `slip`
///        (SupportGeometry::slipDirections; may be empty): sticking contacts S, a slider
///        slipping more than kSlipStep + or - its way (else F: at rest it is stuck, not relied
///        on), the others L.
ContactRoles supportRoles(const ContactSet& set, const VecC& slip, int m);

/// \brief The sticking finger's hold on the part during a pivot.
struct PivotAnchor {
  int finger = -1;      ///< k
  double xi = 0.0;      ///< boundary parameter held [rad]
  double stroke = 0.0;  ///< l_k [m]
};

/// \brief Geometric limits of a valid support (file comment).
struct SupportSettings {
  double theta_margin = 0.03;        ///< [rad]
  double stroke_margin = 0.01;       ///< [m]
  double clearance = 0.01;           ///< retracted tips below the part [m]
  double min_normal_cosine = 0.35;   ///< sliding contacts' normals against the finger axis
  double min_sticking_cosine = 0.1;  ///< sticking contacts' (friction carries the rest)
  bool require_determined = true;    ///< the joints alone must fix the part
  /// \brief A run that starts from rest with sliding contacts must break its sliders loose
  ///        before any sticking contact slips (breaksAway()).
  bool require_breakaway = true;
  BalanceSettings balance;  ///< force margins
  /// \brief Put every support and breakaway to the contact-force law too (file comment).
  bool law_check = true;
  ContactForceSettings law;       ///< the law's forces (FeedbackSettings::forces of the plan)
  RoleFeasibilitySettings roles;  ///< what the law's answer must meet
};

/// \brief A support's configuration and verdict.
struct Support {
  bool valid = false;
  double margin = 0.0;  ///< the balance margin when the geometry is valid
  VecQ q;               ///< the configuration (state_layout.h)
  ContactBalance balance;
  SupportRule refusal = SupportRule::kBalance;  ///< the first rule broken when not valid
  RoleVerdict law;  ///< the law's answer (law_check; feasible when not checked)
};

/// \brief Builds and checks supports; one per thread (holds a ModelData).
class SupportGeometry {
 public:
  SupportGeometry(const RbsfModel& model, SupportSettings settings);

  /// \brief Entry of finger i's line into the part at `pose`: stroke and boundary
  ///        parameter; false when the line misses the part or meets it where the inward
  ///        normal is more than acos(min_cosine) from the finger's axis.
  bool entry(const JigPose& pose, int i, double& stroke, double& xi, double min_cosine) const;
  /// \brief entry() with the sliding contacts' bound min_normal_cosine.
  bool entry(const JigPose& pose, int i, double& stroke, double& xi) const {
    return entry(pose, i, stroke, xi, settings_.min_normal_cosine);
  }

  /// \brief The configuration of `set` at `pose` (no balance check); nothing when the
  ///        geometry is invalid. `check_limits` false: only a touching finger whose line
  ///        misses the part fails (the margins are the search's, not the motion's).
  ///        On failure `why`, when given, gets the first rule broken (support_reach.h).
  std::optional<VecQ> configuration(const JigPose& pose, const ContactSet& set,
                                    bool check_limits = true, SupportRule* why = nullptr) const;

  /// \brief Configuration and verdict; `slip` (may be empty) the planned slip direction of
  ///        each contact (contact_balance.h), from slipDirections().
  Support check(const JigPose& pose, const ContactSet& set, const VecC& slip = VecC());
  /// \brief The verdict of check() for `set` at configuration q, which configuration()
  ///        gave (the balance alone: the geometry was checked there).
  Support balanceAt(const VecQ& q, const ContactSet& set, const VecC& slip = VecC());

  /// \brief Whether a run of `set` can start from rest at configuration q with the planned
  ///        slip `slip` (slipDirections()): true without a sliding contact, else
  ///        ContactBalancer::breakaway is balanced. At rest every tip sticks, so the sliders
  ///        must all reach mu_s f_n against their slip while the part stays in balance. A
  ///        heavily loaded tip planned to slide beside a lightly loaded one planned to stick
  ///        fails: the plant's tips stay stuck until the lighter one gives, and the pivot is
  ///        lost. So does a run on sliding tips alone whose tips cannot all break loose at
  ///        once: the lighter ones give first and the heaviest stays stuck.
  bool breaksAway(const VecQ& q, const ContactSet& set, const VecC& slip);

  /// \brief Whether the law holds the part at rest at `pose` while the forces go from `from`'s
  ///        (at configuration q_from) to `to`'s (at q_to): the hand-over's midpoint, every
  ///        finger of either set touching, those in both that stick in both S, the others
  ///        F (not relied on), the demand the mean of the two sets' static inputs. True
  ///        without law_check.
  bool handsOver(const JigPose& pose, const ContactSet& from, const VecQ& q_from,
                 const ContactSet& to, const VecQ& q_to);

  /// \brief The contact-force law's answer (role_feasibility.h) for `set` at q with the slip
  ///        `slip` (supportRoles) and the feed-forward `tau` (a plan's: the balance's input
  ///        there; may be empty): a breakaway when `loose` is false and a slider slips, else
  ///        a slide or a hold.
  RoleVerdict lawCheck(const VecQ& q, const ContactSet& set, const VecC& slip, bool loose,
                       const VecU& tau = VecU());

  /// \brief T_i^T (q1 - q0) per finger: the slip each contact sees moving from q0 to q1.
  VecC slipDirections(const VecQ& q0, const VecQ& q1);

  /// \brief The pose of a pivot about `anchor` with part angle psi and base angle theta.
  JigPose pivotPose(const PivotAnchor& anchor, double psi, double theta) const;
  /// \brief The pivot about `anchor` that puts the part on world pose `goal`: the tip's
  ///        world point w = (x, y) + R(phi) c(xi) is fixed, so the stroke is
  ///        sqrt(|w|^2 - r_k^2) and the base angle atan2(w) - atan2(stroke, r_k); psi is
  ///        phi - theta, taken within pi of `psi_near`. False when the stroke or the base
  ///        angle is outside its limits (with the margins).
  bool pivotOnto(const PivotAnchor& anchor, const Pose& goal, double psi_near, double& psi,
                 double& theta, double& stroke) const;

  /// \brief Every finger whose line meets the part's underside at `pose` with a stroke
  ///        inside its limits (the placement rule's set, all sliding).
  ContactSet placedSet(const JigPose& pose) const;

  const RbsfModel& model() const { return model_; }
  const SupportSettings& settings() const { return settings_; }

 private:
  const RbsfModel& model_;
  SupportSettings settings_;
  ContactBalancer balancer_;
  RoleFeasibility law_;
  ModelData data_;
};

}  // namespace rbsf::planner
