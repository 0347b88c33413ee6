#pragma once
/// \file
/// \brief The input of one control tick chosen by the contact forces it produces: the law's
///        demand made contact-consistent (control_law.h). Contact-consistent inverse dynamics
///        as in the whole-body control of legged robots, per contact role as in the hybrid
///        force-velocity control of contact-rich plans (Hou and Mason, ICRA 2019).
///
/// **Prediction.** At the estimated state (q, v) each contact gets a mode from its role
/// (contact_roles.h) and the estimate: a lifted finger is separated; a sticking or free
/// contact is as estimated (touching: sticking or sliding); a planned slider sticks until it
/// has broken loose (`loose`), then slides with kinetic friction against its slip. A free
/// contact whose least-norm force under the demand would leave its cone is held at the
/// cone's edge, as the plant's contact problem holds it (one contact at a time, the worst
/// first, until none would). Within
/// that mode the dynamics are affine in the input and in a generalized force f on the part
/// (mode_dynamics.h, with the simulator's least-norm rule where the forces are
/// indeterminate):
///
///   dv/dt = a0 + B tau,      lambda = l0 + L tau + E f,
///
/// lambda the forces of the mode's rows (touching normals in finger order, then the
/// sticking tangentials) [N]. The fingers are force actuators: along the directions of tau
/// that B maps to zero the input changes only internal forces, never the motion; the
/// internal forces no actuator reaches (three sticking tips: a lateral squeeze) are the
/// plant's, here its least-norm rule.
///
/// **Rows** r_j(lambda) >= 0, linear in tau, per contact:
///   - touching, relied on (S, +, -):  f_n - normal_floor m_o g
///   - sticking (S):                   friction_use mu_s f_n -+ f_t          (two rows)
///   - slider not yet loose:           -s f_t - breakaway mu_s f_n - pull_margin m_o g:
///                                     pulled against its planned slip s beyond the static
///                                     cone (breakaway)
///   - slider loose:                   m_o (s (T_i^T dv/dt + h_t) - slip_gain (floor_i -
///                                     s T_i^T v)): its slip speed never falls below its
///                                     floor inside a planned slide (a slider that stops
///                                     sticks again where mu_k < mu_s); the law sets the
///                                     floor to slip_speed where the reference itself slides
///                                     the tip that way at least that fast, else no row (a
///                                     run that comes to rest or turns its slip)
///   - free (F):                       f_n >= 0 and |f_t| <= mu_s f_n (as predicted)
///   - lifted:                         m_o (g'' + 2 a g' + a^2 (g - clearance)), g the gap,
///                                     g'' = G1_i^T dv/dt + h_n (a control barrier: the tip
///                                     keeps clear of the part; still touching, it lets go)
/// Each relied-on row also has a **robust margin** R_j: the worst change of r_j that the
/// cell's stated uncertainty (sensing.h) can make, to first order, through E and L: the
/// part's weight (mass), a gravity moment (COM offset) and each actuator's gain times the
/// demand.
///
/// **QP** in x = (tau, rho, sigma, pi) (QpLayout), with Delta = tau - tau_d and tau_d the
/// demand (feed-forward plus feedback):
///
///   min  |S B Delta|^2 + eps_tau |Delta / (m_o g)|^2 + c_sigma sigma + sigma^2
///        + c_pi pi + pi^2 - c_rho rho + 10^-3 rho^2
///   s.t. r_j >= -sigma m_o g                    every row but the pulls (its violation)
///        r_j >= R_j + rho m_o g                 every relied-on row but the pulls (margin)
///        r_j >= -pi m_o g                       every breakaway pull (its shortfall)
///        |tau_k| <= limit_k,   rho <= margin_cap,   sigma, pi >= 0,
///
/// S = diag(M_kk / scale_k): each coordinate's generalized-force error per part weight
/// (moments per part weight times 0.1 m). So the rows that hold the part come first (sigma,
/// their least violation, costs far more than a motion error); a breakaway pull that they
/// leave out of reach is taken as far as they allow (pi, below them, above the motion); the
/// motion asked for is kept as well as those allow, and the
/// internal forces the motion leaves free maximise the smallest margin rho beyond the robust
/// ones (the squeeze that holds best). Always feasible (sigma is unbounded above), solved
/// exactly by the dual active-set method of small_qp.h; the input is clamped to its limits.
///
/// Real time: solve() allocates nothing (fixed-capacity buffers). One per control loop.

