#include "rbsf/dynamics/control/sensor_model.h"

#include <algorithm>
#include <cmath>

#include "rbsf/dynamics/core/state_layout.h"

namespace rbsf {

SensorModel::SensorModel(const Sensing& sensing, double time_step, std::uint64_t seed, bool noise,
                         const Vec2& com_offset)
    : sensing_(sensing), h_(time_step), noise_(noise), d_(com_offset), rng_(seed) {
  const PartPoseSensing& s = sensing.part_pose;
  if (s.present) {
    every_ = std::max(1L, std::lround(1.0 / (s.rate * h_)));
    latency_ = std::lround(s.latency / h_);
  }
  shots_.resize(static_cast<std::size_t>(latency_ / every_ + 2));
}

void SensorModel::joints(const VecQ& q, VecU& out) {
  const int nu = static_cast<int>(q.size()) - layout::kObjectDim;
  out.resize(nu);
  for (int j = 0; j < nu; ++j) {
    const double sd =
        j == layout::kTauTheta ? sensing_.joints.angle_noise : sensing_.joints.stroke_noise;
    out[j] = q[layout::inputToConfig(j)] + sd * normal();
  }
}

Pose SensorModel::framePose(const VecQ& q) const {
  const Vec2 p = Vec2(q[layout::kX], q[layout::kY]) - rotate(q[layout::kPhi], d_);
  return {p.x(), p.y(), q[layout::kPhi]};
}

}  // namespace rbsf
