#pragma once
/// \file
/// \brief The dynamics of docs/model.md at the optimiser's knots, for any scalar (double or
///        Eigen's AutoDiffScalar), so the collocation and contact constraints get exact
///        derivatives by forward-mode automatic differentiation. The terms themselves are
///        RbsfModel's (dynamics/equations.h); here they are evaluated at the decision
///        variables: the contact point is the boundary point of the variable xi_i, not the
///        closest point.
///
/// Derivative vectors have a fixed maximum size (kMaxLocal, enough for two knots of a
/// 12-finger cell plus a duration), so AutoDiff arithmetic never touches the heap.

#include <cmath>

#include <Eigen/Core>
#include <unsupported/Eigen/AutoDiff>

#include "rbsf/dynamics/core/equations.h"
#include "rbsf/dynamics/core/model.h"
#include "rbsf/trajopt/decision_layout.h"

namespace rbsf::trajopt {

/// \brief Largest number of element-local variables: two knot blocks and one duration.
inline constexpr int kMaxLocal = 2 * (2 * kMaxConfig + (kMaxFingers + 1) + 3 * kMaxFingers) + 1;
/// \brief Derivative vector of the AutoDiff scalar (stack storage).
using LocalDerivative = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxLocal, 1>;
/// \brief Forward-mode AutoDiff scalar over an element's local variables.
using ADScalar = Eigen::AutoDiffScalar<LocalDerivative>;
/// \brief A configuration-sized vector of scalars S.
template <class S>
using ConfigVector = Eigen::Matrix<S, Eigen::Dynamic, 1, 0, 2 * kMaxConfig, 1>;
template <class S>
using Vec2T = Eigen::Matrix<S, 2, 1>;

/// \brief Boundary point c(xi) and unit tangent t(xi) in the object frame; the inward
///        normal is n = S t (docs/model.md).
template <class S>
struct FootPoint {
  Vec2T<S> c, t;
};

/// \brief Number of derivative levels of a scalar: 0 for double, 1 for AutoDiffScalar
///        over doubles, 2 for AutoDiff over AutoDiff (Hessians).
template <class S>
struct AdOrder {
  static constexpr int value = 0;
};
template <class D>
struct AdOrder<Eigen::AutoDiffScalar<D>> {
  static constexpr int value = 1 + AdOrder<typename D::Scalar>::value;
};

/// \brief The plain value of a (nested) AutoDiff scalar.
inline double scalarValue(double x) { return x; }
template <class D>
double scalarValue(const Eigen::AutoDiffScalar<D>& x) {
  return scalarValue(x.value());
}

/// \brief Taylor coefficients of c(xi) and t(xi) at xi0 up to second order:
///        c ~ c0 + c1 d + c2 d^2 / 2, t ~ t0 + t1 d + t2 d^2 / 2 (d = xi - xi0), with
///        t' = (c'' - t s') / s and t'' = (c''' - 2 t' s' - t s'') / s, s = |c'|,
///        s' = t . c'', s'' = t' . c'' + t . c'''. c''' is exact for ellipses and circles
///        (c''' = -c') and a central difference of c'' otherwise; only Hessians use it.
struct FootJet {
  Vec2 c0, c1, c2, t0, t1, t2;
};
FootJet footJet(const Shape& shape, double xi, bool second_order);

/// \brief c and t at xi for any scalar: the jet evaluated at d = xi - xi0, exact in value,
///        first and second derivatives.
template <class S>
void footPoint(const Shape& shape, const S& xi, FootPoint<S>& out) {
  const double x0 = scalarValue(xi);
  const FootJet j = footJet(shape, x0, AdOrder<S>::value >= 2);
  if constexpr (AdOrder<S>::value == 0) {
    out.c = j.c0;
    out.t = j.t0;
  } else {
    const S d = xi - x0;
    for (int a = 0; a < 2; ++a) {
      out.c[a] = j.c0[a] + d * (j.c1[a] + 0.5 * j.c2[a] * d);
      out.t[a] = j.t0[a] + d * (j.t1[a] + 0.5 * j.t2[a] * d);
    }
  }
}

/// \brief Rotation R(a) b for any scalar.
template <class S>
Vec2T<S> rotated(const S& ca, const S& sa, const Vec2T<S>& b) {
  return Vec2T<S>(ca * b[0] - sa * b[1], sa * b[0] + ca * b[1]);
}

/// \brief Generalized force of contact i on (x, y, phi, theta, l_i), the non-zero entries
///        of G1_i f_n + T_i f_t (docs/model.md): equations::contactColumn for the world force
///        f = f_n n_i + f_t t_i at the foot point of xi [N, N m].
template <class S>
void contactWrench(const RbsfModel& model, int i, const S& phi, const S& theta, const S& l,
                   const S& fn, const S& ft, const S& xi, S* w) {
  using std::cos;
  using std::sin;
  FootPoint<S> foot;
  footPoint(model.shape(), xi, foot);
  const S cp = cos(phi), sp = sin(phi), ct = cos(theta), st = sin(theta);
  // Force in the object frame (n = S t), then world; the lever R(phi) c; the tip
  // R(theta)(r_i, l_i); the finger's axis R(theta)(0, 1).
  const Vec2T<S> f_local(fn * (-foot.t[1]) + ft * foot.t[0], fn * foot.t[0] + ft * foot.t[1]);
  const Vec2T<S> f = rotated<S>(cp, sp, f_local);
  const Vec2T<S> lever = rotated<S>(cp, sp, foot.c);
  const double r = model.cell().fingers[i].r;
  const S px = ct * r - st * l, py = st * r + ct * l;
  const S ax = -st;
  equations::contactColumn<S>(lever[0], lever[1], px, py, ax, ct, f[0], f[1], w);
}

/// \brief out = M(q) a (dynamics/equations.h), without forming M. q is read from z at
///        offset oq.
template <class S>
void massTimes(const Cell& cell, const S* z, int oq, const ConfigVector<S>& a,
               ConfigVector<S>& out) {
  const int m = cell.numFingers();
  out.resize(layout::configDim(m));
  out[layout::kX] = cell.object.mass * a[layout::kX];
  out[layout::kY] = cell.object.mass * a[layout::kY];
  out[layout::kPhi] = cell.object.inertia * a[layout::kPhi];
  S base = equations::baseInertia<S>(cell, z + oq) * a[layout::kTheta];
  for (int i = 0; i < m; ++i) {
    const FingerParams& f = cell.fingers[i];
    base += f.mass * f.r * a[layout::stroke(i)];
    out[layout::stroke(i)] = f.mass * f.r * a[layout::kTheta] + f.mass * a[layout::stroke(i)];
  }
  out[layout::kTheta] = base;
}

/// \brief r = u(tau) + sum_i (G1_i f_n,i + T_i f_t,i) - Q(q, v): the right-hand side of
///        M(q) dv/dt = r at one knot whose block starts at z[o] (DecisionLayout local
///        offsets), with that knot's contact forces f_n, f_t. Forces act at the foot points
///        x_o + R(phi) c(xi_i); the mechanism side is -J_i^T f_i with J_i's columns S p_i
///        (theta) and R(theta)(0, 1) (l_i).
template <class S>
void knotRhs(const RbsfModel& model, const DecisionLayout& dl, const S* z, int o,
             ConfigVector<S>& r) {
  const Cell& cell = model.cell();
  const int m = model.numFingers();
  const int n = layout::configDim(m);
  r.resize(n);
  const S* q = &z[o];
  const S* v = &z[o + dl.localV()];
  const S* tau = &z[o + dl.localTau()];
  const S* fn = &z[o + dl.localFn()];
  const S* ft = &z[o + dl.localFt()];
  const S* xi = &z[o + dl.localXi()];
  equations::bias<S>(cell, q, v, r);
  for (int a = 0; a < n; ++a) r[a] = -r[a];
  for (int j = 0; j < layout::controlDim(m); ++j) r[layout::inputToConfig(j)] += tau[j];
  // Contact forces.
  S w[5];
  for (int i = 0; i < m; ++i) {
    contactWrench<S>(model, i, q[layout::kPhi], q[layout::kTheta], q[layout::stroke(i)], fn[i],
                     ft[i], xi[i], w);
    r[layout::kX] += w[0];
    r[layout::kY] += w[1];
    r[layout::kPhi] += w[2];
    r[layout::kTheta] += w[3];
    r[layout::stroke(i)] += w[4];
  }
}

}  // namespace rbsf::trajopt

namespace rbsf::trajopt {

/// \brief First-order AutoDiff over N local variables (stack storage).
template <int N>
using ADN = Eigen::AutoDiffScalar<Eigen::Matrix<double, N, 1>>;
/// \brief Second-order (nested) AutoDiff over N local variables: for y of this type,
///        y.value().derivatives() is the gradient and y.derivatives()[a].derivatives()[b]
///        the Hessian entry (a, b).
template <int N>
using ADNx2 = Eigen::AutoDiffScalar<Eigen::Matrix<ADN<N>, N, 1>>;
/// \brief First- and second-order AutoDiff over 6 local variables (contact elements).
using AD6 = ADN<6>;
using AD6x2 = ADNx2<6>;

/// \brief Seed out[a] as the a-th of N independent variables with value x[a].
template <int N>
void seedSecondOrder(const double* x, ADNx2<N>* out) {
  for (int a = 0; a < N; ++a) {
    out[a].value() = ADN<N>(x[a], N, a);
    out[a].derivatives().setConstant(ADN<N>(0.0));
    out[a].derivatives()[a] = ADN<N>(1.0);
  }
}

}  // namespace rbsf::trajopt
