#include "rbsf/dynamics/core/placement.h"

#include <cmath>
#include <cstdio>

#include "rbsf/dynamics/core/errors.h"

namespace rbsf {

double angleDifference(double a, double b) {
  double d = std::remainder(a - b, 2.0 * M_PI);
  if (d <= -M_PI) d += 2.0 * M_PI;
  return d;
}

Placement placeFingers(const RbsfModel& model, const Pose& pose, double theta) {
  const int m = model.numFingers();
  const Vec2 x_o(pose.x, pose.y);
  const Vec2 dir_world = rotate(theta, Vec2(0.0, 1.0));
  const Vec2 dir = rotate(-pose.phi, dir_world);
  Placement out;
  out.strokes = VecC::Zero(m);
  char buf[256];
  for (int i = 0; i < m; ++i) {
    const FingerParams& f = model.cell().fingers[i];
    const Vec2 origin = rotate(-pose.phi, rotate(theta, Vec2(f.r, 0.0)) - x_o);
    double s = 0.0, xi = 0.0;
    if (!model.shape().entryAlongLine(origin, dir, s, xi)) {
      std::snprintf(buf, sizeof buf,
                    "finger %d cannot reach the object: its line of travel (r = %g m) misses it",
                    i + 1, f.r);
      out.finger = i;
      out.message = buf;
      return out;
    }
    if (s < f.stroke_min || s > f.stroke_max) {
      std::snprintf(buf, sizeof buf,
                    "finger %d cannot reach the object within its stroke: needs l = %.6g m, "
                    "stroke is [%g, %g] m",
                    i + 1, s, f.stroke_min, f.stroke_max);
      out.finger = i;
      out.message = buf;
      return out;
    }
    out.strokes[i] = s;
  }
  out.ok = true;
  return out;
}

VecQ restingConfiguration(const RbsfModel& model, const Pose& pose, double theta) {
  const Placement p = placeFingers(model, pose, theta);
  if (!p.ok) throw InputError(p.message);
  VecQ q(model.configDim());
  q[layout::kX] = pose.x;
  q[layout::kY] = pose.y;
  q[layout::kPhi] = pose.phi;
  q[layout::kTheta] = theta;
  for (int i = 0; i < model.numFingers(); ++i) q[layout::stroke(i)] = p.strokes[i];
  return q;
}

}  // namespace rbsf
