#include "rbsf/dynamics/core/trajectory_sample.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace rbsf {

std::string trajectoryCsvHeader(int m) {
  std::string h = "t,x,y,phi,theta";
  for (int i = 1; i <= m; ++i) h += ",l" + std::to_string(i);
  h += ",dx,dy,dphi,dtheta";
  for (int i = 1; i <= m; ++i) h += ",dl" + std::to_string(i);
  h += ",tau_theta";
  for (int i = 1; i <= m; ++i) h += ",tau_" + std::to_string(i);
  for (int i = 1; i <= m; ++i) h += ",fn_" + std::to_string(i);
  return h + ",phase";
}

void appendTrajectoryCsvRow(std::string& text, const TrajectorySample& s, int m) {
  if (s.q.size() != m + 4 || s.v.size() != m + 4 || s.tau.size() != m + 1 || s.f_n.size() != m)
    throw std::runtime_error("trajectory sample sized for another number of fingers");
  char buf[32];
  auto put = [&](double x, bool comma) {
    if (!std::isfinite(x)) throw std::runtime_error("trajectory holds a non-finite number");
    std::snprintf(buf, sizeof buf, comma ? ",%.17g" : "%.17g", x);
    text += buf;
  };
  put(s.t, false);
  for (const auto* v : {&s.q, &s.v})
    for (int k = 0; k < v->size(); ++k) put((*v)[k], true);
  for (int k = 0; k < s.tau.size(); ++k) put(s.tau[k], true);
  for (int k = 0; k < s.f_n.size(); ++k) put(s.f_n[k], true);
  text += ',';
  text += toString(s.phase);
  text += '\n';
}

std::string trajectoryCsvText(const std::vector<TrajectorySample>& samples, int m) {
  std::string text = trajectoryCsvHeader(m) + "\n";
  for (const TrajectorySample& s : samples) appendTrajectoryCsvRow(text, s, m);
  return text;
}

}  // namespace rbsf
