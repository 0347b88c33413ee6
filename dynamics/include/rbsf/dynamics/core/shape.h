#pragma once
/// \file
/// \brief Smooth closed convex object boundaries c(xi) in the object (COM) frame.
///
/// Every shape is a curve c(xi), xi in [0, 2 pi) (periodic), traversed counter-clockwise
/// (docs/model.md "Frames and symbols"). From c, c' and c'' the base class derives
/// - unit tangent      t = c' / |c'|
/// - inward unit normal n = S t            (S = rotation by +90 degrees)
/// - curvature          kappa = (c' x c'') / |c'|^3  (> 0 for a convex CCW curve)
/// so that dt/ds = kappa n and dn/ds = -kappa t along arc length s.
/// Lengths are in metres, xi is dimensionless.

#include <algorithm>
#include <memory>
#include <string>

#include "rbsf/dynamics/core/types.h"

namespace rbsf {

/// \brief Geometry of the boundary at one parameter value (object frame).
struct BoundaryPoint {
  Vec2 point;        ///< c(xi) [m]
  Vec2 tangent;      ///< unit tangent t(xi)
  Vec2 normal;       ///< inward unit normal n(xi) = S t(xi)
  double speed;      ///< |c'(xi)| [m per unit xi]
  double curvature;  ///< kappa(xi) >= 0 [1/m]
};

/// \brief Closest boundary point to a query point (object frame).
struct ClosestPoint {
  double xi;               ///< parameter of the closest boundary point, in [0, 2 pi)
  Vec2 point;              ///< c(xi) [m]
  double signed_distance;  ///< distance [m]; positive outside the shape, negative inside
};

/// \brief A smooth closed convex curve. Immutable and thread-safe once built.
class Shape {
 public:
  virtual ~Shape() = default;

  /// \brief Type name as written in a cell file ("ellipse", "circle", "superellipse").
  virtual std::string type() const = 0;

  /// \brief c(xi), c'(xi) and c''(xi) in the object frame.
  virtual void derivatives(double xi, Vec2& c, Vec2& dc, Vec2& ddc) const = 0;

  /// \brief Radius of a circle about the COM that contains the whole shape [m].
  virtual double boundingRadius() const = 0;

  /// \brief The same boundary moved by d in the object frame: the part's geometry seen
  ///        from a COM that sits -d from where this shape has it [m].
  virtual std::shared_ptr<const Shape> shifted(const Vec2& d) const = 0;

  /// \brief A positive lower bound of the radius of curvature over the whole boundary [m]:
  ///        a point inside the shape no deeper than this has a unique closest point.
  virtual double minCurvatureRadius() const = 0;

  /// \brief Point, tangent, inward normal, speed and curvature at xi.
  BoundaryPoint boundary(double xi) const;

  /// \brief c(xi) only.
  Vec2 point(double xi) const;

  /// \brief Globally closest boundary point to p, with the signed distance
  ///        (positive outside). Exact to ~1e-12 m; allocation-free.
  virtual ClosestPoint closest(const Vec2& p) const;

  /// \brief Closest boundary point by Newton's method started at xi_hint; falls back to
  ///        closest(p) when the local iteration does not converge or cannot be certified
  ///        global. Use when the previous contact parameter is known (simulation,
  ///        tracking). When `at` is given it receives boundary(result.xi), reusing the
  ///        last evaluation.
  virtual ClosestPoint closestNear(const Vec2& p, double xi_hint,
                                   BoundaryPoint* at = nullptr) const;

  /// \brief First boundary crossing of the line origin + s * dir (dir a unit vector)
  ///        entering the shape, i.e. the smallest s with origin + s dir on the boundary.
  /// \return false when the line misses the shape. The generic version scans the
  ///         boundary for the arcs between the points where c' is parallel to dir and
  ///         finds one crossing on each; ellipses and circles solve a quadratic.
  virtual bool entryAlongLine(const Vec2& origin, const Vec2& dir, double& s, double& xi) const;

