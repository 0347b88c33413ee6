// Derivatives of the optimiser's NLP: every constraint block's AutoDiff Jacobian, the cost
// gradients and the exact Hessian of the Lagrangian against central finite differences
// (over every variable, xi and the run durations included), the AutoDiff dynamics against
// RbsfModel, and Ipopt's own derivative checker on a small instance.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>

#include "rbsf/trajopt/ad_dynamics.h"
#include "rbsf/trajopt/plan_optimizer.h"
#include "rbsf/trajopt/trajectory_problem.h"
#include "trajopt_support.h"

namespace rbsf::trajopt {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

OptimizerSettings smallSettings() {
  OptimizerSettings s;
  s.knots = 12;
  return s;
}

// The problems every derivative is checked on: a kinodynamic plan's (runs by phase letter)
// and a support plan's (runs on its stated roles, three tips sticking: the least-norm rows).
struct Case {
  const char* name;
  const plan::Plan& plan;
  OptimizerSettings settings;
};
std::vector<Case> cases() {
  OptimizerSettings support = smallSettings();
  support.stated_roles = true;
  support.normal_floor = 0.08;
  support.motion_limits = true;
  support.tube_position = 0.01;
  support.tube_angle = 0.035;
  return {{"kinodynamic plan", test::shortPlan(), smallSettings()},
          {"support plan", test::threeTipPlan(), support}};
}

// A generic point near the initial guess: every variable moved a little, so no entry is
// accidentally at a special value (f_t = 0, v = 0).
VectorXd testPoint(const TrajectoryProblem& p) {
  VectorXd z = p.variables().initialGuess();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int c = 0; c < z.size(); ++c) z[c] += 0.01 * u(rng) * (1.0 + 0.1 * std::abs(z[c]));
  return z;
}

MatrixXd denseJacobian(const ConstraintSet& set, const VectorXd& z) {
  std::vector<double> values(set.structure().size());
  set.jacobian(z, values.data());
  MatrixXd J = MatrixXd::Zero(set.rows(), z.size());
  for (std::size_t e = 0; e < values.size(); ++e)
    J(set.structure()[e].first, set.structure()[e].second) += values[e];
  return J;
}

TEST(TrajoptDerivatives, ConstraintJacobiansMatchCentralDifferences) {
  for (const Case& k : cases()) {
    SCOPED_TRACE(k.name);
    const TrajectoryProblem p(test::defaultModel(), k.plan, k.settings);
    ASSERT_TRUE(p.ok()) << p.why();
    const VectorXd z = testPoint(p);
    bool internal = false;
    for (const auto& set : p.constraints()) {
      internal = internal || (set->name() == "internal_force" && set->rows() > 0);
      const MatrixXd J = denseJacobian(*set, z);
      MatrixXd fd(set->rows(), z.size());
      VectorXd gp(set->rows()), gm(set->rows());
      for (int c = 0; c < z.size(); ++c) {
        const double step = 1e-6 * std::max(1.0, std::abs(z[c]));
        VectorXd zp = z, zm = z;
        zp[c] += step;
        zm[c] -= step;
        set->values(zp, gp);
        set->values(zm, gm);
        fd.col(c) = (gp - gm) / (2.0 * step);
      }
      // Entrywise, relative to the entry's size (the rows mix N and m/s scales).
      const MatrixXd err = (J - fd).cwiseAbs().cwiseQuotient(
          fd.cwiseAbs().cwiseMax(MatrixXd::Ones(fd.rows(), fd.cols())));
      Eigen::Index r, c;
      const double worst = err.maxCoeff(&r, &c);
      EXPECT_LT(worst, 1e-6) << set->name() << " row " << r << " col " << c << ": " << J(r, c)
                             << " vs " << fd(r, c);
    }
    if (k.settings.stated_roles) {
      EXPECT_TRUE(internal) << "no least-norm row was checked";
    }
  }
}

TEST(TrajoptDerivatives, CostGradientsMatchCentralDifferences) {
  for (const Case& k : cases()) {
    SCOPED_TRACE(k.name);
    const TrajectoryProblem p(test::defaultModel(), k.plan, k.settings);
    const VectorXd z = testPoint(p);
    for (const auto& cost : p.costs()) {
      VectorXd g = VectorXd::Zero(z.size()), fd(z.size());
      cost->addGradient(z, g);
      for (int c = 0; c < z.size(); ++c) {
        const double step = 1e-6 * std::max(1.0, std::abs(z[c]));
        VectorXd zp = z, zm = z;
        zp[c] += step;
        zm[c] -= step;
        fd[c] = (cost->value(zp) - cost->value(zm)) / (2.0 * step);
      }
      EXPECT_LT((g - fd).cwiseAbs().maxCoeff(), 1e-7 * std::max(1.0, fd.cwiseAbs().maxCoeff()))
          << cost->name();
    }
  }
}

// grad_z (sigma J + lambda^T g) from the analytic gradient and Jacobian.
VectorXd lagrangianGradient(const TrajectoryProblem& p, const VectorXd& z, double sigma,
                            const VectorXd& lambda) {
  VectorXd g = VectorXd::Zero(z.size());
  p.gradient(z, g);
  g *= sigma;
  std::vector<double> values(p.nonZeros());
  p.jacobianValues(z, values.data());
  for (int e = 0; e < p.nonZeros(); ++e)
    g[p.jacobianCols()[e]] += lambda[p.jacobianRows()[e]] * values[e];
  return g;
}

