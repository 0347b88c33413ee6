#pragma once
/// \file
/// \brief Fixed-capacity Eigen types used on every hot path.
///
/// Dynamic-size Eigen objects with a compile-time maximum live on the stack, so the
/// dynamics, the contact solvers and the simulator step never touch the heap. The
/// capacity bounds the number of fingers a cell may have (kMaxFingers); the cell
/// loader refuses more.

#include <cmath>

#include <Eigen/Core>

namespace rbsf {

/// \brief Largest number of fingers a cell may have.
inline constexpr int kMaxFingers = 12;
/// \brief Largest configuration dimension m + 4.
inline constexpr int kMaxConfig = kMaxFingers + 4;
/// \brief Largest number of contact constraint rows (normal + tangential per finger).
inline constexpr int kMaxRows = 2 * kMaxFingers;

using Vec2 = Eigen::Vector2d;
using Mat2 = Eigen::Matrix2d;

/// \brief A configuration-sized vector (q, v, dv/dt, u, Q): length m + 4.
using VecQ = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxConfig, 1>;
/// \brief An input-sized vector tau: length m + 1.
using VecU = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxFingers + 1, 1>;
/// \brief A per-contact vector (F_n, gaps, xi): length m.
using VecC = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxFingers, 1>;
/// \brief A vector over contact constraint rows (up to 2m).
using VecR = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxRows, 1>;
/// \brief (m+4) x (m+4) matrix (M, M^-1).
using MatQQ = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxConfig, kMaxConfig>;
/// \brief (m+4) x m matrix (G1, T).
using MatQC = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxConfig, kMaxFingers>;
/// \brief (m+4) x 2m matrix (stacked constraint columns).
using MatQR = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxConfig, kMaxRows>;
/// \brief m x m matrix (the Delassus matrix A of eq. 21).
using MatCC = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxFingers, kMaxFingers>;
/// \brief 3 x m matrix (a part's three balance rows over its contacts).
using Mat3C = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMaxFingers>;
/// \brief 3 x 2m matrix (the same rows over normal and tangential contact forces).
using Mat3R = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMaxRows>;
/// \brief 2m x 2m matrix.
using MatRR = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxRows, kMaxRows>;

/// \brief S = [[0, -1], [1, 0]] (the paper's D): rotation by +90 degrees.
inline Vec2 perp(const Vec2& a) { return Vec2(-a.y(), a.x()); }
/// \brief 2-D cross product a x b = (S a)^T b.
inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
/// \brief R(angle) applied to a.
inline Vec2 rotate(double angle, const Vec2& a) {
  const double c = std::cos(angle), s = std::sin(angle);
  return Vec2(c * a.x() - s * a.y(), s * a.x() + c * a.y());
}

}  // namespace rbsf