  /// \brief Wrap a parameter into [0, 2 pi).
  static double wrap(double xi);

  /// \brief Tangent, normal, speed and curvature from c, c' and c''.
  static BoundaryPoint geometry(const Vec2& c, const Vec2& dc, const Vec2& ddc);
};

/// \brief Ellipse c(xi) = e + (a cos xi, b sin xi), e the geometric centre relative to
///        the COM (paper Fig. 3: a part whose COM is shifted from its centre).
class EllipseShape final : public Shape {
 public:
  /// \throws InputError when a or b is not positive and finite.
  EllipseShape(double a, double b, const Vec2& center = Vec2::Zero());
  std::string type() const override { return "ellipse"; }
  void derivatives(double xi, Vec2& c, Vec2& dc, Vec2& ddc) const override;
  std::shared_ptr<const Shape> shifted(const Vec2& d) const override;
  double boundingRadius() const override;
  double minCurvatureRadius() const override {
    return std::min(a_, b_) * std::min(a_, b_) / std::max(a_, b_);
  }
  /// \brief The smaller root s of |diag(1/a, 1/b) (origin + s dir - e)|^2 = 1.
  bool entryAlongLine(const Vec2& origin, const Vec2& dir, double& s, double& xi) const override;
  double a() const { return a_; }
  double b() const { return b_; }
  const Vec2& center() const { return center_; }

 private:
  double a_, b_;
  Vec2 center_;
};

/// \brief Circle c(xi) = e + r (cos xi, sin xi); closest point in closed form.
class CircleShape final : public Shape {
 public:
  /// \throws InputError when the radius is not positive and finite.
  explicit CircleShape(double radius, const Vec2& center = Vec2::Zero());
  std::string type() const override { return "circle"; }
  void derivatives(double xi, Vec2& c, Vec2& dc, Vec2& ddc) const override;
  std::shared_ptr<const Shape> shifted(const Vec2& d) const override;
  double boundingRadius() const override;
  double minCurvatureRadius() const override { return r_; }
  ClosestPoint closest(const Vec2& p) const override;
  ClosestPoint closestNear(const Vec2& p, double xi_hint,
                           BoundaryPoint* at = nullptr) const override;
  /// \brief The smaller root s of |origin + s dir - e|^2 = r^2.
  bool entryAlongLine(const Vec2& origin, const Vec2& dir, double& s, double& xi) const override;
  double radius() const { return r_; }
  const Vec2& center() const { return center_; }

 private:
  double r_;
  Vec2 center_;
};

/// \brief Boxy superellipse |x'/a|^n + |y'/b|^n = 1 (x' = x - e), n >= 2, parametrised by
///        the polar angle about its centre: c(xi) = e + rho(xi) (cos xi, sin xi),
///        rho = (|cos xi / a|^n + |sin xi / b|^n)^(-1/n). C^2 for n >= 2, so curvature is
///        continuous; n = 2 is an ellipse, large n approaches an a-by-b rectangle.
class SuperellipseShape final : public Shape {
 public:
  /// \throws InputError for non-positive a, b or an exponent outside [2, 20].
  SuperellipseShape(double a, double b, double exponent, const Vec2& center = Vec2::Zero());
  std::string type() const override { return "superellipse"; }
  void derivatives(double xi, Vec2& c, Vec2& dc, Vec2& ddc) const override;
  std::shared_ptr<const Shape> shifted(const Vec2& d) const override;
  double boundingRadius() const override;
  /// Half the smallest radius of curvature over the construction-time scan (within 2%).
  double minCurvatureRadius() const override;
  double a() const { return a_; }
  double b() const { return b_; }
  double exponent() const { return n_; }
  const Vec2& center() const { return center_; }

 private:
  double a_, b_, n_;
  Vec2 center_;
  double min_curvature_radius_ = 0.0;
};

}  // namespace rbsf
