#include "rbsf/dynamics/core/shape.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "rbsf/dynamics/core/errors.h"

namespace rbsf {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

enum class Kind { kEllipse, kCircle, kSuperellipse };
const Kind kKinds[] = {Kind::kEllipse, Kind::kCircle, Kind::kSuperellipse};

// A shape of the given kind with random parameters; `exponent` < 0 picks a random one.
std::unique_ptr<Shape> randomShape(Kind kind, std::mt19937& rng, double exponent = -1.0) {
  std::uniform_real_distribution<double> size(0.05, 0.5), off(-0.2, 0.2), ex(2.0, 20.0);
  const Vec2 e(off(rng), off(rng));
  const double a = size(rng), b = size(rng);
  switch (kind) {
    case Kind::kEllipse:
      return std::make_unique<EllipseShape>(a, b, e);
    case Kind::kCircle:
      return std::make_unique<CircleShape>(a, e);
    case Kind::kSuperellipse:
      return std::make_unique<SuperellipseShape>(a, b, exponent < 0.0 ? ex(rng) : exponent, e);
  }
  return nullptr;
}

// Inside test from the implicit equation, independent of the parametrisation: < 0 inside.
double implicitValue(const Shape& s, const Vec2& p) {
  if (const auto* c = dynamic_cast<const CircleShape*>(&s))
    return (p - c->center()).squaredNorm() / (c->radius() * c->radius()) - 1.0;
  if (const auto* e = dynamic_cast<const EllipseShape*>(&s)) {
    const Vec2 q = p - e->center();
    return std::pow(q.x() / e->a(), 2) + std::pow(q.y() / e->b(), 2) - 1.0;
  }
  const auto& se = dynamic_cast<const SuperellipseShape&>(s);
  const Vec2 q = p - se.center();
  return std::pow(std::abs(q.x() / se.a()), se.exponent()) +
         std::pow(std::abs(q.y() / se.b()), se.exponent()) - 1.0;
}

// Reference closest distance: 100000 uniform samples, then golden-section refinement of every
// discrete local minimum (so near-ties between separate minima are resolved too).
double bruteDistance(const Shape& s, const Vec2& p) {
  constexpr int kN = 100000;
  const double h = kTwoPi / kN;
  std::vector<double> d2(kN);
  int best = 0;
  for (int k = 0; k < kN; ++k) {
    d2[k] = (s.point(k * h) - p).squaredNorm();
    if (d2[k] < d2[best]) best = k;
  }
  double result = INFINITY;
  for (int k = 0; k < kN; ++k) {
    const double l = d2[(k + kN - 1) % kN], r = d2[(k + 1) % kN];
    if (k != best && !(d2[k] < l && d2[k] <= r)) continue;
    double lo = (k - 1) * h, hi = (k + 1) * h;
    for (int it = 0; it < 80; ++it) {
      const double m1 = lo + 0.381966 * (hi - lo), m2 = hi - 0.381966 * (hi - lo);
      if ((s.point(m1) - p).squaredNorm() < (s.point(m2) - p).squaredNorm())
        hi = m2;
      else
        lo = m1;
    }
    result = std::min(result, (s.point(0.5 * (lo + hi)) - p).norm());
  }
  return result;
}

// Smallest radius of curvature from a dense scan.
double denseMinCurvatureRadius(const Shape& s) {
  double kmax = 0.0;
  for (int k = 0; k < 20000; ++k) kmax = std::max(kmax, s.boundary(kTwoPi * k / 20000).curvature);
  return 1.0 / kmax;
}

TEST(Shape, DerivativesMatchFiniteDifferences) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> xi_dist(0.0, kTwoPi);
  constexpr double h = 1e-4;
  for (Kind kind : kKinds) {
    for (double exponent : {-1.0, 2.0, 20.0}) {
      auto s = randomShape(kind, rng, exponent);
      const double size = s->boundingRadius();
      for (int i = 0; i < 300; ++i) {
        const double xi = xi_dist(rng);
        Vec2 c, dc, ddc, cp, dcp, ddcp, cm, dcm, ddcm, cp2, dcp2, ddcp2, cm2, dcm2, ddcm2;
        s->derivatives(xi, c, dc, ddc);
        s->derivatives(xi + h, cp, dcp, ddcp);
        s->derivatives(xi - h, cm, dcm, ddcm);
        s->derivatives(xi + 2 * h, cp2, dcp2, ddcp2);
        s->derivatives(xi - 2 * h, cm2, dcm2, ddcm2);
        // Fourth-order central differences.
        const Vec2 fd1 = (8.0 * (cp - cm) - (cp2 - cm2)) / (12.0 * h);
        const Vec2 fd2 = (8.0 * (dcp - dcm) - (dcp2 - dcm2)) / (12.0 * h);
        EXPECT_LE((fd1 - dc).norm(), 1e-6 * std::max(dc.norm(), size)) << s->type() << " xi=" << xi;
        EXPECT_LE((fd2 - ddc).norm(), 1e-6 * std::max(ddc.norm(), size))
            << s->type() << " xi=" << xi;
      }
    }
  }
}

