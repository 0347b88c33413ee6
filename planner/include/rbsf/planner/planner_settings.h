#pragma once
/// \file
/// \brief What the kinodynamic planner (reorientation_planner.h) can be told, and the
///        problem it solves: plain settings and data, without OMPL, so that code which
///        configures a planner (the pipeline, the controller facade, the tools) does not
///        depend on OMPL's headers. The classes that use each struct name it.

#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rbsf/dynamics/core/placement.h"
#include "rbsf/dynamics/core/simulator.h"

namespace rbsf::planner {

/// \brief Speed bounds of the state space (state_space.h; also checked by the validity checker).
struct SpeedBounds {
  double linear = 2.0;   ///< object |dx/dt|, |dy/dt| and stroke rates [m/s]
  double angular = 6.0;  ///< |dphi/dt|, |dtheta/dt| [rad/s]
};

/// \brief Thresholds of SupportValidityChecker (validity.h).
struct ValiditySettings {
  int min_touching = 2;                 ///< contacts that must touch
  double touch_distance = 1e-3;         ///< gap counted as touching [m]
  double penetration_tolerance = 2e-3;  ///< largest allowed -gap [m]
  double min_height = 0.05;             ///< lowest COM y [m]
};

/// \brief The decisive-modes rule of the propagator (propagator.h).
struct DecisiveModes {
  bool enabled = true;       ///< false: every propagation step counts
  int settle_steps = 2;      ///< simulator steps in which a propagation step may switch modes
  double cone_margin = 0.9;  ///< sticking contacts keep |f_t| <= cone_margin mu_s f_n after
};

/// \brief Probabilities and target ranges of PhaseControlSampler (control_sampler.h).
struct SamplerSettings {
  double p_stick = 0.5;           ///< weight of phase C targets
  double p_slide = 0.5;           ///< weight of phase U targets
  double p_random = 0.05;         ///< probability of a uniformly random tau
  double max_base_accel = 6.0;    ///< [rad/s^2]
  double max_stroke_accel = 2.0;  ///< [m/s^2]
  double max_omega_dot = 30.0;    ///< [rad/s^2]
  double damping = 3.0;           ///< [1/s]
  double centering = 20.0;        ///< [1/s^2] pull of the COM toward home_x in phase U
  double home_x = 0.0;            ///< [m]
};

/// \brief Progress during the search (reported about once per second).
struct Progress {
  double elapsed = 0.0;  ///< [s]
  std::uint64_t propagations = 0;
  double best_distance = 0.0;  ///< goal distance in tolerance units (<= 1: reached)
};

/// \brief OMPL's control planners the kinodynamic search can run (planner_setup.h).
enum class KinodynamicPlanner { kKPIECE1, kRRT, kSST, kEST, kPDST };

/// \brief Every KinodynamicPlanner, in declaration order.
const std::array<KinodynamicPlanner, 5>& kinodynamicPlanners();
/// \brief OMPL's name of the planner: "KPIECE1", "RRT", "SST", "EST", "PDST".
const char* toString(KinodynamicPlanner planner);
/// \brief The planner named `name` (toString's words), or nothing.
std::optional<KinodynamicPlanner> parsePlanner(std::string_view name);

/// \brief Everything the planner can be told.
struct PlannerSettings {
  KinodynamicPlanner planner = KinodynamicPlanner::kKPIECE1;
  /// \brief Wall-clock bound of the search [s]; infinity: none, max_propagations and the
  ///        call's cancel flag alone end it (the same plan on any machine, under any load).
  double time_limit = 30.0;
  /// \brief Propagations at most (0: no bound). A budget in propagations gives the same plan
  ///        on any machine, under any load, where the time limit does not bind first.
  std::uint64_t max_propagations = 0;
  std::uint32_t seed = 1;
  SimulatorSettings simulator;
  int steps_per_control = 20;    ///< simulator steps per propagation step
  int min_control_steps = 1;     ///< propagation steps per control, least
  int max_control_steps = 10;    ///< and most
  int sample_steps = 10;         ///< simulator steps between plan samples
  double projection_cell = 0.1;  ///< [rad], both projection axes
  double goal_bias = 0.05;
  SpeedBounds speed;
  ValiditySettings validity;
  DecisiveModes decisive_modes;  ///< propagation steps a tracking cell repeats (propagator.h)
  /// \brief Every propagated state keeps the cell's motion limits (propagator.h): the plans
  ///        are slow or there is none. false: only SpeedBounds (a throw may be found).
  bool keep_motion_limits = true;
  SamplerSettings sampler;
};

/// \brief What one search is told besides its settings: when to stop and whom to tell how
///        it goes. Settings say what to compute and are plain values; this is the call's.
struct SearchContext {
  /// \brief When set and it becomes true (another thread, a signal handler), the search
  ///        stops at its next check and returns the best plan found so far.
  const std::atomic<bool>* cancel = nullptr;
  std::function<void(const Progress&)> progress;  ///< called about once per second

  /// \brief The cancel flag is set and true.
  bool cancelled() const { return cancel != nullptr && cancel->load(std::memory_order_relaxed); }
};

/// \brief How near the goal pose a plan must end: the searches' goal region and the
///        certificate's criteria (the part at rest within both).
struct GoalTolerance {
  double position = 0.01;           ///< [m]
  double angle = 2.0 * M_PI / 180;  ///< [rad]
};

/// \brief The problem: start pose (fingers placed at start_theta, part at rest), goal and
///        how near the goal is near enough.
struct Problem {
  Pose start;
  double start_theta = 0.0;
  Pose goal;
  /// \brief false: the goal angle is a pose, reached whichever way the part turns (phi
  ///        compared modulo 2 pi, so 270 deg is -90 deg). true: the goal angle is the
  ///        part's total turn from phi = 0 (phi is never wrapped along a motion), so a
  ///        start at 0 and a goal at -270 deg asks for three quarters of a clockwise turn.
  bool absolute_angle = false;
  GoalTolerance tolerance;
};

/// \brief The rules of Problem that need no cell: positive, finite goal tolerances.
///        \throws InputError naming the tolerance.
void checkTolerance(const GoalTolerance& tolerance);

/// \brief The rules of DecisiveModes: settle_steps >= 0, cone_margin in (0, 1].
///        \throws InputError naming the setting and its value.
void checkSettings(const DecisiveModes& rule);

/// \brief The rules of PlannerSettings, in one place (the planner, the pipeline and the
///        tools check through it): a known planner, a positive finite time limit,
///        positive and ordered control steps, and the decisive-modes rule's. \throws InputError
///        naming the first bad setting.
void checkSettings(const PlannerSettings& settings);

}  // namespace rbsf::planner
