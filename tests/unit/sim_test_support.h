#pragma once
// Controllers and bookkeeping shared by the simulator tests.

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "rbsf/dynamics/core/holding.h"
#include "rbsf/dynamics/core/simulator.h"
#include "test_support.h"

namespace rbsf::test {

/// The configuration q0 turned rigidly about the world origin by `angle`: object pose and
/// base angle rotate together, strokes unchanged (what phase C does).
inline VecQ turnedWithBase(const VecQ& q0, double angle) {
  VecQ q = q0;
  const Vec2 x = rotate(angle, Vec2(q0[layout::kX], q0[layout::kY]));
  q[layout::kX] = x.x();
  q[layout::kY] = x.y();
  q[layout::kPhi] += angle;
  q[layout::kTheta] += angle;
  return q;
}

/// Holding tau of q with every finger touching (holdingTorques()).
inline HoldingSolution holdingAt(const RbsfModel& model, const VecQ& q) {
  ModelData d(model.numFingers());
  model.updateContacts(q, d);
  return holdingTorques(model, q, d);
}

/// PD servo added to a feedforward tau: base angle to theta_ref (rate feedforward
/// theta_dot_ref), strokes to their targets. Gains are stiff against the 24 kg part.
struct Servo {
  double kp_base = 2e4, kd_base = 2e3;      // [N m/rad], [N m s/rad]
  double kp_stroke = 2e4, kd_stroke = 1e3;  // [N/m], [N s/m]

  VecU operator()(const VecU& feedforward, const SimState& s, double theta_ref,
                  double theta_dot_ref, const VecC& strokes) const {
    VecU tau = feedforward;
    tau[layout::kTauTheta] += kp_base * (theta_ref - s.q[layout::kTheta]) +
                              kd_base * (theta_dot_ref - s.v[layout::kTheta]);
    for (int i = 0; i < strokes.size(); ++i) {
      tau[layout::fingerForce(i)] +=
          kp_stroke * (strokes[i] - s.q[layout::stroke(i)]) - kd_stroke * s.v[layout::stroke(i)];
    }
    return tau;
  }
};

/// A figure for RecordProperty(), in %.4g.
inline std::string figure(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

inline VecC strokesOf(const VecQ& q) { return q.tail(q.size() - layout::kFirstStroke); }

/// Bitwise equality of two vectors (same values, same signs of zero, same NaN payloads).
inline bool sameBits(const VecQ& a, const VecQ& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<size_t>(a.size())) == 0;
}

}  // namespace rbsf::test
