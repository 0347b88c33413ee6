#pragma once
/// \file
/// \brief What goes wrong on a real cell (cell file section `faults`): the faults a
///        certificate's trials and rbsf-replay draw beside the uncertainty (plan/trial.h).
///
/// ```yaml
/// faults:
///   pose_dropouts: {rate: 1.0, length: 0.2}    # the part-pose sensor goes dark: events per
///                                              # second of run, each this long [s]
///   joint_spikes: {rate: 2.0, size: 0.001, nan: 0.5}
///                                              # one reading of one joint off by +-size
///                                              # [rad or m], or not a number (this share)
///   missed_ticks: {rate: 5.0}                  # the loop skips a tick: the last input is
///                                              # held one more period
///   force_cut: {chance: 1.0, to: 0.6}          # in this share of trials, one finger's force
///                                              # limit falls to `to` of itself mid-run
///   mass_error: 0.10                           # the part is heavier or lighter than its
///                                              # drawing by this much beyond the drawn mass
/// ```
///
/// Every key is optional; a section left out draws no fault (the defaults are all zero).
/// Event times are a Poisson process over the run (the plan and its settle hold) at the
/// given rate; the force cut comes at a time uniform over the plan, on a finger drawn
/// uniformly; the mass error is +-mass_error, its sign drawn.

namespace rbsf {

/// \brief The part-pose sensor's dropouts.
struct PoseDropouts {
  double rate = 0.0;    ///< events per second
  double length = 0.2;  ///< each [s]
};

/// \brief Single bad joint readings.
struct JointSpikes {
  double rate = 0.0;       ///< events per second
  double size = 1e-3;      ///< a finite spike's size [rad or m]
  double nan_share = 0.5;  ///< the share of spikes that are not a number
};

/// \brief Faults a trial draws (file comment).
struct Faults {
  PoseDropouts pose_dropouts;
  JointSpikes joint_spikes;
  double missed_tick_rate = 0.0;  ///< ticks skipped per second
  double force_cut_chance = 0.0;  ///< share of trials with a finger's force limit cut
  double force_cut_to = 0.6;      ///< the cut limit, a fraction of the finger's limit
  double mass_error = 0.0;        ///< relative, beyond the drawn uncertainty

  /// \brief True when any fault is drawn at all.
  bool any() const {
    return pose_dropouts.rate > 0.0 || joint_spikes.rate > 0.0 || missed_tick_rate > 0.0 ||
           force_cut_chance > 0.0 || mass_error > 0.0;
  }
};

}  // namespace rbsf
