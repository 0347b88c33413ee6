#include "rbsf/plan/confidence.h"

#include <cmath>
#include <string>

#include "rbsf/dynamics/core/errors.h"

namespace rbsf::plan {

namespace {

/// ln Gamma(x) for x > 0: Stirling's series from x >= 10, the recurrence below. Written out
/// rather than std::lgamma, which writes the global signgam (a data race when certificates
/// run on several threads).
double logGamma(double x) {
  double shift = 0.0;
  while (x < 10.0) {
    shift -= std::log(x);
    x += 1.0;
  }
  const double inv = 1.0 / x, inv2 = inv * inv;
  const double series =
      inv * (1.0 / 12 - inv2 * (1.0 / 360 - inv2 * (1.0 / 1260 - inv2 * (1.0 / 1680))));
  return shift + (x - 0.5) * std::log(x) - x + 0.5 * std::log(2.0 * M_PI) + series;
}

/// The continued fraction of I_p(a, b) (modified Lentz), fast for p < (a + 1) / (a + b + 2).
double betaFraction(double a, double b, double p) {
  constexpr double kTiny = 1e-300;
  const double qab = a + b, qap = a + 1.0, qam = a - 1.0;
  double c = 1.0, d = 1.0 - qab * p / qap;
  if (std::abs(d) < kTiny) d = kTiny;
  d = 1.0 / d;
  double h = d;
  for (int m = 1; m <= 100000; ++m) {
    const double m2 = 2.0 * m;
    double aa = m * (b - m) * p / ((qam + m2) * (a + m2));
    d = 1.0 + aa * d;
    if (std::abs(d) < kTiny) d = kTiny;
    c = 1.0 + aa / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    h *= d * c;
    aa = -(a + m) * (qab + m) * p / ((a + m2) * (qap + m2));
    d = 1.0 + aa * d;
    if (std::abs(d) < kTiny) d = kTiny;
    c = 1.0 + aa / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-16) break;
  }
  return h;
}

/// I_p(a, b) for a, b > 0, p in (0, 1).
double incompleteBeta(double a, double b, double p) {
  const double log_front =
      logGamma(a + b) - logGamma(a) - logGamma(b) + a * std::log(p) + b * std::log1p(-p);
  if (p < (a + 1.0) / (a + b + 2.0)) return std::exp(log_front) * betaFraction(a, b, p) / a;
  return 1.0 - std::exp(log_front) * betaFraction(b, a, 1.0 - p) / b;
}

}  // namespace

double binomialUpperTail(int x, int n, double p) {
  if (x <= 0) return 1.0;
  if (x > n) return 0.0;
  if (!(p > 0.0)) return 0.0;
  if (!(p < 1.0)) return 1.0;
  return incompleteBeta(x, n - x + 1.0, p);
}

double clopperPearsonLower(int successes, int trials, double confidence) {
  if (trials < 1 || successes < 0 || successes > trials)
    throw InputError("confidence bound: successes must be in 0..trials and trials >= 1 (got " +
                     std::to_string(successes) + " of " + std::to_string(trials) + ")");
  if (!(confidence > 0.0 && confidence < 1.0))
    throw InputError("confidence bound: the confidence must be in (0, 1)");
  const double alpha = 1.0 - confidence;
  if (successes == 0) return 0.0;
  if (successes == trials) return std::pow(alpha, 1.0 / trials);
  // The tail grows with p from 0 (p = 0) to 1 (p = 1): bisection to the last bits.
  double lo = 0.0, hi = 1.0;
  for (int k = 0; k < 200 && hi - lo > 1e-15; ++k) {
    const double mid = 0.5 * (lo + hi);
    (binomialUpperTail(successes, trials, mid) < alpha ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace rbsf::plan
