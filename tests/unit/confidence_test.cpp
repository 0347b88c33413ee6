// The one-sided Clopper-Pearson lower bound (plan/confidence.h): known values, values
// checked against the Beta quantile relation computed another way (closed forms and a
// direct binomial sum), its monotonicity, and its refusals.
#include <gtest/gtest.h>

#include <cmath>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/plan/confidence.h"

namespace rbsf::plan {
namespace {

/// P(X >= x | n, p) summed term by term in log space: independent of the continued
/// fraction behind binomialUpperTail.
double tailBySum(int x, int n, double p) {
  double sum = 0.0;
  for (int k = x; k <= n; ++k)
    sum += std::exp(std::lgamma(n + 1.0) - std::lgamma(k + 1.0) - std::lgamma(n - k + 1.0) +
                    k * std::log(p) + (n - k) * std::log1p(-p));
  return sum;
}

/// The p at which a tail that grows with p equals `alpha`, by bisection.
template <class Tail>
double solve(Tail tail, double alpha) {
  double lo = 0.0, hi = 1.0;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (tail(mid) < alpha ? lo : hi) = mid;
  }
  return lo;
}

TEST(ClopperPearson, KnownValues) {
  EXPECT_NEAR(clopperPearsonLower(64, 64, 0.95), 0.9543, 5e-5);
  EXPECT_NEAR(clopperPearsonLower(126, 128, 0.95), 0.9516, 5e-5);
  EXPECT_NEAR(clopperPearsonLower(32, 32, 0.95), 0.9106, 5e-5);
  // 5 of 10: the lower end of the textbook two-sided 90 % interval [0.2224, 0.7776].
  EXPECT_NEAR(clopperPearsonLower(5, 10, 0.95), 0.2224, 5e-5);
  // Computed with exact rational binomial sums (Python fractions) and bisection.
  EXPECT_NEAR(clopperPearsonLower(60, 64, 0.95), 0.8626601192, 1e-9);
  EXPECT_NEAR(clopperPearsonLower(57, 64, 0.95), 0.8043596004, 1e-9);
  EXPECT_NEAR(clopperPearsonLower(120, 128, 0.90), 0.9004610716, 1e-9);
  EXPECT_NEAR(clopperPearsonLower(190, 192, 0.99), 0.9569430095, 1e-9);
  EXPECT_NEAR(clopperPearsonLower(3, 4, 0.95), 0.2486046257, 1e-9);
  EXPECT_NEAR(clopperPearsonLower(500, 512, 0.95), 0.9623023739, 1e-9);
  // 59 of 59 is the fewest all-success trials that reach 0.95, 58 of 58 fall short.
  EXPECT_GE(clopperPearsonLower(59, 59, 0.95), 0.95);
  EXPECT_LT(clopperPearsonLower(58, 58, 0.95), 0.95);
}

TEST(ClopperPearson, IsTheBetaQuantileComputedOtherWays) {
  // The bound is the (1 - c) quantile of Beta(x, n - x + 1). Its CDF in closed form:
  // x = n: p^n; x = 1: 1 - (1 - p)^n; x = n - 1: n p^(n-1) - (n - 1) p^n.
  for (int n : {1, 2, 7, 64, 300}) {
    for (double c : {0.5, 0.9, 0.95, 0.99}) {
      const double alpha = 1.0 - c;
      EXPECT_NEAR(clopperPearsonLower(n, n, c), std::pow(alpha, 1.0 / n), 1e-12) << n;
      EXPECT_NEAR(clopperPearsonLower(1, n, c), 1.0 - std::pow(c, 1.0 / n), 1e-12) << n;
      if (n >= 2) {
        const double want = solve(
            [n](double p) { return n * std::pow(p, n - 1) - (n - 1) * std::pow(p, n); }, alpha);
        EXPECT_NEAR(clopperPearsonLower(n - 1, n, c), want, 1e-11) << n << " " << c;
      }
    }
  }
  // Elsewhere, against the binomial sum and its own bisection.
  for (int n : {10, 64, 200, 512}) {
    for (int x : {1, n / 3, n / 2, (9 * n) / 10, n - 2}) {
      const double want = solve([&](double p) { return tailBySum(x, n, p); }, 0.05);
      EXPECT_NEAR(clopperPearsonLower(x, n, 0.95), want, 1e-10) << x << "/" << n;
    }
  }
}

TEST(ClopperPearson, TheTailAgreesWithTheBinomialSum) {
  for (int n : {1, 5, 64, 512, 3000})
    for (double p : {0.01, 0.3, 0.9, 0.95, 0.999})
      for (int x : {0, 1, n / 2, n - 1, n}) {
        const double sum = x <= 0 ? 1.0 : tailBySum(x, n, p);
        EXPECT_NEAR(binomialUpperTail(x, n, p), sum, 1e-12 + 1e-9 * sum)
            << x << "/" << n << " at " << p;
      }
  EXPECT_EQ(binomialUpperTail(0, 10, 0.3), 1.0);
  EXPECT_EQ(binomialUpperTail(11, 10, 0.3), 0.0);
  EXPECT_EQ(binomialUpperTail(3, 10, 0.0), 0.0);
  EXPECT_EQ(binomialUpperTail(3, 10, 1.0), 1.0);
}

TEST(ClopperPearson, IsMonotoneAndBelowTheObservedRate) {
  EXPECT_EQ(clopperPearsonLower(0, 50, 0.95), 0.0);
  for (int n : {1, 8, 64, 129}) {
    double last = -1.0;
    for (int x = 0; x <= n; ++x) {
      const double b = clopperPearsonLower(x, n, 0.95);
      EXPECT_GT(b, last) << x << "/" << n;  // more successes, a higher bound
      EXPECT_LE(b, static_cast<double>(x) / n);
      EXPECT_GE(b, 0.0);
      if (x > 0) {  // a higher confidence, a lower bound
        EXPECT_LT(clopperPearsonLower(x, n, 0.99), b);
        EXPECT_GT(clopperPearsonLower(x, n, 0.9), b);
      }
      last = b;
    }
  }
  for (int n = 1; n < 600; n += 7) {
    // All successes: more of them, a higher bound; the same successes in more trials, a
    // lower one.
    EXPECT_LT(clopperPearsonLower(n, n, 0.95), clopperPearsonLower(n + 1, n + 1, 0.95));
    EXPECT_GT(clopperPearsonLower(n, n, 0.95), clopperPearsonLower(n, n + 1, 0.95));
  }
  // The bound of the rate 0.97 tightens towards it as the trials grow.
  EXPECT_LT(clopperPearsonLower(97, 100, 0.95), clopperPearsonLower(970, 1000, 0.95));
  EXPECT_LT(clopperPearsonLower(970, 1000, 0.95), clopperPearsonLower(97000, 100000, 0.95));
  EXPECT_NEAR(clopperPearsonLower(97000, 100000, 0.95), 0.97, 0.002);
}

TEST(ClopperPearson, RefusesCountsAndConfidencesOutOfRange) {
  EXPECT_THROW(clopperPearsonLower(1, 0, 0.95), InputError);
  EXPECT_THROW(clopperPearsonLower(-1, 5, 0.95), InputError);
  EXPECT_THROW(clopperPearsonLower(6, 5, 0.95), InputError);
  EXPECT_THROW(clopperPearsonLower(3, 5, 1.0), InputError);
  EXPECT_THROW(clopperPearsonLower(3, 5, 0.0), InputError);
  EXPECT_THROW(clopperPearsonLower(3, 5, std::nan("")), InputError);
}

}  // namespace
}  // namespace rbsf::plan
