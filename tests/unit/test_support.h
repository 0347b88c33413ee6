#pragma once
// Cells built in code and random contact states for the unit tests.

#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>

#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/core/model.h"
#include "rbsf/dynamics/core/placement.h"
#include "rbsf/dynamics/core/state_layout.h"

namespace rbsf::test {

/// `settings` without a clock (an infinite time_limit): its budget (expansions,
/// propagations) alone ends the search, so the outcome is the same on an idle and on a
/// loaded machine.
template <class Settings>
Settings withoutClock(Settings settings) {
  settings.time_limit = std::numeric_limits<double>::infinity();
  return settings;
}

enum class ShapeKind { kEllipse, kCircle, kSuperellipse };

inline std::shared_ptr<const Shape> makeShape(ShapeKind kind) {
  switch (kind) {
    case ShapeKind::kEllipse:
      return std::make_shared<EllipseShape>(0.30, 0.15, Vec2(-0.10, 0.0));
    case ShapeKind::kCircle:
      return std::make_shared<CircleShape>(0.25, Vec2(0.03, -0.02));
    case ShapeKind::kSuperellipse:
      return std::make_shared<SuperellipseShape>(0.30, 0.16, 4.0, Vec2(0.05, 0.01));
  }
  return nullptr;
}

/// The default cell (cells/default.yaml) with another shape, m fingers spread over
/// [-0.2, 0.2] m, and varied carriage parameters so that every term of M and Q matters.
inline Cell makeCell(ShapeKind kind = ShapeKind::kEllipse, int m = 3) {
  Cell c;
  c.gravity = 9.81;
  c.base = {5.0, -0.785398, 0.785398, 400.0};
  for (int i = 0; i < m; ++i) {
    FingerParams f;
    f.r = m == 1 ? 0.0 : -0.20 + 0.40 * i / (m - 1);
    f.stroke_min = 0.05;
    f.stroke_max = 0.55;
    f.mass = 2.0 + 0.25 * i;
    f.force_limit = 800.0;
    f.com_offset = -0.02 * i;
    f.inertia = 0.01 * i;
    c.fingers.push_back(f);
  }
  c.object.shape = makeShape(kind);
  c.object.mass = 24.0;
  c.object.inertia = 0.675;
  c.friction = {0.5, 0.0};
  c.name = "test cell";
  return c;
}

/// COM x [m] that centres each test shape over the fingers.
inline double centredX(const RbsfModel& model) {
  const std::string type = model.shape().type();
  return type == "ellipse" ? 0.10 : type == "circle" ? -0.03 : -0.05;
}

/// A resting configuration near the centred pose with every tip on the boundary.
inline VecQ randomContactState(const RbsfModel& model, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int attempt = 0; attempt < 1000; ++attempt) {
    Pose pose{centredX(model) + 0.03 * u(rng), 0.40 + 0.03 * u(rng), 0.25 * u(rng)};
    const double theta = 0.3 * u(rng);
    const Placement p = placeFingers(model, pose, theta);
    if (p.ok) return restingConfiguration(model, pose, theta);
  }
  throw std::logic_error("test cell: no reachable resting pose near the centred one");
}

inline VecQ randomVector(int n, std::mt19937& rng, double scale = 1.0) {
  std::uniform_real_distribution<double> u(-scale, scale);
  VecQ v(n);
  for (int i = 0; i < n; ++i) v[i] = u(rng);
  return v;
}

/// \brief A rows x cols matrix of uniform entries in [-1, 1], drawn column by column.
inline Eigen::MatrixXd randomMatrix(std::mt19937& rng, Eigen::Index rows, Eigen::Index cols) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index j = 0; j < cols; ++j) {
    for (Eigen::Index i = 0; i < rows; ++i) m(i, j) = u(rng);
  }
  return m;
}

}  // namespace rbsf::test
