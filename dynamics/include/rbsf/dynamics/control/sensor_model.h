#pragma once
/// \file
/// \brief A simulated cell's sensors (sensing.h): what the control law gets from a plant
///        state. Used by the certificate's trials and the example controller loop.
///
/// Joints: theta and every stroke each control step, plus Gaussian noise of the sensing's
/// standard deviations. Part pose: every round(1 / (rate h)) steps the pose of the part's
/// frame (the COM frame moved back by the COM offset d: what a camera over the jig sees)
/// plus Gaussian noise, stamped with the time it was taken and handed over round(latency /
/// h) steps later. Noise from one generator seeded at construction: the same seed gives
/// the same measurements. Allocation-free after construction.

#include <cstdint>
#include <random>
#include <vector>

#include "rbsf/dynamics/core/placement.h"
#include "rbsf/dynamics/core/sensing.h"
#include "rbsf/dynamics/core/types.h"

namespace rbsf {

/// \brief The sensors of one simulated run (file comment).
class SensorModel {
 public:
  /// \param com_offset d: the plant's COM in the part's frame [m].
  /// \param noise false: exact measurements.
  SensorModel(const Sensing& sensing, double time_step, std::uint64_t seed, bool noise = true,
              const Vec2& com_offset = Vec2::Zero());

  /// \brief The joints measured from q (tau order: theta, l_1..l_m).
  void joints(const VecQ& q, VecU& out);

  /// \brief The pose of the part's frame in q (no noise).
  Pose framePose(const VecQ& q) const;

  /// \brief At step n (time n h) of the plant in q: take a part sample when one is due, and
  ///        hand every sample whose latency has passed to deliver(stamp, pose).
  template <class Deliver>
  void partPose(long n, const VecQ& q, Deliver&& deliver) {
    if (!sensing_.part_pose.present) return;
    if (n % every_ == 0 && count_ < shots_.size()) {
      const Pose p = framePose(q);
      const PartPoseSensing& s = sensing_.part_pose;
      shots_[(first_ + count_++) % shots_.size()] = {
          n + latency_, static_cast<double>(n) * h_,
          Pose{p.x + s.position_noise * normal(), p.y + s.position_noise * normal(),
               p.phi + s.angle_noise * normal()}};
    }
    while (count_ > 0 && shots_[first_].deliver <= n) {
      deliver(shots_[first_].stamp, shots_[first_].pose);
      first_ = (first_ + 1) % shots_.size();
      --count_;
    }
  }

 private:
  struct Shot {
    long deliver = 0;
    double stamp = 0.0;
    Pose pose;
  };
  double normal() { return noise_ ? dist_(rng_) : 0.0; }

  Sensing sensing_;
  double h_;
  bool noise_;
  Vec2 d_;
  long every_ = 1, latency_ = 0;
  std::mt19937_64 rng_;
  std::normal_distribution<double> dist_{0.0, 1.0};
  std::vector<Shot> shots_;  ///< ring of samples in flight
  std::size_t first_ = 0, count_ = 0;
};

}  // namespace rbsf