TEST(TrajoptDerivatives, LagrangianHessianMatchesCentralDifferences) {
  for (const Case& k : cases()) {
    SCOPED_TRACE(k.name);
    const TrajectoryProblem p(test::defaultModel(), k.plan, k.settings);
    // Knots shared by intervals of two runs (two steps h) are in the check.
    ASSERT_GE(p.layout().runs(), 2);
    const VectorXd z = testPoint(p);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    VectorXd lambda(p.rows());
    for (int r = 0; r < p.rows(); ++r) lambda[r] = u(rng);
    const double sigma = 0.7;
    std::vector<double> values(p.hessianPattern().size());
    p.hessianValues(z, sigma, lambda.data(), values.data());
    MatrixXd H = MatrixXd::Zero(z.size(), z.size());
    for (std::size_t e = 0; e < values.size(); ++e) {
      const int r = p.hessianPattern().rows()[e], c = p.hessianPattern().cols()[e];
      ASSERT_GE(r, c);  // lower triangle, as Ipopt wants it
      H(r, c) += values[e];
      if (r != c) H(c, r) += values[e];
    }
    MatrixXd fd(z.size(), z.size());
    for (int c = 0; c < z.size(); ++c) {
      const double step = 1e-6 * std::max(1.0, std::abs(z[c]));
      VectorXd zp = z, zm = z;
      zp[c] += step;
      zm[c] -= step;
      fd.col(c) =
          (lagrangianGradient(p, zp, sigma, lambda) - lagrangianGradient(p, zm, sigma, lambda)) /
          (2.0 * step);
    }
    const MatrixXd err = (H - fd).cwiseAbs().cwiseQuotient(
        fd.cwiseAbs().cwiseMax(MatrixXd::Ones(fd.rows(), fd.cols())));
    Eigen::Index r, c;
    const double worst = err.maxCoeff(&r, &c);
    EXPECT_LT(worst, 1e-5) << "row " << r << " col " << c << ": " << H(r, c) << " vs " << fd(r, c);
  }
}

TEST(TrajoptDerivatives, AutoDiffDynamicsAgreesWithModel) {
  // knotRhs (templated, AutoDiff-ready) against RbsfModel: u + G1 f_n + T f_t - Q at the
  // closest points of a configuration.
  const RbsfModel& model = test::defaultModel();
  const int m = model.numFingers(), n = model.configDim();
  const DecisionLayout dl(m, 1, 1);
  std::vector<double> knot(dl.knotSize());
  VecQ q = test::shortPlan().samples[5].q, v = test::shortPlan().samples[5].v;
  v[layout::kTheta] += 0.3;
  for (int i = 0; i < m; ++i) v[layout::stroke(i)] += 0.1 * (i + 1);
  ModelData data(m);
  model.updateContacts(q, data);
  VecU tau(m + 1);
  VecC fn(m), ft(m);
  for (int j = 0; j <= m; ++j) tau[j] = 10.0 * (j + 1);
  for (int i = 0; i < m; ++i) {
    fn[i] = 50.0 + i;
    ft[i] = 5.0 - 3.0 * i;
  }
  for (int a = 0; a < n; ++a) {
    knot[a] = q[a];
    knot[dl.localV() + a] = v[a];
  }
  for (int j = 0; j <= m; ++j) knot[dl.localTau() + j] = tau[j];
  for (int i = 0; i < m; ++i) {
    knot[dl.localFn() + i] = fn[i];
    knot[dl.localFt() + i] = ft[i];
    knot[dl.localXi() + i] = data.contacts[i].xi;
  }
  ConfigVector<double> r;
  knotRhs<double>(model, dl, knot.data(), 0, r);
  VecQ u, Q;
  model.generalizedInput(tau, u);
  model.bias(q, v, Q);
  const VecQ expected = u + data.G1 * fn + data.T * ft - Q;
  EXPECT_LT((r - expected).cwiseAbs().maxCoeff(), 1e-9);
  // and M(q) a.
  MatQQ M;
  model.massMatrix(q, M);
  ConfigVector<double> a(n), Ma;
  for (int c = 0; c < n; ++c) a[c] = 0.3 * c - 1.0;
  massTimes<double>(model.cell(), knot.data(), 0, a, Ma);
  EXPECT_LT((Ma - M * a).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(TrajoptDerivatives, IpoptDerivativeCheckerFindsNoErrors) {
  char path[] = "/tmp/rbsf_trajopt_dtXXXXXX";
  const int fd = mkstemp(path);
  ASSERT_GE(fd, 0);
  close(fd);
  OptimizerSettings s;
  s.knots = 10;
  s.max_iterations = 0;  // check at the initial guess, no solve
  s.derivative_test = true;
  s.derivative_test_file = path;
  const PlanOptimizer opt(test::defaultModel(), s);
  opt.optimize(test::shortPlan());
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  std::remove(path);
  const std::string out = text.str();
  ASSERT_NE(out.find("Starting derivative checker for first derivatives"), std::string::npos)
      << out;
  EXPECT_NE(out.find("No errors detected by derivative checker."), std::string::npos)
      << out.substr(0, 20000);
}

}  // namespace
}  // namespace rbsf::trajopt
