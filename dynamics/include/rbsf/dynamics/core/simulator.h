#pragma once
/// \file
/// \brief Hybrid contact simulator: velocity-level time stepping (Stewart-Trinkle /
///        Anitescu-Potra) over the full state (q, v) through stick, slip, separation and
///        renewed contact, with the mechanism's hard limits (docs/model.md; paper 2.2-2.4).
///
/// One step of size h with tau held over it (semi-implicit Euler):
///
///   v+ = v + h M^-1 (u - Q(q, v)) + M^-1 W lambda,      q+ = q + h v+ + dq_corr
///
/// (angles are plain numbers, never wrapped). W stacks, for the rows active in this step,
///   - contact i: normal column G1_i, tangential T_i;
///   - hard limits: +e_k for a lower end (gap q_k - q_min), -e_k for an upper end
///     (gap q_max - q_k), k = theta or a stroke.
/// A row is active when g + h min(0, r_free) <= activation_distance, r_free its rate under
/// the free velocity v + h M^-1 (u - Q): near rows, and far ones that would close within
/// the step (no tunnelling at speed).
/// The impulses lambda [N s] solve the contact problem of contact_impulse_solver.h with
/// the row velocities y = W^T v+ + c:
///   normal rows   y_n = G1_i^T v+ + (h/2) h_n,i  [+ g_i / h when the row is open],
///   tangent rows  y_t = T_i^T v+  + (h/2) h_t,i,
///   limit rows    y_l = +-v+_k                     [+ g_l / h when the row is open],
///   0 <= lambda_u _|_ y_u >= 0, planar Coulomb on (lambda_n, lambda_t) with mu_i.
/// h_n, h_t are the velocity products of model.h: (h/2) h_n makes y_n the midpoint rate of
/// the gap, so a contact sliding over a curved boundary follows it to second order. An
/// open row (gap > contact_tolerance) carries g/h, so it may close within the step but
/// not penetrate: contact is regained inelastically (y_n = 0 from then on, no rebound).
///
/// Friction memory. A contact that sticks (or has just touched) uses mu_s; once it slides
/// it uses mu_k (default 0, as in the paper). Within a step: a sticking contact whose
/// solution slips faster than slip_tolerance turns sliding and the step is solved again
/// with mu_k; a sliding contact whose slip drops below the tolerance or reverses sign turns
/// sticking and the step is solved again with mu_s. At most one such re-solve per step.
///
/// Drift correction (post-stabilisation, positions only, so it adds no kinetic energy).
/// Rows that were closed at the start of the step and stay closed, and sticking contacts'
/// tangential rows measured against the material point where they began to stick (the
/// anchor a_i, object frame), get the position correction
///   dq_corr = -M^-1 W_c (D_c + eps I)^-1 e_c,
/// e_c = (g_i; t_i . (x_o + R(phi) a_i - p_i); limit gaps), the M-least-norm displacement
/// that zeroes them to first order. It keeps the gaps of touching contacts at rounding
/// level over any horizon and makes sticking contacts stay exactly where they stuck
/// (paper 2.2: the object turns with the base). Inconsistent targets (m >= 3 sticking
/// contacts are kinematically dependent) only meet the regularisation's null space,
/// which W maps to zero: the correction stays the least-squares one.
///
/// Reports, per contact: mode (separated if inactive, or open in the solution with its
/// end-of-step gap g + h y_n above contact_tolerance; otherwise sliding if its slip
/// |y_t| > slip_tolerance, sticking if not), forces f = lambda / h [N]
/// (the step's average), the gap at the start of the step. Phase (docs/model.md, paper 2.2)
/// from the number s of sticking contacts among the touching ones: C if s >= 2, P if
/// s = 1, U if s = 0, unsupported when none touches.
///
/// Determinism and resumption: the step is a pure function of (SimState, tau, settings);
/// SimState carries everything that influences the result (mode memory, slip signs,
/// anchors, closest-point hints and the solver's mode guesses), so a saved state resumed
/// with the same tau sequence reproduces the same bits. One workspace per thread.

#include <array>
#include <cstdint>
#include <string_view>

#include "rbsf/dynamics/core/contact_impulse_solver.h"
#include "rbsf/dynamics/core/model.h"
#include "rbsf/dynamics/core/phase.h"

namespace rbsf {

/// \brief Numerical settings of the simulator. Lengths in m, angles in rad, time in s.
struct SimulatorSettings {
  double time_step = 1e-3;            ///< h [s]
  double activation_distance = 1e-3;  ///< rows with gap <= this enter a step [m or rad]
  double contact_tolerance = 1e-6;    ///< |gap| <= this counts as closed [m or rad]
  double slip_tolerance = 1e-6;       ///< |slip| above this is sliding [m/s]
  double regularization = 1e-9;       ///< CFM eps relative to max diag of the Delassus matrix
  bool curvature_terms = true;        ///< add (h/2) h_n, (h/2) h_t to the rows
  bool drift_correction = true;       ///< position correction of closed rows and anchors
  /// The drift correction moves the part alone, the joints held: an estimator's, whose
  /// joints are measured (moving them would feed its joint update a residual it made).
  /// Not written to plan files: a plant's correction moves every coordinate.
  bool drift_moves_part_only = false;
  int max_mode_iterations = 8;  ///< active-set iterations before Lemke
};

/// \brief Mode of a contact as reported and remembered.
enum class ContactMode : std::uint8_t { kStick, kSlide, kSeparated };

/// \brief "stick", "slide" or "separated".
std::string_view toString(ContactMode mode);

/// \brief Everything a step depends on besides tau: resuming from a copy reproduces the
///        same bits. Sized for m fingers; fixed capacity, no heap.
struct SimState {
  /// \brief At rest or moving with (q, v); every contact separated in memory (a touching
  ///        contact starts sticking), closest points searched globally at the first step.
  SimState(const VecQ& q, const VecQ& v);

