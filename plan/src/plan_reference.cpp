#include "rbsf/plan/plan_reference.h"

#include "rbsf/dynamics/core/errors.h"

namespace rbsf::plan {

ReferenceTrajectory makeReference(const Plan& plan) {
  if (plan.samples.empty() || plan.segments.empty())
    throw InputError("plan has no samples or no segments: nothing to track");
  ReferenceTrajectory ref;
  for (const PlanSample& s : plan.samples)
    if (ref.numKnots() == 0 || s.t > ref.endTime()) ref.addKnot(s.t, s.q, s.v);
  double t = 0.0;
  for (const PlanSegment& seg : plan.segments) {
    ref.addInputPiece(t, seg.duration, seg.tau, seg.tau_end, seg.phase, seg.contacts);
    t += seg.duration;
  }
  return ref;
}

Sensing lawSensing(const Sensing& cell, const Plan& plan) {
  Sensing s = cell;
  if (plan.joint_feedback) s.part_pose.present = false;
  return s;
}

}  // namespace rbsf::plan
