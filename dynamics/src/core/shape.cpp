#include "rbsf/dynamics/core/shape.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "rbsf/dynamics/core/errors.h"

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

struct Sample {
  double x;
  Vec2 c, dc, ddc;
};

Sample sampleAt(const Shape& shape, double x) {
  Sample s{x, {}, {}, {}};
  shape.derivatives(x, s.c, s.dc, s.ddc);
  return s;
}

// Visits a and the samples inside (a, b), bisecting while the tangent turns by more than
// kMaxTurn between neighbours.
template <class Visit>
void scanInterval(const Shape& shape, const Sample& a, const Sample& b, int depth, Visit& visit) {
  constexpr double kMaxTurn = 0.15;
  double turn = std::atan2(cross(a.dc, b.dc), a.dc.dot(b.dc));
  if (turn < 0.0) turn += kTwoPi;  // a convex arc turns by (0, 2 pi)
  if (depth == 0 || turn <= kMaxTurn) {
    visit(a);
    return;
  }
  const Sample m = sampleAt(shape, 0.5 * (a.x + b.x));
  scanInterval(shape, a, m, depth - 1, visit);
  scanInterval(shape, m, b, depth - 1, visit);
}

// Calls visit(sample) for increasing x covering [0, 2 pi): a uniform grid, refined where the
// tangent turns quickly (superellipse corners, whose polar parametrisation crowds them into a
// tiny range of xi; ellipse vertices of high aspect ratio). Between neighbouring samples the
// curve is then nearly straight, so separate local minima of the distance and the zeros of
// dir.c' fall into separate intervals.
template <class Visit>
void scanBoundary(const Shape& shape, Visit&& visit) {
  constexpr int kCoarse = 64, kDepth = 24;
  Sample a = sampleAt(shape, 0.0);
  for (int k = 1; k <= kCoarse; ++k) {
    const Sample b = sampleAt(shape, kTwoPi * k / kCoarse);
    scanInterval(shape, a, b, kDepth, visit);
    a = b;
  }
}

// Local minimiser of |c(x) - p|^2 in (lo, hi), given a start x whose value is not above the
// values at lo and hi. Newton on f = c'.(c - p) where it stays inside the bracket and
// descends; golden-section steps otherwise, which keeps the bracket shrinking.
double minimizeDistance(const Shape& shape, const Vec2& p, double lo, double x, double hi) {
  constexpr double kGold = 0.3819660112501051;
  Vec2 c, dc, ddc;
  shape.derivatives(x, c, dc, ddc);
  double d2 = (c - p).squaredNorm(), f = dc.dot(c - p), fp = ddc.dot(c - p) + dc.squaredNorm();
  for (int it = 0; it < 200 && hi - lo > 1e-15 * (1.0 + std::abs(x)); ++it) {
    const double step = -f / fp;
    const bool newton = fp > 0.0 && x + step > lo && x + step < hi;
    const double xn =
        newton ? x + step : (hi - x > x - lo ? x + kGold * (hi - x) : x - kGold * (x - lo));
    shape.derivatives(xn, c, dc, ddc);
    const double d2n = (c - p).squaredNorm();
    // Once Newton converges quadratically, rounding in d2 cannot rank the iterates any more.
    const bool converging = newton && std::abs(step) < 1e-7;
    if (converging || d2n < d2) {
      (xn > x ? lo : hi) = x;
      x = xn, d2 = d2n, f = dc.dot(c - p), fp = ddc.dot(c - p) + dc.squaredNorm();
      if (converging && std::abs(step) < 1e-14) break;
    } else {
      (xn > x ? hi : lo) = xn;
    }
  }
  return x;
}

// Root of fn (fn(x, f, f') fills value and derivative) in the bracket [a, b] whose ends have
// values of opposite sign (or zero): Newton, falling back to bisection when it leaves the
// bracket.
template <class Fn>
double findRoot(Fn&& fn, double a, double b) {
  double fa, fb, d;
  fn(a, fa, d);
  fn(b, fb, d);
  if (fa == 0.0) return a;
  if (fb == 0.0) return b;
  double neg = fa < 0.0 ? a : b, pos = fa < 0.0 ? b : a;
  double x = 0.5 * (a + b);
  for (int it = 0; it < 200; ++it) {
    double f, fp;
    fn(x, f, fp);
    if (f == 0.0) return x;
    (f < 0.0 ? neg : pos) = x;
    double xn = x - f / fp;
    if (!((xn - neg) * (xn - pos) <= 0.0)) xn = 0.5 * (neg + pos);
    const double tol = 1e-15 * (1.0 + std::abs(x));
    if (std::abs(xn - x) <= tol || std::abs(pos - neg) <= tol) return xn;
    x = xn;
  }
  return x;
}

ClosestPoint makeClosest(const Shape& shape, const Vec2& p, double x) {
  Vec2 c, dc, ddc;
  shape.derivatives(x, c, dc, ddc);
  const double d = (p - c).norm();
  return {Shape::wrap(x), c, (p - c).dot(perp(dc)) > 0.0 ? -d : d};
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
  return geometry(c, dc, ddc);
}

