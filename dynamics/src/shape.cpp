#include "rbsf/dynamics/shape.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "rbsf/dynamics/errors.h"

namespace rbsf {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

std::string fmt(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

void requirePositive(const char* name, double v) {
  if (!(std::isfinite(v) && v > 0.0))
    throw InputError(std::string("shape.") + name + " must be positive and finite (got " + fmt(v) +
                     ")");
}

void requireFinite(const Vec2& center) {
  if (!center.allFinite())
    throw InputError("shape.center must be finite (got [" + fmt(center.x()) + ", " +
                     fmt(center.y()) + "])");
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Base class

double Shape::wrap(double xi) {
  double r = std::fmod(xi, kTwoPi);
  if (r < 0.0) r += kTwoPi;
  // fmod of a tiny negative number plus 2 pi can round up to exactly 2 pi.
  return r >= kTwoPi ? 0.0 : r;
}

Vec2 Shape::point(double xi) const {
  Vec2 c, dc, ddc;
  derivatives(xi, c, dc, ddc);
  return c;
}

BoundaryPoint Shape::boundary(double xi) const {
  Vec2 c, dc, ddc;
  derivatives(xi, c, dc, ddc);
  BoundaryPoint b;
  b.point = c;
  b.speed = dc.norm();
  b.tangent = dc / b.speed;
  b.normal = perp(b.tangent);
  b.curvature = cross(dc, ddc) / (b.speed * b.speed * b.speed);
  return b;
}

ClosestPoint Shape::closest(const Vec2& p) const {
  // Preliminary: coarse scan plus Newton (replaced by the robust version below).
  constexpr int kN = 256;
  double best_xi = 0.0, best_d2 = INFINITY;
  for (int k = 0; k < kN; ++k) {
    const double xi = kTwoPi * k / kN;
    const double d2 = (point(xi) - p).squaredNorm();
    if (d2 < best_d2) best_d2 = d2, best_xi = xi;
  }
  double xi = best_xi;
  for (int it = 0; it < 30; ++it) {
    Vec2 c, dc, ddc;
    derivatives(xi, c, dc, ddc);
    const Vec2 r = c - p;
    const double fp = ddc.dot(r) + dc.squaredNorm();
    if (fp <= 0.0) break;
    const double step = -dc.dot(r) / fp;
    xi += std::clamp(step, -kTwoPi / kN, kTwoPi / kN);
    if (std::abs(step) < 1e-15) break;
  }
  const BoundaryPoint b = boundary(xi);
  const double d = (p - b.point).norm();
  return {wrap(xi), b.point, (p - b.point).dot(b.normal) > 0.0 ? -d : d};
}

ClosestPoint Shape::closestNear(const Vec2& p, double /*xi_hint*/) const { return closest(p); }

bool Shape::entryAlongLine(const Vec2& /*origin*/, const Vec2& /*dir*/, double& /*s*/,
                           double& /*xi*/) const {
  return false;
}

// ---------------------------------------------------------------------------------------------
// Ellipse

EllipseShape::EllipseShape(double a, double b, const Vec2& center) : a_(a), b_(b), center_(center) {
  requirePositive("a", a);
  requirePositive("b", b);
  requireFinite(center);
}

void EllipseShape::derivatives(double xi, Vec2& c, Vec2& dc, Vec2& ddc) const {
  const double cs = std::cos(xi), sn = std::sin(xi);
  c = center_ + Vec2(a_ * cs, b_ * sn);
  dc = Vec2(-a_ * sn, b_ * cs);
  ddc = Vec2(-a_ * cs, -b_ * sn);
}

double EllipseShape::boundingRadius() const { return center_.norm() + std::max(a_, b_); }

// ---------------------------------------------------------------------------------------------
// Circle

CircleShape::CircleShape(double radius, const Vec2& center) : r_(radius), center_(center) {
  requirePositive("radius", radius);
  requireFinite(center);
}

void CircleShape::derivatives(double xi, Vec2& c, Vec2& dc, Vec2& ddc) const {
  const double cs = std::cos(xi), sn = std::sin(xi);
  c = center_ + r_ * Vec2(cs, sn);
  dc = r_ * Vec2(-sn, cs);
  ddc = -r_ * Vec2(cs, sn);
}

double CircleShape::boundingRadius() const { return center_.norm() + r_; }

ClosestPoint CircleShape::closest(const Vec2& p) const {
  const Vec2 d = p - center_;
  const double len = d.norm();
  // At the centre every boundary point is closest; pick xi = 0.
  const double xi = len > 0.0 ? wrap(std::atan2(d.y(), d.x())) : 0.0;
  return {xi, center_ + r_ * Vec2(std::cos(xi), std::sin(xi)), len - r_};
}

// ---------------------------------------------------------------------------------------------
// Superellipse

SuperellipseShape::SuperellipseShape(double a, double b, double exponent, const Vec2& center)
    : a_(a), b_(b), n_(exponent), center_(center) {
  requirePositive("a", a);
  requirePositive("b", b);
  if (!(exponent >= 2.0 && exponent <= 20.0))
    throw InputError("shape.exponent must be in [2, 20] (got " + fmt(exponent) + ")");
  requireFinite(center);
}

void SuperellipseShape::derivatives(double xi, Vec2& c, Vec2& dc, Vec2& ddc) const {
  // F(xi) = |u|^n + |v|^n with u = cos/a, v = sin/b; rho = F^(-1/n). Only the ratios F'/F and
  // F''/F are needed, so u, v and their derivatives are scaled by max(|u|, |v|) first: that
  // keeps |u|^n away from overflow/underflow for any a, b and n <= 20.
  const double cs = std::cos(xi), sn = std::sin(xi);
  const double n = n_;
  double u = cs / a_, v = sn / b_, du = -sn / a_, dv = cs / b_;
  const double scale = std::max(std::abs(u), std::abs(v));
  u /= scale, v /= scale, du /= scale, dv /= scale;
  // |x|^(n-2) is finite and continuous for n >= 2 (pow(0, 0) = 1), so every term below is.
  const double pu = std::pow(std::abs(u), n - 2.0), pv = std::pow(std::abs(v), n - 2.0);
  const double g = pu * u * u + pv * v * v;               // F / scale^n, in [1, 2]
  const double fa = n * (pu * u * du + pv * v * dv) / g;  // F'/F (u'' = -u, v'' = -v)
  const double fb = n * ((n - 1.0) * (pu * du * du + pv * dv * dv) - (pu * u * u + pv * v * v)) / g;
  const double rho = 1.0 / (scale * std::pow(g, 1.0 / n));
  const double drho = -rho * fa / n;
  const double ddrho = -(drho * fa + rho * (fb - fa * fa)) / n;
  const Vec2 w(cs, sn), wp(-sn, cs);
  c = center_ + rho * w;
  dc = drho * w + rho * wp;
  ddc = (ddrho - rho) * w + 2.0 * drho * wp;
}

double SuperellipseShape::boundingRadius() const { return center_.norm() + std::hypot(a_, b_); }

}  // namespace rbsf
