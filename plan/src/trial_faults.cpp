#include "rbsf/plan/trial_faults.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace rbsf::plan {

std::uint64_t splitMix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

long FaultDraw::firstStep() const {
  long first = mass_error != 0.0 ? 0 : -1;
  auto earlier = [&](long n) {
    if (n >= 0 && (first < 0 || n < first)) first = n;
  };
  if (!dropouts.empty()) earlier(dropouts.front().first);
  if (!spikes.empty()) earlier(spikes.front());
  if (!missed.empty()) earlier(missed.front());
  earlier(cut_step);
  return first;
}

FaultDraw drawFaults(const Faults& f, const Plan& plan, std::uint64_t seed, int index, long steps,
                     double h, int inputs) {
  FaultDraw d;
  if (!f.any()) return d;
  std::mt19937_64 rng(
      splitMix64(splitMix64(seed ^ 0xfa017ULL) ^ static_cast<std::uint64_t>(index)));
  std::uniform_real_distribution<double> u(0.0, 1.0);
  // Poisson events at `rate` per second: exponential gaps.
  auto events = [&](double rate, std::vector<long>& at) {
    if (rate <= 0.0) return;
    for (double t = -std::log(1.0 - u(rng)) / rate; t < static_cast<double>(steps) * h;
         t += -std::log(1.0 - u(rng)) / rate)
      at.push_back(std::lround(t / h));
  };
  std::vector<long> starts;
  events(f.pose_dropouts.rate, starts);
  for (long s : starts) d.dropouts.emplace_back(s, s + std::lround(f.pose_dropouts.length / h));
  events(f.joint_spikes.rate, d.spikes);
  for (std::size_t i = 0; i < d.spikes.size(); ++i) {
    d.spike_joints.push_back(std::min(inputs - 1, static_cast<int>(u(rng) * inputs)));
    const bool nan = u(rng) < f.joint_spikes.nan_share;
    d.spike_values.push_back(nan ? std::numeric_limits<double>::quiet_NaN()
                                 : (u(rng) < 0.5 ? -1.0 : 1.0) * f.joint_spikes.size);
  }
  events(f.missed_tick_rate, d.missed);
  if (u(rng) < f.force_cut_chance) {
    d.cut_step = std::lround(u(rng) * plan.duration() / h);
    d.cut_finger = std::min(inputs - 2, static_cast<int>(u(rng) * (inputs - 1)));
    d.cut_to = f.force_cut_to;
  }
  if (f.mass_error > 0.0) d.mass_error = (u(rng) < 0.5 ? -1.0 : 1.0) * f.mass_error;
  return d;
}

bool FaultInjector::missed(long n) {
  while (next_missed_ < d_.missed.size() && d_.missed[next_missed_] < n) ++next_missed_;
  return next_missed_ < d_.missed.size() && d_.missed[next_missed_] == n;
}

void FaultInjector::corruptJoints(long n, VecU& joints) {
  while (next_spike_ < d_.spikes.size() && d_.spikes[next_spike_] < n) ++next_spike_;
  for (std::size_t i = next_spike_; i < d_.spikes.size() && d_.spikes[i] == n; ++i) {
    const int j = d_.spike_joints[i];
    joints[j] =
        std::isnan(d_.spike_values[i]) ? d_.spike_values[i] : joints[j] + d_.spike_values[i];
  }
}

bool FaultInjector::dropped(long n) const {
  return std::any_of(d_.dropouts.begin(), d_.dropouts.end(),
                     [n](const std::pair<long, long>& w) { return n >= w.first && n < w.second; });
}

void FaultInjector::cut(long n, const Cell& cell, VecU& tau) const {
  if (d_.cut_step < 0 || n < d_.cut_step) return;
  const int j = d_.cut_finger + 1;
  const double limit = d_.cut_to * cell.inputLimit(j);
  tau[j] = std::clamp(tau[j], -limit, limit);
}

}  // namespace rbsf::plan