TEST(Shape, ShiftedShapeIsTheSameBoundaryMoved) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.01, 0.01), xi(0.0, kTwoPi);
  for (Kind kind : kKinds) {
    const auto shape = randomShape(kind, rng);
    const Vec2 d(u(rng), u(rng));
    const auto moved = shape->shifted(d);
    EXPECT_EQ(moved->type(), shape->type());
    for (int k = 0; k < 20; ++k) {
      const double x = xi(rng);
      EXPECT_LT((moved->point(x) - shape->point(x) - d).norm(), 1e-14);
      EXPECT_LT((moved->boundary(x).normal - shape->boundary(x).normal).norm(), 1e-14);
      const Vec2 p(u(rng) * 30, u(rng) * 30);
      EXPECT_NEAR(moved->closest(p + d).signed_distance, shape->closest(p).signed_distance, 1e-10);
    }
  }
}

TEST(Shape, BoundaryFrameIsUnitOrthogonalAndInward) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> xi_dist(0.0, kTwoPi);
  for (Kind kind : kKinds) {
    for (int shape = 0; shape < 5; ++shape) {
      auto s = randomShape(kind, rng);
      for (int i = 0; i < 100; ++i) {
        const double xi = xi_dist(rng);
        const BoundaryPoint b = s->boundary(xi);
        Vec2 c, dc, ddc;
        s->derivatives(xi, c, dc, ddc);
        EXPECT_NEAR(b.tangent.norm(), 1.0, 1e-14);
        EXPECT_NEAR(b.normal.norm(), 1.0, 1e-14);
        EXPECT_NEAR(b.tangent.dot(b.normal), 0.0, 1e-14);
        EXPECT_NEAR(cross(b.tangent, b.normal), 1.0, 1e-14);  // n = S t
        EXPECT_NEAR(b.speed, dc.norm(), 1e-14);
        EXPECT_LE((b.point - c).norm(), 1e-15);
        // The superellipse (n > 2) is flat at its axis points, so there its curvature only
        // approaches 0 (it must not go negative beyond rounding).
        if (kind == Kind::kSuperellipse) {
          EXPECT_GE(b.curvature, -1e-20);
        } else {
          EXPECT_GT(b.curvature, 0.0);
        }
        const double eps = 1e-4 * s->boundingRadius();
        EXPECT_LT(implicitValue(*s, b.point + eps * b.normal), 0.0);
        EXPECT_GT(implicitValue(*s, b.point - eps * b.normal), 0.0);
        EXPECT_NEAR(s->closest(b.point + eps * b.normal).signed_distance, -eps, 1e-12);
        // Frenet: dt/ds = kappa n.
        const double h = 1e-5;
        const Vec2 dt = (s->boundary(xi + h).tangent - s->boundary(xi - h).tangent) / (2 * h);
        EXPECT_LE((dt / b.speed - b.curvature * b.normal).norm(), 1e-5 * (1.0 + b.curvature));
      }
    }
  }
}

TEST(Shape, CurvatureMatchesClosedForms) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> xi_dist(0.0, kTwoPi);
  const CircleShape circle(0.37, Vec2(0.1, -0.2));
  const EllipseShape ellipse(0.3, 0.15, Vec2(-0.1, 0.0));
  const SuperellipseShape super2(0.3, 0.15, 2.0);
  for (int i = 0; i < 200; ++i) {
    const double xi = xi_dist(rng);
    EXPECT_NEAR(circle.boundary(xi).curvature, 1.0 / 0.37, 1e-12);
    const double sn = std::sin(xi), cs = std::cos(xi);
    const double expected = 0.3 * 0.15 / std::pow(0.09 * sn * sn + 0.0225 * cs * cs, 1.5);
    EXPECT_NEAR(ellipse.boundary(xi).curvature, expected, 1e-12 * expected);
    // n = 2 is the same ellipse, parametrised by the polar angle instead.
    const Vec2 p = super2.point(xi);
    EXPECT_NEAR(std::atan2(p.y(), p.x()), std::remainder(xi, kTwoPi), 1e-12);
    const double t = std::atan2(p.y() / 0.15, p.x() / 0.3);
    const double st = std::sin(t), ct = std::cos(t);
    const double at_t = 0.3 * 0.15 / std::pow(0.09 * st * st + 0.0225 * ct * ct, 1.5);
    EXPECT_NEAR(super2.boundary(xi).curvature, at_t, 1e-10 * at_t);
  }
}