BoundaryPoint Shape::geometry(const Vec2& c, const Vec2& dc, const Vec2& ddc) {
  BoundaryPoint b;
  b.point = c;
  b.speed = dc.norm();
  b.tangent = dc / b.speed;
  b.normal = perp(b.tangent);
  b.curvature = cross(dc, ddc) / (b.speed * b.speed * b.speed);
  return b;
}

ClosestPoint Shape::closest(const Vec2& p) const {
  // Every local minimum of the sampled squared distance is refined; the scan resolves the
  // tangent direction finely enough that distinct minima (e.g. on two sides of a superellipse
  // corner) fall into distinct brackets.
  struct Node {
    double x, d2;
  };
  double best_x = 0.0, best_d2 = INFINITY;
  auto consider = [&](const Node& lo, const Node& mid, const Node& hi) {
    if (mid.d2 > lo.d2 || mid.d2 > hi.d2) return;
    const double x = minimizeDistance(*this, p, lo.x, mid.x, hi.x);
    const double d2 = (point(x) - p).squaredNorm();
    if (d2 < best_d2) best_d2 = d2, best_x = x;
  };
  Node first{}, second{}, prev2{}, prev1{};
  int count = 0;
  scanBoundary(*this, [&](const Sample& s) {
    const Node node{s.x, (s.c - p).squaredNorm()};
    if (count == 0) first = node;
    if (count == 1) second = node;
    if (count >= 2) consider(prev2, prev1, node);
    prev2 = prev1, prev1 = node, ++count;
  });
  consider(prev2, prev1, {first.x + kTwoPi, first.d2});
  consider({prev1.x - kTwoPi, prev1.d2}, first, second);
  return makeClosest(*this, p, best_x);
}

ClosestPoint Shape::closestNear(const Vec2& p, double xi_hint, BoundaryPoint* at) const {
  double x = xi_hint;
  Vec2 c, dc, ddc;
  for (int it = 0; it < 8; ++it) {
    derivatives(x, c, dc, ddc);
    const double fp = ddc.dot(c - p) + dc.squaredNorm();
    if (!(fp > 0.0)) break;  // not in the basin of a minimum
    const double step = -dc.dot(c - p) / fp;
    if (!(std::abs(step) < 0.5)) break;
    if (std::abs(step) > 1e-12) {
      x += step;
      continue;
    }
    // Converged at x (the last step moves c by under 1e-12 |c'|): reuse this evaluation.
    const double depth = (p - c).dot(perp(dc).normalized());
    // Outside, a critical point with p on its outer side is the metric projection onto the
    // convex set, hence unique. Inside, a disc of the smallest radius of curvature rolls freely
    // along the boundary (Blaschke), so a local minimum no deeper than that radius is global.
    if (depth <= 0.0 || depth <= minCurvatureRadius()) {
      if (at) *at = geometry(c, dc, ddc);
      return {wrap(x), c, depth > 0.0 ? -(p - c).norm() : (p - c).norm()};
    }
    break;
  }
  const ClosestPoint global = closest(p);
  if (at) *at = boundary(global.xi);
  return global;
}

ClosestPoint CircleShape::closestNear(const Vec2& p, double, BoundaryPoint* at) const {
  const ClosestPoint cp = closest(p);  // closed form: no iteration to warm-start
  if (at) *at = boundary(cp.xi);
  return cp;
}

bool Shape::entryAlongLine(const Vec2& origin, const Vec2& dir, double& s, double& xi) const {
  // g(xi) = (S dir).(c - origin) is the signed offset of c from the line. On a convex curve g
  // has one maximum and one minimum (where c' is parallel to dir) and is monotone between
  // them, so each arc holds exactly one crossing when min g <= 0 <= max g.
  const Vec2 u = perp(dir);
  auto support = [&](double x, double& f, double& fp) {
    Vec2 c, dc, ddc;
    derivatives(x, c, dc, ddc);
    f = u.dot(dc), fp = u.dot(ddc);
  };
  auto offset = [&](double x, double& f, double& fp) {
    Vec2 c, dc, ddc;
    derivatives(x, c, dc, ddc);
    f = u.dot(c - origin), fp = u.dot(dc);
  };
  double up_lo = NAN, down_lo = NAN, first_x = 0.0, prev_x = 0.0, prev_h = 0.0, first_h = 0.0;
  double step_up = 0.0, step_down = 0.0;
  int count = 0;
  auto edge = [&](double x0, double h0, double x1, double h1) {
    if (h0 <= 0.0 && h1 > 0.0) up_lo = x0, step_up = x1 - x0;
    if (h0 > 0.0 && h1 <= 0.0) down_lo = x0, step_down = x1 - x0;
  };
  scanBoundary(*this, [&](const Sample& smp) {
    const double h = u.dot(smp.dc);
    if (count == 0) first_x = smp.x, first_h = h;
    if (count > 0) edge(prev_x, prev_h, smp.x, h);
    prev_x = smp.x, prev_h = h, ++count;
  });
  edge(prev_x, prev_h, first_x + kTwoPi, first_h);
  if (std::isnan(up_lo) || std::isnan(down_lo)) return false;  // degenerate direction
  const double x_min = findRoot(support, up_lo, up_lo + step_up);
  double x_max = findRoot(support, down_lo, down_lo + step_down);
  double f_min, f_max, fp;
  offset(x_min, f_min, fp);
  offset(x_max, f_max, fp);
  if (f_min > 0.0 || f_max < 0.0) return false;
  if (x_max < x_min) x_max += kTwoPi;
  const double roots[2] = {findRoot(offset, x_min, x_max), findRoot(offset, x_max, x_min + kTwoPi)};
  const double scale = 1.0 / dir.squaredNorm();
  s = INFINITY;
  for (double x : roots) {
    const double sx = dir.dot(point(x) - origin) * scale;
    if (sx < s) s = sx, xi = wrap(x);
  }
  return true;
}

