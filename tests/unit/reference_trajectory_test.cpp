// ReferenceTrajectory: the Hermite interpolant passes through the knots with their
// velocities, v_ref is the derivative of q_ref (central differences), tau follows the held
// and ramped pieces, t is clamped outside the plan, and bad input is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rbsf/dynamics/control/reference_trajectory.h"
#include "rbsf/dynamics/core/errors.h"

namespace rbsf {
namespace {

constexpr int kN = 7;  // m = 3

ReferenceTrajectory makeReference() {
  ReferenceTrajectory r;
  // Uneven knots of a smooth curve with its exact velocities.
  const double ts[] = {0.0, 0.05, 0.13, 0.2, 0.37, 0.5};
  for (double t : ts) {
    VecQ q(kN), v(kN);
    for (int k = 0; k < kN; ++k) {
      q[k] = (1.0 + k) * std::sin(1.3 * t + k);
      v[k] = 1.3 * (1.0 + k) * std::cos(1.3 * t + k);
    }
    r.addKnot(t, q, v);
  }
  VecU a(4), b(4), c(4);
  a << 10, 20, 30, 40;
  b << -5, 0, 5, 10;
  c << 1, 2, 3, 4;
  r.addInputPiece(0.0, 0.2, a, VecU(), Phase::kC);  // held
  r.addInputPiece(0.2, 0.2, b, c, Phase::kU);       // ramp b -> c
  r.addInputPiece(0.4, 0.1, c, VecU(), Phase::kP);
  return r;
}

TEST(ReferenceTrajectory, PassesThroughKnotsWithTheirVelocities) {
  const ReferenceTrajectory r = makeReference();
  ReferenceSample s;
  for (double t : {0.0, 0.05, 0.13, 0.2, 0.37, 0.5}) {
    r.sample(t, s);
    for (int k = 0; k < kN; ++k) {
      EXPECT_NEAR(s.q[k], (1.0 + k) * std::sin(1.3 * t + k), 1e-12) << "t = " << t;
      EXPECT_NEAR(s.v[k], 1.3 * (1.0 + k) * std::cos(1.3 * t + k), 1e-11) << "t = " << t;
    }
  }
  // Between knots a cubic Hermite of a smooth curve is accurate to O(d^4).
  r.sample(0.3, s);
  EXPECT_NEAR(s.q[0], std::sin(1.3 * 0.3), 1e-4);
}

TEST(ReferenceTrajectory, VelocityIsTheDerivativeOfPosition) {
  const ReferenceTrajectory r = makeReference();
  ReferenceSample a, b, c;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(0.001, 0.499);
  const double e = 1e-6;
  for (int n = 0; n < 50; ++n) {
    const double t = U(rng);
    r.sample(t, a);
    r.sample(t + e, b);
    r.sample(t - e, c);
    const VecQ fd = (b.q - c.q) / (2 * e);
    EXPECT_LE((fd - a.v).cwiseAbs().maxCoeff(), 1e-6) << "t = " << t;
  }
}

TEST(ReferenceTrajectory, InputFollowsHeldAndRampedPieces) {
  const ReferenceTrajectory r = makeReference();
  ReferenceSample s;
  r.sample(0.1, s);
  EXPECT_EQ(s.tau[2], 30.0);  // held: exact
  EXPECT_EQ(s.phase, Phase::kC);
  r.sample(0.25, s);  // a quarter of the ramp from b to c
  EXPECT_NEAR(s.tau[0], -5 + 0.25 * 6, 1e-12);
  EXPECT_NEAR(s.tau[3], 10 + 0.25 * -6, 1e-12);
  EXPECT_EQ(s.phase, Phase::kU);
  r.sample(0.45, s);
  EXPECT_EQ(s.tau[1], 2.0);
  EXPECT_EQ(s.phase, Phase::kP);
}

TEST(ReferenceTrajectory, ClampsOutsideThePlan) {
  const ReferenceTrajectory r = makeReference();
  ReferenceSample s, first, last;
  r.sample(0.0, first);
  r.sample(0.5, last);
  r.sample(-1.0, s);
  EXPECT_TRUE(s.q == first.q);
  EXPECT_EQ(s.tau[0], 10.0);
  r.sample(7.0, s);
  EXPECT_TRUE(s.q == last.q);
  EXPECT_TRUE(s.v == last.v);
  EXPECT_EQ(s.tau[3], 4.0);
  EXPECT_EQ(s.t, 0.5);
}

TEST(ReferenceTrajectory, RefusesBadInput) {
  ReferenceTrajectory r;
  const VecQ q = VecQ::Zero(kN);
  r.addKnot(0.1, q, q);
  EXPECT_THROW(r.addKnot(0.1, q, q), InputError);
  EXPECT_THROW(r.addKnot(0.2, VecQ::Zero(5), VecQ::Zero(5)), InputError);
  VecQ bad = q;
  bad[2] = NAN;
  EXPECT_THROW(r.addKnot(0.3, bad, q), InputError);
  const VecU tau = VecU::Zero(4);
  r.addInputPiece(0.0, 0.1, tau, VecU(), Phase::kC);
  EXPECT_THROW(r.addInputPiece(0.2, 0.1, tau, VecU(), Phase::kC), InputError);  // gap
  EXPECT_THROW(r.addInputPiece(0.1, 0.0, tau, VecU(), Phase::kC), InputError);
  EXPECT_THROW(r.addInputPiece(0.1, 0.1, tau, VecU::Zero(3), Phase::kC), InputError);
}

}  // namespace
}  // namespace rbsf
