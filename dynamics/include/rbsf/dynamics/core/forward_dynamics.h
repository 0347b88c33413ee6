#pragma once
/// \file
/// \brief Acceleration-level forward dynamics of phase U (omega_o-unconstrained, every
///        contact frictionless; paper eqs. 19-24).

#include "rbsf/dynamics/core/model.h"

namespace rbsf {

/// \brief One full acceleration-level evaluation: contacts, then the LCP of eqs. 21-22
///
///   A = G1^T M^-1 G1,  p = h_n + G1^T M^-1 (u - Q),
///   F_n >= 0,  delta_n = A F_n + p >= 0,  F_n^T delta_n = 0,
///   dv/dt = M^-1 (u - Q + G1 F_n)                                  (eqs. 19-20)
///
/// solved exactly by principal pivoting (unique when G1 has full column rank). Every
/// finger is treated as a potential contact: one whose gap would open gets F_n = 0.
/// Writes data.contacts, G1, T, h_n, h_t, bias, free_acc, MinvG1, A, p, fn, delta_n,
/// vdot and lcp. Units: q, v, tau in the SI units of state_layout.h. Allocation-free.
void forwardDynamicsU(const RbsfModel& model, const VecQ& q, const VecQ& v, const VecU& tau,
                      ModelData& data);

/// \brief Smallest singular value of G1 (eq. 14) at the contacts in data: the model is
///        determinate (unique F_n and accelerations) when it is well above zero.
double smallestSingularValueG1(const ModelData& data);

}  // namespace rbsf
