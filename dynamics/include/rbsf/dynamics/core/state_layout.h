#pragma once
/// \file
/// \brief The one place that fixes the order of the configuration, velocity and input
///        vectors (docs/model.md, "State layout"). Nobody else hard-codes an index.
///
/// Configuration q in R^(m+4), velocity v = dq/dt (same order, same frame):
/// | index      | symbol   | meaning                                   | unit |
/// |------------|----------|-------------------------------------------|------|
/// | kX         | x        | object COM, world x                       | m    |
/// | kY         | y        | object COM, world y (up)                  | m    |
/// | kPhi       | phi      | object angle, counter-clockwise           | rad  |
/// | kTheta     | theta    | base angle about the world origin, CCW    | rad  |
/// | stroke(i)  | l_i      | extension of finger i along the base y    | m    |
///
/// Input tau in R^(m+1): tau_theta [N m] at index kTauTheta, finger force tau_i [N] at
/// fingerForce(i). The generalized input is u = (0, 0, 0, tau), so tau index j sits at
/// configuration index kTheta + j.

namespace rbsf::layout {

/// \brief Object COM x [m] (world frame).
inline constexpr int kX = 0;
/// \brief Object COM y [m] (world frame, up).
inline constexpr int kY = 1;
/// \brief Object angle phi [rad].
inline constexpr int kPhi = 2;
/// \brief Base angle theta [rad].
inline constexpr int kTheta = 3;
/// \brief Number of object coordinates (x, y, phi).
inline constexpr int kObjectDim = 3;
/// \brief Index of the first finger stroke l_1 [m].
inline constexpr int kFirstStroke = 4;

/// \brief Index of finger i's stroke l_i (i counted from 0).
constexpr int stroke(int i) { return kFirstStroke + i; }
/// \brief Dimension of q and v for m fingers.
constexpr int configDim(int m) { return m + 4; }
/// \brief Number of mechanism coordinates (theta, l_1..l_m).
constexpr int mechanismDim(int m) { return m + 1; }

/// \brief Index of the base torque tau_theta [N m] in tau.
inline constexpr int kTauTheta = 0;
/// \brief Index of finger i's force tau_i [N] in tau (i counted from 0).
constexpr int fingerForce(int i) { return 1 + i; }
/// \brief Dimension of tau for m fingers.
constexpr int controlDim(int m) { return m + 1; }
/// \brief Configuration index that tau index j drives (u = (0, 0, 0, tau)).
constexpr int inputToConfig(int j) { return kTheta + j; }

}  // namespace rbsf::layout
