#pragma once
/// \file
/// \brief The exact one-sided Clopper-Pearson lower confidence bound of a success rate, the
///        rule by which a certificate (certificate.h) judges its trials.
///
/// For x successes in n independent trials with success probability p, the one-sided lower
/// bound at confidence c is the p_L with
///
///     P(X >= x | n, p_L) = sum_{k=x}^{n} C(n, k) p_L^k (1 - p_L)^(n-k) = 1 - c,
///
/// so that a true rate below p_L would give x or more successes with probability less than
/// 1 - c. Equivalently p_L is the (1 - c) quantile of Beta(x, n - x + 1), because
/// P(X >= x | n, p) = I_p(x, n - x + 1), the regularized incomplete beta function. Edge
/// cases in closed form: p_L = 0 for x = 0 and p_L = (1 - c)^(1/n) for x = n. Examples at
/// c = 0.95: 64/64 gives 0.9543, 126/128 gives 0.9516, 32/32 gives 0.9106; at least 59 of
/// 59 trials are needed for a bound of 0.95.
///
/// "Exact" means the bound is computed from the binomial distribution itself (no normal
/// approximation): its coverage is at least c for every p, conservative for small n.

namespace rbsf::plan {

/// \brief P(X >= x) for X ~ Binomial(n, p), as I_p(x, n - x + 1) (Lentz's continued
///        fraction of the incomplete beta function); 1 for x <= 0, 0 for x > n. Relative
///        error about 1e-12 for n up to 100000.
double binomialUpperTail(int x, int n, double p);

/// \brief The one-sided Clopper-Pearson lower bound p_L of the success rate (file comment)
///        for `successes` of `trials` at `confidence` in (0, 1): bisection on
///        binomialUpperTail, to about 1e-12.
/// \throws InputError unless 0 <= successes <= trials, trials >= 1 and confidence in (0, 1).
double clopperPearsonLower(int successes, int trials, double confidence);

}  // namespace rbsf::plan