TEST(Shape, SuperellipseCurvatureIsNonNegativeOnFlatSides) {
  // Near the axis points the curvature ~ |xi|^(n-2) is far below the rounding of c''; a plain
  // c' x c'' returns noise of about 1e-15 of either sign there. It must come out non-negative
  // (up to 1e-20) and decay monotonically towards the axis.
  const SuperellipseShape s(0.3, 0.15, 12.0, Vec2(0.1, -0.05));
  for (double axis : {0.0, std::numbers::pi / 2, std::numbers::pi, 1.5 * std::numbers::pi}) {
    double previous = INFINITY;
    for (double dx = 0.2; dx > 1e-4; dx *= 0.5) {
      const double k = s.boundary(axis + dx).curvature;
      EXPECT_GE(k, -1e-20);
      if (k > 1e-20) {
        EXPECT_LT(k, previous) << dx;
      }
      previous = k;
    }
    EXPECT_NEAR(s.boundary(axis).curvature, 0.0, 1e-20);
  }
}

TEST(Shape, SuperellipseCornerApproachesRectangle) {
  // For large n the boundary hugs the a-by-b rectangle: every point satisfies
  // max(|x|/a, |y|/b) in [2^(-1/n), 1].
  const SuperellipseShape s(0.3, 0.15, 20.0, Vec2(0.05, 0.02));
  for (int k = 0; k < 1000; ++k) {
    const Vec2 q = s.point(kTwoPi * k / 1000) - s.center();
    const double m = std::max(std::abs(q.x()) / 0.3, std::abs(q.y()) / 0.15);
    EXPECT_LE(m, 1.0 + 1e-14);
    EXPECT_GE(m, std::pow(2.0, -1.0 / 20.0) - 1e-14);
  }
}

TEST(Shape, BoundingRadiusContainsShape) {
  std::mt19937 rng(4);
  for (Kind kind : kKinds) {
    for (int shape = 0; shape < 10; ++shape) {
      auto s = randomShape(kind, rng);
      double r = 0.0;
      for (int k = 0; k < 4000; ++k) r = std::max(r, s->point(kTwoPi * k / 4000).norm());
      EXPECT_LE(r, s->boundingRadius());
    }
  }
}

TEST(Shape, WrapIntoPeriod) {
  EXPECT_DOUBLE_EQ(Shape::wrap(1.0), 1.0);
  EXPECT_DOUBLE_EQ(Shape::wrap(-std::numbers::pi / 2), 1.5 * std::numbers::pi);
  EXPECT_NEAR(Shape::wrap(7.0), 7.0 - kTwoPi, 1e-15);
  EXPECT_NEAR(Shape::wrap(-5.0 * kTwoPi + 0.25), 0.25, 1e-14);
  EXPECT_EQ(Shape::wrap(kTwoPi), 0.0);
  const double tiny = Shape::wrap(-1e-20);
  EXPECT_GE(tiny, 0.0);
  EXPECT_LT(tiny, kTwoPi);
}

TEST(Shape, TypeNames) {
  EXPECT_EQ(EllipseShape(1, 2).type(), "ellipse");
  EXPECT_EQ(CircleShape(1).type(), "circle");
  EXPECT_EQ(SuperellipseShape(1, 2, 4).type(), "superellipse");
}

void expectInputError(const std::function<void()>& make, const std::string& message) {
  try {
    make();
    ADD_FAILURE() << "no InputError, expected: " << message;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
  }
}

