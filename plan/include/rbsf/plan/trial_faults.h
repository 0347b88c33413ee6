#pragma once
/// \file
/// \brief The faults of one trial (trial.h): what a trial drew from the cell's faults
///        section (faults.h), and their effect on the trial's loop, step by step.

#include <cstdint>
#include <utility>
#include <vector>

#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/core/faults.h"
#include "rbsf/dynamics/core/types.h"
#include "rbsf/plan/plan.h"

namespace rbsf::plan {

/// \brief One trial's faults (the cell's `faults` section, faults.h), as steps of the run.
struct FaultDraw {
  std::vector<std::pair<long, long>> dropouts;  ///< [first, last) steps without part poses
  std::vector<long> spikes;                     ///< steps with one bad joint reading
  std::vector<int> spike_joints;                ///< which input's reading (tau order)
  std::vector<double> spike_values;             ///< added to it; NaN: the reading is NaN
  std::vector<long> missed;                     ///< steps the loop skips (the input held)
  long cut_step = -1;                           ///< from this step ...
  int cut_finger = -1;                          ///< ... this finger's force limit (0-based)
  double cut_to = 1.0;                          ///< ... is this fraction of itself
  double mass_error = 0.0;                      ///< the part's mass error applied (relative)
  /// \brief The first step any fault acts (0 for a mass error), -1 when none.
  long firstStep() const;
  bool any() const { return firstStep() >= 0; }
};

/// \brief SplitMix64: decorrelates the generators of neighbouring trials and seeds (the
///        trials' draws and their faults' draw mix their seeds with it).
std::uint64_t splitMix64(std::uint64_t x);

/// \brief The faults of trial `index` of `seed` over `steps` steps of h (faults.h), from a
///        generator of their own; `inputs` = m + 1.
FaultDraw drawFaults(const Faults& faults, const Plan& plan, std::uint64_t seed, int index,
                     long steps, double h, int inputs);

/// \brief What a trial's loop does with its drawn faults, step by step (allocation-free).
class FaultInjector {
 public:
  explicit FaultInjector(const FaultDraw& draw) : d_(draw) {}
  /// \brief True when the loop skips step n (the last input held).
  bool missed(long n);
  /// \brief The reading of step n as the faulty sensor gives it.
  void corruptJoints(long n, VecU& joints);
  /// \brief True when a part pose taken at step n is lost in a dropout.
  bool dropped(long n) const;
  /// \brief The input of step n as the faulty finger applies it (its limit cut).
  void cut(long n, const Cell& cell, VecU& tau) const;

 private:
  const FaultDraw& d_;
  std::size_t next_spike_ = 0, next_missed_ = 0;
};

}  // namespace rbsf::plan
