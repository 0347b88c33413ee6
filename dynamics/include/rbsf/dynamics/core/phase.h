#pragma once
/// \file
/// \brief Kinematic phases of paper 2.2 and the classification of a state into them.

#include <string_view>

#include "rbsf/dynamics/core/stick_dynamics.h"

namespace rbsf {

/// \brief Phase by the number s of sticking contacts among the touching ones (docs/model.md).
enum class Phase {
  kC,            ///< s >= 2: omega_o-constrained, every contact sticks
  kP,            ///< s = 1: point-constrained, the object pivots about one contact
  kU,            ///< s = 0: omega_o-unconstrained, every contact slides
  kUnsupported,  ///< no contact touches
};

/// \brief "C", "P", "U" or "unsupported".
std::string_view toString(Phase phase);

/// \brief Tolerances of classifyPhase().
struct PhaseTolerances {
  double slip_speed = 1e-9;  ///< |T_i^T v| [m/s] below which a contact may stick
};

/// \brief Classification of a state with its dynamics in the chosen phase.
struct PhaseClassification {
  Phase phase = Phase::kU;
  StickSolution stick;  ///< the C or P solution when phase is C or P
  int sticking = 0;     ///< number of contacts with zero slip speed (candidates)
};

/// \brief Classify (q, v, tau), every contact touching: contacts whose slip speed
///        |T_i^T v| is below tolerance may stick. If every contact may stick (at least
///        two) and phase C fits the friction cones, C; else if some contact may stick and
///        phase P about it fits its cone (first such contact), P; else U.
/// \pre model.updateContacts(q, data) has been called for q.
PhaseClassification classifyPhase(const RbsfModel& model, const VecQ& q, const VecQ& v,
                                  const VecU& tau, ModelData& data,
                                  const PhaseTolerances& tol = {});

}  // namespace rbsf