TEST(Shape, ConstructorsRejectBadParameters) {
  expectInputError([] { (void)EllipseShape(-1, 1); },
                   "shape.a must be positive and finite (got -1)");
  expectInputError([] { (void)EllipseShape(1, 0); }, "shape.b must be positive and finite (got 0)");
  expectInputError([] { (void)EllipseShape(NAN, 1); }, "shape.a");
  expectInputError([] { (void)EllipseShape(1, INFINITY); }, "shape.b");
  expectInputError([] { (void)EllipseShape(1, 1, Vec2(NAN, 0)); }, "shape.center");
  expectInputError([] { (void)CircleShape(-0.5); }, "shape.radius must be positive and finite");
  expectInputError([] { (void)CircleShape(INFINITY); }, "shape.radius");
  expectInputError([] { (void)CircleShape(1, Vec2(0, INFINITY)); }, "shape.center");
  expectInputError([] { (void)SuperellipseShape(0, 1, 4); }, "shape.a");
  expectInputError([] { (void)SuperellipseShape(1, -2, 4); }, "shape.b");
  expectInputError([] { (void)SuperellipseShape(1, 1, 1.9); }, "shape.exponent");
  expectInputError([] { (void)SuperellipseShape(1, 1, 20.5); }, "shape.exponent");
  expectInputError([] { (void)SuperellipseShape(1, 1, NAN); }, "shape.exponent");
  expectInputError([] { (void)SuperellipseShape(1, 1, 4, Vec2(NAN, 0)); }, "shape.center");
  EXPECT_NO_THROW(SuperellipseShape(1, 1, 2));
  EXPECT_NO_THROW(SuperellipseShape(1, 1, 20));
}

TEST(Shape, ClosestMatchesBruteForce) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), xi_dist(0.0, kTwoPi);
  for (Kind kind : kKinds) {
    for (int shape = 0; shape < 8; ++shape) {
      auto s = randomShape(kind, rng);
      const double r = s->boundingRadius();
      for (int i = 0; i < 6; ++i) {
        Vec2 p;
        switch (i % 3) {
          case 0:  // anywhere around the shape, inside or outside
            p = Vec2(unit(rng), unit(rng)) * 1.2 * r;
            break;
          case 1: {  // near the boundary, either side
            const BoundaryPoint b = s->boundary(xi_dist(rng));
            p = b.point + 1e-3 * unit(rng) * r * b.normal;
            break;
          }
          default: {  // inside, anywhere along an inward normal
            const BoundaryPoint b = s->boundary(xi_dist(rng));
            p = b.point + 0.5 * (unit(rng) + 1.0) * r * b.normal;
            if (implicitValue(*s, p) > 0.0) p = b.point + 0.01 * r * b.normal;
            break;
          }
        }
        const ClosestPoint cp = s->closest(p);
        const double ref = bruteDistance(*s, p);
        EXPECT_NEAR(std::abs(cp.signed_distance), ref, 1e-12)
            << s->type() << " p=" << p.transpose();
        EXPECT_NEAR((cp.point - p).norm(), ref, 1e-12);
        EXPECT_LE((s->point(cp.xi) - cp.point).norm(), 1e-12);
        EXPECT_GE(cp.xi, 0.0);
        EXPECT_LT(cp.xi, kTwoPi);
        const double f = implicitValue(*s, p);
        if (std::abs(f) > 1e-9) {
          EXPECT_EQ(cp.signed_distance < 0.0, f < 0.0) << p.transpose();
        }
      }
    }
  }
}