  double t = 0.0;                               ///< time [s]
  VecQ q;                                       ///< configuration (state_layout.h)
  VecQ v;                                       ///< velocity
  VecC xi_hint;                                 ///< closest-point hints (NaN: global search)
  VecC slip;                                    ///< last slip velocity y_t per contact [m/s]
  std::array<ContactMode, kMaxFingers> mode{};  ///< friction memory
  std::array<FrictionMode, kMaxFingers> friction_guess{};  ///< solver guess
  std::array<bool, kMaxFingers> anchored{};                ///< anchor valid
  std::array<Vec2, kMaxFingers> anchor{};                  ///< stuck point, object frame [m]
  std::array<bool, kMaxLimitRows> limit_closed{};          ///< solver guess per limit
};

/// \brief What one step did, per contact (finger order).
struct ContactStepReport {
  ContactMode mode = ContactMode::kSeparated;
  double f_n = 0.0;   ///< normal force, average over the step [N]
  double f_t = 0.0;   ///< tangential force along t_i [N]
  double gap = 0.0;   ///< gap at the start of the step [m]
  double slip = 0.0;  ///< relative tangential velocity y_t [m/s]
};

/// \brief Result of one step.
struct StepReport {
  std::array<ContactStepReport, kMaxFingers> contacts{};
  Phase phase = Phase::kUnsupported;
  int touching = 0;  ///< contacts not separated
  int sticking = 0;  ///< contacts sticking
  VecQ limit_force;  ///< generalized force of the hard limits, order of q [N or N m]
  ImpulseSolvePath path = ImpulseSolvePath::kModeGuess;  ///< worst path of the step
  bool resolved = false;  ///< a friction-memory switch solved the step twice
};

/// \brief Preallocated buffers of Simulator::step(); one per thread. About 100 KB of
///        fixed-capacity matrices (plus a heap-allocated Lemke tableau): keep it on the heap
///        when many are needed or threads have small stacks.
struct SimulatorWorkspace {
  explicit SimulatorWorkspace(int m);

  ModelData data;
  ContactImpulseSolver solver;
  VecQ acc;     ///< M^-1 (u - Q)
  VecQ v_free;  ///< v + h acc
  VecQ dq;      ///< drift correction
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxConfig, kMaxImpulseRows> W, MinvW;
  std::array<int, kMaxFingers> contact_finger{};  ///< finger of each active contact
  std::array<int, kMaxLimitRows> limit_index{};   ///< limit (2k lower, 2k+1 upper) per row
  VecI gap;                                       ///< gap of each unilateral row
  std::array<bool, kMaxFingers + kMaxLimitRows> open_row{};  ///< carries g/h
  std::array<FrictionMode, kMaxFingers> memory_guess{};
  MatII Dc;     ///< drift-correction system
  VecI ec, mc;  ///< its right-hand side and solution
  std::array<int, kMaxImpulseRows> corr_row{};
};

/// \brief The simulator: a model and settings, immutable; step() writes only the state,
///        the workspace and the report.
class Simulator {
 public:
  /// \throws InputError for a non-positive time step or negative tolerances.
  explicit Simulator(const RbsfModel& model, const SimulatorSettings& settings = {});

  /// \brief The checks of the constructor. \throws InputError naming the setting.
  static void checkSettings(const SimulatorSettings& settings);

  const RbsfModel& model() const { return model_; }
  const SimulatorSettings& settings() const { return settings_; }

  /// \brief Advance `state` by one step h with tau (order of state_layout.h) held constant.
  ///        Allocation-free. `report` may be null. `slip_tolerance`, when given, replaces
  ///        the settings' slip_tolerance per contact (finger order) for this step [m/s].
  /// \throws std::invalid_argument when state, tau or workspace are sized for another m.
  void step(SimState& state, const VecU& tau, SimulatorWorkspace& ws, StepReport* report = nullptr,
            const VecC* slip_tolerance = nullptr) const;

 private:
  int assembleRows(const SimState& state, SimulatorWorkspace& ws) const;
  void correctDrift(const SimState& state, SimulatorWorkspace& ws) const;
  /// \brief The mode of contact row `r` after the solve: separated, sliding or sticking.
  ContactMode classify(const SimulatorWorkspace& ws, int r, const VecC* slip_tolerance) const;
  /// \brief Friction memory: mu_k where static friction broke, mu_s where a slide stopped or
  ///        reversed; true when a row's mu changed (the step is solved again).
  bool switchFriction(const SimState& state, SimulatorWorkspace& ws, int nc,
                      const VecC* slip_tolerance) const;
  /// \brief The new velocity, position (with the drift correction) and time.
  void integrate(SimState& state, SimulatorWorkspace& ws) const;
  /// \brief The contacts' memory (mode, slip, anchors) in `state` and their report.
  void recordContacts(SimState& state, const SimulatorWorkspace& ws, int nc, double phi_start,
                      StepReport* report, const VecC* slip_tolerance) const;
  /// \brief The closed joint limits in `state` and their forces in the report.
  void recordLimits(SimState& state, const SimulatorWorkspace& ws, int nc,
                    StepReport* report) const;

  const RbsfModel& model_;
  SimulatorSettings settings_;
};

}  // namespace rbsf
