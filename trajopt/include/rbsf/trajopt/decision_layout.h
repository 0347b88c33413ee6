#pragma once
/// \file
/// \brief The one place that fixes the order of the optimiser's decision vector z.
///        Every NLP element asks this class for its offsets; nobody else computes one.
///
/// z stacks K = N + 1 knot blocks (N collocation intervals, knot k at the start of
/// interval k, knot N at the end of the plan), then one duration per phase run:
/// | block (knot k)  | size  | symbol   | meaning                                     | unit      |
/// |-----------------|-------|----------|---------------------------------------------|-----------|
/// | q(k)            | m + 4 | q_k      | configuration, order of state_layout.h      | m, rad    |
/// | v(k)            | m + 4 | v_k      | velocity dq/dt                              | m/s, rad/s|
/// | tau(k)          | m + 1 | tau_k    | input, order of state_layout.h              | N m, N    |
/// | fn(k)           | m     | f_n,k    | normal force of each finger, on interval k  | N         |
/// | ft(k)           | m     | f_t,k    | force along t_i (0 unless sticking), ditto  | N         |
/// | xi(k)           | m     | xi_k     | boundary parameter of each finger's foot point | -      |
/// | duration(j)     | 1     | T_j      | duration of phase run j (after the knots)   | s         |
/// Forces act on the object at the foot point x_o + R(phi) c(xi_i), world frame:
/// f_i = f_n,i n_i + f_t,i t_i (docs/model.md "Contact kinematics"; n_i inward).
/// The forces of knot k act at knot k, along its foot points' normals and tangents; the
/// velocity-Verlet collocation (collocation_constraint.h) sees each knot's force in the
/// positions, so they cannot alternate from knot to knot unseen.
/// xi is not wrapped: it moves continuously over the plan (the initial guess unwraps it).

#include "rbsf/dynamics/core/state_layout.h"

namespace rbsf::trajopt {

/// \brief Offsets of every block of z for m fingers, N intervals and R runs.
class DecisionLayout {
 public:
  DecisionLayout(int fingers, int intervals, int runs)
      : m_(fingers), intervals_(intervals), runs_(runs) {}

  int fingers() const { return m_; }
  /// \brief Number of collocation intervals N.
  int intervals() const { return intervals_; }
  /// \brief Number of knots N + 1.
  int knots() const { return intervals_ + 1; }
  /// \brief Number of phase runs R (one duration variable each).
  int runs() const { return runs_; }
  /// \brief Entries per knot: 2 (m + 4) + (m + 1) + 3 m.
  int knotSize() const { return 2 * layout::configDim(m_) + layout::controlDim(m_) + 3 * m_; }
  /// \brief Size of z.
  int size() const { return knots() * knotSize() + runs_; }

  /// \brief First index of knot k's block.
  int knot(int k) const { return k * knotSize(); }
  /// \brief q_k, length m + 4.
  int q(int k) const { return knot(k); }
  /// \brief v_k, length m + 4.
  int v(int k) const { return knot(k) + layout::configDim(m_); }
  /// \brief tau_k, length m + 1.
  int tau(int k) const { return knot(k) + 2 * layout::configDim(m_); }
  /// \brief f_n,k, length m.
  int fn(int k) const { return tau(k) + layout::controlDim(m_); }
  /// \brief f_t,k, length m.
  int ft(int k) const { return fn(k) + m_; }
  /// \brief xi_k, length m.
  int xi(int k) const { return ft(k) + m_; }
  /// \brief T_j, duration of run j [s].
  int duration(int j) const { return knots() * knotSize() + j; }

  /// \brief Offsets of the blocks inside one knot block (for element-local vectors).
  int localV() const { return layout::configDim(m_); }
  int localTau() const { return 2 * layout::configDim(m_); }
  int localFn() const { return localTau() + layout::controlDim(m_); }
  int localFt() const { return localFn() + m_; }
  int localXi() const { return localFt() + m_; }

 private:
  int m_, intervals_, runs_;
};

}  // namespace rbsf::trajopt