TEST(Shape, ClosestHardCases) {
  const EllipseShape ellipse(0.3, 0.15, Vec2(-0.1, 0.0));
  const SuperellipseShape box(0.3, 0.15, 20.0, Vec2(0.0, 0.05));
  const SuperellipseShape square(0.2, 0.2, 20.0);
  // Aspect ratio 100: the polar parametrisation squeezes each end into |xi| < 0.01.
  const SuperellipseShape sliver(1.0, 0.01, 8.0);
  const EllipseShape needle(1.0, 0.01);
  std::vector<std::pair<const Shape*, Vec2>> cases = {
      {&ellipse, Vec2(-0.1, 0.0)},      // centre: two symmetric minima
      {&ellipse, Vec2(0.125, 0.0005)},  // near the evolute cusp on the major axis
      {&ellipse, Vec2(-0.1, 0.0) + Vec2(0.2249, 0.0)},
      {&ellipse, Vec2(300.0, -400.0)},        // far away
      {&box, Vec2(0.0, 0.05)},                // centre of a nearly rectangular shape
      {&box, Vec2(0.295, 0.19)},              // inside near a corner, closer to the side
      {&box, Vec2(0.28, 0.195)},              // inside near a corner, closer to the top
      {&box, Vec2(0.305, 0.205)},             // outside the corner
      {&box, Vec2(0.1, 0.05 + 0.15)},         // on the flat top
      {&box, Vec2(0.1, 0.05 + 0.15 + 1e-9)},  // just above the flat top
      {&box, Vec2(-1e4, 3e3)},                // far away
      {&square, Vec2(0.0, 0.0)},              // four equal minima
      {&square, Vec2(0.15, 0.149)},
      {&sliver, Vec2(0.99039, -7.88392e-05)},  // inside near the end, closest on a long side
      {&sliver, Vec2(0.982184, 6.17366e-05)},
      {&sliver, Vec2(1.003, 0.0101)},  // outside the corner
      {&needle, Vec2(0.9999, 0.0)},    // inside near the vertex (radius of curvature 1e-4)
      {&needle, Vec2(0.9995, 1e-5)},   // on the diagonal near a corner
  };
  for (const auto& [s, p] : cases) {
    const ClosestPoint cp = s->closest(p);
    EXPECT_NEAR(std::abs(cp.signed_distance), bruteDistance(*s, p), 1e-12 * (1.0 + p.norm()))
        << s->type() << " p=" << p.transpose();
    const double f = implicitValue(*s, p);
    if (std::abs(f) > 1e-9) {
      EXPECT_EQ(cp.signed_distance < 0.0, f < 0.0) << p.transpose();
    }
  }
  // Closed-form circle: the centre is at distance -r from every boundary point.
  const CircleShape circle(0.25, Vec2(1.0, 2.0));
  EXPECT_DOUBLE_EQ(circle.closest(Vec2(1.0, 2.0)).signed_distance, -0.25);
  const ClosestPoint cc = circle.closest(Vec2(1.0, 3.0));
  EXPECT_NEAR(cc.signed_distance, 0.75, 1e-15);
  EXPECT_NEAR(cc.xi, std::numbers::pi / 2, 1e-15);
  EXPECT_LE((cc.point - Vec2(1.0, 2.25)).norm(), 1e-15);
}

TEST(Shape, SignedDistanceAlongNormal) {
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> u01(0.0, 1.0), xi_dist(0.0, kTwoPi);
  for (Kind kind : kKinds) {
    for (int shape = 0; shape < 5; ++shape) {
      auto s = randomShape(kind, rng);
      const double rho_min = denseMinCurvatureRadius(*s);
      for (int i = 0; i < 40; ++i) {
        const double xi = xi_dist(rng);
        const BoundaryPoint b = s->boundary(xi);
        const double out = 0.1 * u01(rng) * s->boundingRadius();
        const ClosestPoint co = s->closest(b.point - out * b.normal);
        EXPECT_NEAR(co.signed_distance, out, 1e-12);
        EXPECT_NEAR(std::remainder(co.xi - xi, kTwoPi), 0.0, 1e-9);
        // A disc of radius rho_min rolls inside, so depths below it are exact.
        const double in = 0.9 * u01(rng) * rho_min;
        EXPECT_NEAR(s->closest(b.point + in * b.normal).signed_distance, -in, 1e-12);
      }
    }
  }
}

TEST(Shape, ClosestNearAgreesWithClosest) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), xi_dist(0.0, kTwoPi);
  for (Kind kind : kKinds) {
    for (int shape = 0; shape < 6; ++shape) {
      auto s = randomShape(kind, rng);
      const double r = s->boundingRadius();
      for (int i = 0; i < 60; ++i) {
        const double xi = xi_dist(rng);
        const BoundaryPoint b = s->boundary(xi);
        // Mostly small penetrations and gaps, as in simulation; some deep or far points.
        const double depth = (i % 4 == 3 ? 0.8 : 1e-3) * unit(rng) * r;
        const Vec2 p = b.point + depth * b.normal;
        const ClosestPoint ref = s->closest(p);
        for (double hint : {xi + 0.02 * unit(rng), ref.xi + 1e-6, xi + std::numbers::pi}) {
          const ClosestPoint near = s->closestNear(p, hint);
          EXPECT_NEAR(near.signed_distance, ref.signed_distance, 1e-12) << s->type();
          EXPECT_NEAR((near.point - p).norm(), std::abs(ref.signed_distance), 1e-12);
          EXPECT_GE(near.xi, 0.0);
          EXPECT_LT(near.xi, kTwoPi);
        }
      }
    }
  }
}

