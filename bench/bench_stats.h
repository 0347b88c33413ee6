#pragma once
/// \file
/// \brief What the benchmark programs share: the median they report.

#include <algorithm>
#include <cmath>
#include <vector>

namespace rbsf::bench {

/// \brief The median of `x` (the upper one of an even count), NaN when empty.
inline double median(std::vector<double> x) {
  if (x.empty()) return NAN;
  std::sort(x.begin(), x.end());
  return x[x.size() / 2];
}

}  // namespace rbsf::bench