#include <array>

#include <Eigen/Core>
#include <Eigen/LU>

#include "rbsf/dynamics/core/contact_roles.h"
#include "rbsf/dynamics/core/mode_dynamics.h"
#include "rbsf/dynamics/core/model.h"
#include "rbsf/dynamics/core/small_qp.h"

namespace rbsf {

/// \brief Settings of ContactForceQp (file comment); forces as fractions of m_o g.
struct ContactForceSettings {
  double friction_use = 0.8;     ///< sticking contacts sought within this share of the cone
  double friction_limit = 0.8;   ///< and kept within this one
  double normal_floor = 0.03;    ///< relied-on touching contacts kept above this x m_o g
  double breakaway = 1.3;        ///< a slider still stuck is pulled to this x mu_s f_n
  double pull_margin = 0.01;     ///< and this x m_o g beyond
  double slip_speed = 0.005;     ///< loose sliders keep slipping at least this fast [m/s]
  double slip_gain = 20.0;       ///< [1/s]: how fast a slow slider is brought to slip_speed
  double clearance = 0.002;      ///< a lifted finger's tip keeps this far from the part [m]
  double clearance_rate = 30.0;  ///< [1/s]: the barrier's rate a
  double margin_cap = 0.1;       ///< margin sought beyond the robust one, x m_o g
  /// \brief A robust margin is at most this x m_o g: where the rows are that sensitive
  ///        (two sticking tips almost level steer their squeeze hardly at all) the
  ///        prediction is no better than the margin.
  double robust_cap = 0.5;
  double margin_reward = 0.01;         ///< c_rho
  double violation_penalty = 10.0;     ///< c_sigma
  double shortfall_penalty = 1.0;      ///< c_pi
  double input_regularization = 1e-4;  ///< eps_tau
};

/// \brief The layout of the QP's variables x = (tau, rho, sigma); nobody else indexes x.
struct QpLayout {
  int nu = 0;  ///< m + 1 inputs first
  int margin() const { return nu; }
  int violation() const { return nu + 1; }
  int shortfall() const { return nu + 2; }
  int size() const { return nu + 3; }
};

/// \brief Whether each planned slider has broken loose (finger order).
using LooseFlags = std::array<bool, kMaxFingers>;

/// \brief What one tick knows of its contacts besides the state (finger order).
struct ContactTick {
  ContactRoles roles{};      ///< the plan's roles
  ContactModes estimated{};  ///< touching and sliding in the estimate
  LooseFlags loose{};        ///< planned sliders that have broken loose
  VecC slip_floor;           ///< a loose slider's least slip speed [m/s] (file comment)
};

/// \brief The contact-consistent input of one tick (file comment). One per control loop.
class ContactForceQp {
 public:
  /// \brief For `model` (the nominal cell: its friction, limits and uncertainty).
  explicit ContactForceQp(const RbsfModel& model, const ContactForceSettings& settings = {});

  /// \brief The input for the estimated state (q, v) closest in motion to `demand` (tau
  ///        order) that keeps the contacts in their roles (`tick`). Closest points start
  ///        from data().xi_hint (updateContacts(q)). Allocation-free.
  /// \return true when every row holds (sigma ~ 0).
  bool solve(const VecQ& q, const VecQ& v, const ContactTick& tick, const VecU& demand, VecU& tau);

  /// \brief Predicted normal and tangential forces of the last solve per finger [N] (0 where
  ///        separated in the prediction; f_t 0 where sliding).
  const VecC& normalForces() const { return fn_; }
  const VecC& tangentialForces() const { return ft_; }
  /// \brief The last solve's margin rho and violation sigma (x m_o g).
  double margin() const { return x_[layout_.margin()]; }
  double violation() const { return x_[layout_.violation()]; }
  /// \brief Largest |f_t| / (mu_s f_n) of the predicted sticking contacts (S) at the last
  ///        solve.
  double frictionUse() const { return use_; }
  /// \brief The accelerations dv/dt the last solve predicts for its input (a0 + B tau).
  VecQ predictedAcceleration(const VecU& tau) const { return a0_ + B_ * tau; }
  /// \brief The last solve's breakaway shortfall pi (x m_o g).
  double shortfall() const { return x_[layout_.shortfall()]; }
  /// \brief The QP's status at the last solve.
  QpStatus status() const { return qp_.status; }

