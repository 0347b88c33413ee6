#include "rbsf/trajopt/ad_dynamics.h"

namespace rbsf::trajopt {

FootJet footJet(const Shape& shape, double xi, bool second_order) {
  Vec2 c, dc, ddc;
  shape.derivatives(xi, c, dc, ddc);
  FootJet j;
  j.c0 = c;
  j.c1 = dc;
  j.c2 = ddc;
  const double s = dc.norm();
  j.t0 = dc / s;
  const double s1 = j.t0.dot(ddc);
  j.t1 = (ddc - j.t0 * s1) / s;
  j.t2.setZero();
  if (second_order) {
    Vec2 dddc;
    if (dynamic_cast<const EllipseShape*>(&shape) || dynamic_cast<const CircleShape*>(&shape)) {
      dddc = -dc;  // c - e is (a cos, b sin): c''' = -c'
    } else {
      constexpr double kStep = 1e-5;
      Vec2 cp, dcp, ddcp, cm, dcm, ddcm;
      shape.derivatives(xi + kStep, cp, dcp, ddcp);
      shape.derivatives(xi - kStep, cm, dcm, ddcm);
      dddc = (ddcp - ddcm) / (2.0 * kStep);
    }
    const double s2 = j.t1.dot(ddc) + j.t0.dot(dddc);
    j.t2 = (dddc - 2.0 * j.t1 * s1 - j.t0 * s2) / s;
  }
  return j;
}

}  // namespace rbsf::trajopt