TEST(Shape, EntryAlongLineHitsBoundaryFirst) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), angle(0.0, kTwoPi);
  for (Kind kind : kKinds) {
    for (int shape = 0; shape < 6; ++shape) {
      auto s = randomShape(kind, rng);
      const SuperellipseShape* se = dynamic_cast<const SuperellipseShape*>(s.get());
      const Vec2 centre =
          se ? se->center()
             : (kind == Kind::kEllipse ? dynamic_cast<const EllipseShape&>(*s).center()
                                       : dynamic_cast<const CircleShape&>(*s).center());
      const double r = s->boundingRadius();
      for (int i = 0; i < 30; ++i) {
        // Aim from outside (or, every third line, from inside) at a point near the centre.
        const Vec2 target = centre + 0.02 * Vec2(unit(rng), unit(rng));
        const double a = angle(rng);
        const Vec2 origin = i % 3 == 2 ? target : target + 3.0 * r * Vec2(std::cos(a), std::sin(a));
        const Vec2 dir =
            i % 3 == 2 ? Vec2(std::cos(a), std::sin(a)) : Vec2((target - origin).normalized());
        double s_hit = NAN, xi = NAN;
        ASSERT_TRUE(s->entryAlongLine(origin, dir, s_hit, xi));
        const Vec2 hit = origin + s_hit * dir;
        EXPECT_LE((s->point(xi) - hit).norm(), 1e-12);
        EXPECT_NEAR(s->closest(hit).signed_distance, 0.0, 1e-12);
        EXPECT_GT(s->closest(origin + (s_hit - 1e-6) * dir).signed_distance, 0.0);
        EXPECT_LT(s->closest(origin + (s_hit + 1e-6) * dir).signed_distance, 0.0);
        if (i % 3 == 2) {
          EXPECT_LT(s_hit, 0.0);
        }
        EXPECT_GE(xi, 0.0);
        EXPECT_LT(xi, kTwoPi);
      }
      // A line passing farther than the bounding radius misses.
      double s_hit = 0.0, xi = 0.0;
      const Vec2 dir(std::cos(0.3), std::sin(0.3));
      EXPECT_FALSE(s->entryAlongLine(1.01 * r * perp(dir) - 5.0 * dir, dir, s_hit, xi));
      EXPECT_FALSE(s->entryAlongLine(-1.01 * r * perp(dir), dir, s_hit, xi));
    }
  }
  // Lines grazing the top of an ellipse: just above misses, just below hits near the top.
  const EllipseShape e(0.3, 0.15);
  double s_hit = 0.0, xi = 0.0;
  EXPECT_FALSE(e.entryAlongLine(Vec2(1.0, 0.15 + 1e-9), Vec2(-1.0, 0.0), s_hit, xi));
  ASSERT_TRUE(e.entryAlongLine(Vec2(1.0, 0.15 - 1e-6), Vec2(-1.0, 0.0), s_hit, xi));
  const double x_hit = 0.3 * std::sqrt(1.0 - std::pow((0.15 - 1e-6) / 0.15, 2));
  EXPECT_NEAR(s_hit, 1.0 - x_hit, 1e-9);
  EXPECT_NEAR(xi, std::acos(x_hit / 0.3), 1e-9);
}

// Ellipses and circles find the entry by a quadratic; the generic boundary scan is an
// independent computation of the same point.
TEST(Shape, ClosedFormEntryAgreesWithTheBoundaryScan) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), angle(0.0, kTwoPi);
  int hits = 0, misses = 0;
  for (Kind kind : {Kind::kEllipse, Kind::kCircle}) {
    for (int shape = 0; shape < 6; ++shape) {
      auto sh = randomShape(kind, rng);
      const double r = sh->boundingRadius();
      for (int i = 0; i < 200; ++i) {
        const double a = angle(rng);
        const Vec2 dir(std::cos(a), std::sin(a));
        const Vec2 origin = 1.5 * r * Vec2(unit(rng), unit(rng));
        double s1 = NAN, xi1 = NAN, s2 = NAN, xi2 = NAN;
        const bool closed = sh->entryAlongLine(origin, dir, s1, xi1);
        const bool scanned = sh->Shape::entryAlongLine(origin, dir, s2, xi2);
        ASSERT_EQ(closed, scanned) << "shape " << shape << " line " << i;
        if (!closed) {
          ++misses;
          continue;
        }
        ++hits;
        EXPECT_NEAR(s1, s2, 1e-9);
        EXPECT_NEAR(std::remainder(xi1 - xi2, kTwoPi), 0.0, 1e-7);
      }
    }
  }
  EXPECT_GT(hits, 300);
  EXPECT_GT(misses, 100);
}

}  // namespace
}  // namespace rbsf