  /// \brief The input the law chooses at (q, v) for the contacts of `tick` when its demand is
  ///        `feedforward` (a plan's input there; when empty, the input whose predicted motion
  ///        is closest to `vdot` in the cost's metric, generalized forces per part weight,
  ///        found on the mode's maps at the zero input): solve() with that demand, then
  ///        solve() again with the input it chose as the demand, whose internal forces keep
  ///        the rows where they can (a free contact's saturation depends on the demand).
  ///        Allocation-free. \return the second solve()'s verdict.
  bool solveForMotion(const VecQ& q, const VecQ& v, const ContactTick& tick, const VecQ& vdot,
                      VecU& tau, const VecU& feedforward = VecU());
  /// \brief The largest error of the last solve's predicted motion for input `tau` against
  ///        `vdot`, per coordinate as a generalized force per part weight: M_cc |(a0 + B tau -
  ///        vdot)_c| / (m_o g), moments per m_o g x 0.1 m (the cost's metric).
  double motionError(const VecU& tau, const VecQ& vdot) const;

  /// \brief Forget the last solve's contact geometry and closest-point hints: the next solve
  ///        searches every closest point afresh, as after construction, so that a law that
  ///        restarts repeats its first run bit for bit.
  void reset();
  const ContactForceSettings& settings() const { return settings_; }
  /// \brief The workspace of the contact geometry (its xi_hint seeds the closest points).
  ModelData& data() { return data_; }
  /// \brief The contact geometry of the last solve (G1, T at its q).
  const ModelData& contactData() const { return data_; }
  /// \brief The contact geometry at q (RbsfModel::updateContacts into data(), its closest
  ///        points searched from data().xi_hint), computed only when data() does not already
  ///        hold q's (the same bits): the law's classification of the tick's contacts and
  ///        solve() share one computation per tick.
  const ModelData& updateContacts(const VecQ& q);

 private:
  /// \brief The mode's maps at (q, v): a0_, B_, L_ (file comment) and the row indices.
  void predict(const VecQ& q, const VecQ& v, const ContactTick& tick, const VecU& demand);
  /// \brief The maps of the modes in mode_ and saturated_.
  void assemble(const VecQ& q, const VecQ& v, const ContactTick& tick);
  /// \brief The QP's cost and rows for `demand`.
  void buildQp(const VecQ& q, const VecQ& v, const ContactTick& tick, const VecU& demand);
  class RowWriter;  ///< the QP's rows in order (contact_force_qp.cpp)
  /// \brief The QP's cost: the motion's error from `demand`, then rho, sigma and pi.
  void setCost(const VecQ& q, const VecU& demand);
  /// \brief The input whose motion on the last prediction's maps is closest to `vdot` in the
  ///        cost's metric (input_regularization keeps it unique), into `demand`.
  void motionDemand(const VecQ& q, const VecQ& vdot, VecU& demand);
  /// \brief The rows of contact `i` in its role and mode; `c` is a row's work vector.
  void contactRows(RowWriter& w, int i, const VecQ& v, const ContactTick& tick, VecR& c) const;

  using MatL = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxRows, kMaxFingers + 5>;

  const RbsfModel& model_;
  ContactForceSettings settings_;
  ModelData data_;
  VecQ contacts_q_;  ///< the q of data_'s contacts (NaN: none)
  QpLayout layout_;
  double weight_;
  ContactModes mode_{};
  std::array<int, kMaxFingers> saturated_{};  ///< +-1: a free contact held at its cone's edge
  std::array<int, kMaxFingers> normal_row_{}, tangent_row_{};
  int rows_ = 0;
  MatQR W_, N_, MinvN_;
  VecR hw_;
  MatRR D_, De_;
  Eigen::PartialPivLU<MatRR> lu_;
  MatQQ Mu_, Mp_, B_, M_, SB_;
  VecQ a0_, af0_;
  MatL L_, L1_;  ///< columns: d/d tau (nu), the constant, d/d f on x, y, phi
  SmallQp qp_;
  QpVecN x_;
  VecC fn_, ft_;
  double use_ = 0.0;
};

}  // namespace rbsf