namespace {

// The first crossing of origin + s dir with c(xi) = e + (a cos xi, b sin xi): in the scaled
// frame where the ellipse is the unit circle, |P + s D|^2 = 1 is a quadratic in s.
bool ellipseEntry(const Vec2& e, double a, double b, const Vec2& origin, const Vec2& dir, double& s,
                  double& xi) {
  const Vec2 P((origin.x() - e.x()) / a, (origin.y() - e.y()) / b);
  const Vec2 D(dir.x() / a, dir.y() / b);
  const double dd = D.squaredNorm(), pd = P.dot(D);
  const double disc = pd * pd - dd * (P.squaredNorm() - 1.0);
  if (!(disc >= 0.0) || !(dd > 0.0)) return false;
  s = (-pd - std::sqrt(disc)) / dd;
  const Vec2 hit = P + s * D;
  xi = Shape::wrap(std::atan2(hit.y(), hit.x()));
  return true;
}

}  // namespace

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

bool EllipseShape::entryAlongLine(const Vec2& origin, const Vec2& dir, double& s,
                                  double& xi) const {
  return ellipseEntry(center_, a_, b_, origin, dir, s, xi);
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

bool CircleShape::entryAlongLine(const Vec2& origin, const Vec2& dir, double& s, double& xi) const {
  return ellipseEntry(center_, r_, r_, origin, dir, s, xi);
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
  // No closed form for n > 2: the largest curvature over the scan samples is within 2% of
  // the true maximum for n in [2, 20] and aspect ratios up to 100; a factor 2 covers that.
  double kappa_max = 0.0;
  scanBoundary(*this, [&](const Sample& t) {
    kappa_max = std::max(kappa_max, cross(t.dc, t.ddc) / std::pow(t.dc.norm(), 3));
  });
  min_curvature_radius_ = 0.5 / kappa_max;
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
  const double fb = n * ((n - 1.0) * (pu * du * du + pv * dv * dv) - g) / g;  // F''/F
  const double rho = 1.0 / (scale * std::pow(g, 1.0 / n));
  const double drho = -rho * fa / n;
  const double ddrho = -(drho * fa + rho * (fb - fa * fa)) / n;
  const Vec2 w(cs, sn), wp(-sn, cs);
  c = center_ + rho * w;
  dc = drho * w + rho * wp;
  ddc = (ddrho - rho) * w + 2.0 * drho * wp;
  // On the flat sides c' x c'' = rho^2 + 2 rho'^2 - rho rho'' cancels to ~ |u|^(n-2) and the
  // formula above returns rounding noise of either sign. By Lagrange's identity it equals
  // (n-1) rho^2 |u|^(n-2) |v|^(n-2) (u v' - u' v)^2 / G^2 with u v' - u' v = 1/(a b scale^2),
  // so the normal part of c'' is rebuilt from that: curvature stays >= 0 to full precision.
  const double k = 1.0 / (a_ * b_ * scale * scale * g);
  const double normal = (n - 1.0) * rho * rho * pu * pv * k * k;  // c' x c''
  const double speed2 = dc.squaredNorm();
  ddc = (dc.dot(ddc) * dc + normal * perp(dc)) / speed2;
}

double SuperellipseShape::boundingRadius() const { return center_.norm() + std::hypot(a_, b_); }

double SuperellipseShape::minCurvatureRadius() const { return min_curvature_radius_; }

std::shared_ptr<const Shape> EllipseShape::shifted(const Vec2& d) const {
  return std::make_shared<EllipseShape>(a_, b_, center_ + d);
}

std::shared_ptr<const Shape> CircleShape::shifted(const Vec2& d) const {
  return std::make_shared<CircleShape>(r_, center_ + d);
}

std::shared_ptr<const Shape> SuperellipseShape::shifted(const Vec2& d) const {
  return std::make_shared<SuperellipseShape>(a_, b_, n_, center_ + d);
}

}  // namespace rbsf
