#pragma once
/// \file
/// \brief One sample of a simulated trajectory and its CSV form, shared by plan files
///        (plan::PlanSample) and rbsf-simulate's output, so both write one format.
///
/// A sample is the state (t, q, v) at the end of a simulator step together with the input
/// tau held over that step, the normal force f_n of each contact averaged over the step
/// and the phase of the step. CSV columns, in order (state_layout.h for q, v and tau;
/// contacts in finger order):
///
///     t, x, y, phi, theta, l1..lm, dx, dy, dphi, dtheta, dl1..dlm,
///     tau_theta, tau_1..tau_m, fn_1..fn_m, phase
///
/// SI units, radians; phase is C, P, U or unsupported; numbers with 17 significant digits
/// (they read back bit for bit).

#include <string>
#include <vector>

#include "rbsf/dynamics/core/phase.h"
#include "rbsf/dynamics/core/types.h"

namespace rbsf {

/// \brief One sample (see the file comment).
struct TrajectorySample {
  double t = 0.0;  ///< [s]
  VecQ q, v;
  VecU tau;
  VecC f_n;  ///< [N]
  Phase phase = Phase::kUnsupported;
};

/// \brief The CSV header line for m fingers (no newline).
std::string trajectoryCsvHeader(int m);

/// \brief Append one sample's CSV line (with its newline) to `text`.
/// \throws std::runtime_error for a non-finite number or a sample sized for other than m
///         fingers (`text` may then hold part of the line).
void appendTrajectoryCsvRow(std::string& text, const TrajectorySample& s, int m);

/// \brief Header and one line per sample, each ending in a newline.
/// \throws std::runtime_error for a non-finite number or a sample sized for other than m
///         fingers (nothing is returned, so nothing half-formatted reaches a file).
std::string trajectoryCsvText(const std::vector<TrajectorySample>& samples, int m);

}  // namespace rbsf
