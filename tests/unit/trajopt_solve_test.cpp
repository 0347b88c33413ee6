// The optimiser on a short real plan (the planner's 15 degree turn): it converges and its
// solution is physical (dynamics residual small, f_n >= 0, sticking forces in their cones,
// goal reached at rest, effort lower than the planner's); failures keep the input plan.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/planner/pipeline/refine_and_certify.h"
#include "rbsf/trajopt/plan_optimizer.h"
#include "rbsf/trajopt/plan_refinement.h"
#include "rbsf/trajopt/trajectory_problem.h"
#include "trajopt_support.h"

namespace rbsf::trajopt {
namespace {

OptimizerSettings testSettings() {
  OptimizerSettings s;
  s.knots = 30;
  return s;
}

class TrajoptSolve : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const PlanOptimizer opt(test::defaultModel(), testSettings());
    result_ = new OptimizedPlan(opt.optimize(test::shortPlan()));
  }
  static void TearDownTestSuite() { delete result_; }
  static OptimizedPlan* result_;
};
OptimizedPlan* TrajoptSolve::result_ = nullptr;

TEST_F(TrajoptSolve, ConvergesAndLowersTheEffort) {
  const plan::OptimizationSummary& o = result_->summary;
  ASSERT_TRUE(result_->success) << toString(o.status) << ": " << o.message;
  EXPECT_TRUE(o.ran);
  EXPECT_TRUE(plan::converged(o.status)) << toString(o.status);
  EXPECT_GT(o.iterations, 0);
  EXPECT_TRUE(o.message.empty());
  EXPECT_NEAR(o.cost_before, planEffort(test::defaultModel(), test::shortPlan()), 1e-12);
  EXPECT_LT(o.cost_after, o.cost_before);
  // The phase sequence is the planner's.
  EXPECT_EQ(result_->plan.phaseSequence(), test::shortPlan().phaseSequence());
}

TEST_F(TrajoptSolve, SolutionIsPhysical) {
  ASSERT_TRUE(result_->success);
  const RbsfModel& model = test::defaultModel();
  const plan::Plan& out = result_->plan;
  const plan::Plan& in = test::shortPlan();
  const int m = model.numFingers();
  ASSERT_EQ(out.samples.size(), out.segments.size() + 1);
  // Start = q0 at rest; end = goal pose at rest.
  EXPECT_LT((out.samples.front().q - in.q0).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT(out.samples.front().v.cwiseAbs().maxCoeff(), 1e-9);
  const plan::PlanSample& last = out.samples.back();
  EXPECT_NEAR(last.q[layout::kX], in.goal.x, 1e-6);
  EXPECT_NEAR(last.q[layout::kY], in.goal.y, 1e-6);
  EXPECT_NEAR(std::remainder(last.q[layout::kPhi] - in.goal.phi, 2 * M_PI), 0.0, 1e-6);
  EXPECT_LT(last.v.cwiseAbs().maxCoeff(), 1e-9);
  // Durations and tau ramps consistent with the samples.
  double t = 0.0;
  for (std::size_t k = 0; k < out.segments.size(); ++k) {
    EXPECT_NEAR(out.samples[k].t, t, 1e-9);
    EXPECT_GT(out.segments[k].duration, 0.0);
    EXPECT_LT((out.segments[k].tau - out.samples[k].tau).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((out.segments[k].tau_end - out.samples[k + 1].tau).cwiseAbs().maxCoeff(), 1e-12);
    t += out.segments[k].duration;
  }
  const Cell& cell = model.cell();
  for (const plan::PlanSample& s : out.samples) {
    for (int i = 0; i < m; ++i) EXPECT_GE(s.f_n[i], -1e-6);
    EXPECT_GE(s.q[layout::kTheta], cell.base.theta_min - 1e-6);
    EXPECT_LE(s.q[layout::kTheta], cell.base.theta_max + 1e-6);
    for (int i = 0; i < m; ++i) {
      EXPECT_GE(s.q[layout::stroke(i)], cell.fingers[i].stroke_min - 1e-6);
      EXPECT_LE(s.q[layout::stroke(i)], cell.fingers[i].stroke_max + 1e-6);
      EXPECT_LE(std::abs(s.tau[layout::fingerForce(i)]), cell.fingers[i].force_limit + 1e-6);
    }
  }
}

TEST_F(TrajoptSolve, DynamicsAndConesHoldByRbsfModel) {
  // Independent of the NLP's own code: RbsfModel's contact frames (closest points), mass
  // matrix and bias give the velocity-Verlet residuals of M dv/dt = u + G1 f_n + T f_t - Q
  // with each knot's own forces: M_k (q_k+1 - q_k - h v_k) = h^2/2 r_k and
  // 1/2 (M_k + M_k+1) (v_k+1 - v_k) = h/2 (r_k + r_k+1).
  ASSERT_TRUE(result_->success);
  const RbsfModel& model = test::defaultModel();
  const plan::Plan& out = result_->plan;
  const int m = model.numFingers();
  const TrajectoryProblem p(model, test::shortPlan(), testSettings());
  const double weight = model.cell().object.mass * model.cell().gravity;
  const double mu = testSettings().cone_margin * model.cell().friction.mu_static;
  ModelData data(m);
  // r at knot e with its forces; checks contacts and cones on the way.
  auto rhs = [&](std::size_t e, VecQ& r, MatQQ& M) {
    const plan::PlanSample& s = out.samples[e];
    const VecC& f_n = s.f_n;
    const VecC& f_t = result_->f_t[e];
    model.updateContacts(s.q, data);
    VecQ u, Q;
    model.generalizedInput(s.tau, u);
    model.bias(s.q, s.v, Q);
    r = u + data.G1 * f_n + data.T * f_t - Q;
    model.massMatrix(s.q, M);
    for (int i = 0; i < m; ++i) {
      if (p.schedule().knotRole(static_cast<int>(e), i) != ContactRole::kOff)
        EXPECT_LT(std::abs(data.contacts[i].gap), 1e-6) << "knot " << e << " finger " << i;
      else
        EXPECT_GT(data.contacts[i].gap, -1e-6) << "knot " << e << " finger " << i;
      const ContactRole role = p.schedule().forceRole(static_cast<int>(e), i);
      if (role == ContactRole::kOff) {
        EXPECT_EQ(f_n[i], 0.0) << "knot " << e;
      }
      if (role == ContactRole::kStick)
        EXPECT_LE(std::abs(f_t[i]), mu * f_n[i] + 1e-6) << "knot " << e;
      else
        EXPECT_EQ(f_t[i], 0.0) << "knot " << e;
    }
  };
  double worst_q = 0.0, worst_v = 0.0;
  VecQ r0, r1;
  MatQQ M0, M1;
  for (std::size_t k = 0; k + 1 < out.samples.size(); ++k) {
    const plan::PlanSample &a = out.samples[k], &b = out.samples[k + 1];
    rhs(k, r0, M0);
    rhs(k + 1, r1, M1);
    const double h = b.t - a.t;
    const VecQ res_q = M0 * (b.q - a.q - h * a.v) / (h * h) - 0.5 * r0;
    const VecQ res_v = 0.5 * (M0 + M1) * (b.v - a.v) / h - 0.5 * (r0 + r1);
    worst_q = std::max(worst_q, res_q.cwiseAbs().maxCoeff());
    worst_v = std::max(worst_v, res_v.cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst_q, 1e-4 * weight);
  EXPECT_LT(worst_v, 1e-4 * weight);
}

TEST_F(TrajoptSolve, StickingContactsHoldTheirFootPointsAndSlidesKeepTheirDirection) {
  // Sticking: the contact is fixed in the object frame (xi constant over the interval).
  // Sliding with a planned direction: xi moves that way or not at all (keep_slide_direction).
  ASSERT_TRUE(result_->success);
  const TrajectoryProblem p(test::defaultModel(), test::shortPlan(), testSettings());
  const Schedule& sched = p.schedule();
  int sticking = 0, sliding = 0;
  for (int k = 0; k < sched.intervals(); ++k) {
    const PhaseRun& run = sched.runOf(k);
    for (int i = 0; i < test::defaultModel().numFingers(); ++i) {
      const double dxi = result_->xi[k + 1][i] - result_->xi[k][i];
      if (sched.role(k, i) == ContactRole::kStick) {
        EXPECT_NEAR(dxi, 0.0, 1e-7) << "interval " << k << " finger " << i;
        ++sticking;
      } else if (sched.role(k, i) == ContactRole::kSlide && run.slide_direction[i] != 0) {
        EXPECT_GE(run.slide_direction[i] * dxi, -1e-7) << "interval " << k << " finger " << i;
        ++sliding;
      }
    }
  }
  EXPECT_GT(sticking, 0);  // the plan (C, P, U) has both kinds
  EXPECT_GT(sliding, 0);
}

TEST(TrajoptFailure, IterationLimitKeepsTheInputPlan) {
  OptimizerSettings s = testSettings();
  s.max_iterations = 1;
  const PlanOptimizer opt(test::defaultModel(), s);
  const OptimizedPlan out = opt.optimize(test::shortPlan());
  EXPECT_FALSE(out.success);
  const plan::OptimizationSummary& o = out.summary;
  EXPECT_TRUE(o.ran);
  EXPECT_EQ(o.status, plan::SolverStatus::kMaximumIterationsExceeded);
  EXPECT_NE(o.message.find("planner's plan is kept"), std::string::npos) << o.message;
  EXPECT_EQ(out.plan.segments.size(), test::shortPlan().segments.size());
  EXPECT_EQ(out.plan.samples.size(), test::shortPlan().samples.size());
  EXPECT_TRUE(out.plan.segments.front().tau_end.size() == 0);
}

TEST(TrajoptFailure, ARaisedCancelStopsTheSolveAndKeepsTheInputPlan) {
  // The call's cancel flag (not a setting): raised before the solve, Ipopt stops at its
  // first iteration and the planner's plan is returned; the fixture above, uncancelled,
  // converges with the same settings.
  const PlanOptimizer opt(test::defaultModel(), testSettings());
  const std::atomic<bool> raised{true};
  const OptimizedPlan out = opt.optimize(test::shortPlan(), &raised);
  EXPECT_FALSE(out.success);
  EXPECT_EQ(out.summary.status, plan::SolverStatus::kUserRequestedStop);
  EXPECT_LE(out.summary.iterations, 1);
  EXPECT_EQ(out.plan.segments.size(), test::shortPlan().segments.size());
  EXPECT_EQ(out.plan.samples.size(), test::shortPlan().samples.size());
}

TEST(TrajoptOptions, AnIpoptOptFileInTheWorkingDirectoryIsIgnored) {
  // Ipopt reads ./ipopt.opt unless told not to; the optimiser's result must not depend on
  // the caller's working directory. The file here would stop Ipopt after one iteration.
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("rbsf_ipopt_opt_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "ipopt.opt") << "max_iter 1\n";
  const std::filesystem::path cwd = std::filesystem::current_path();
  std::filesystem::current_path(dir);
  const PlanOptimizer opt(test::defaultModel(), testSettings());
  const OptimizedPlan out = opt.optimize(test::shortPlan());
  std::filesystem::current_path(cwd);
  std::filesystem::remove_all(dir);
  EXPECT_TRUE(out.success) << toString(out.summary.status);
  EXPECT_GT(out.summary.iterations, 1);
}

TEST(TrajoptSlipRate, SlidingContactsSlideAtLeastAtTheMinimumRate) {
  // The replay sees a sliding contact at rest as sticking; with min_slip_rate the NLP keeps
  // each planned slide moving its way at >= w = min(min_slip_rate, half the planned mean
  // rate over the run) on every interval.
  OptimizerSettings s = testSettings();
  s.min_slip_rate = 0.1;
  const OptimizedPlan out = PlanOptimizer(test::defaultModel(), s).optimize(test::shortPlan());
  ASSERT_TRUE(out.success) << out.summary.message;
  const TrajectoryProblem p(test::defaultModel(), test::shortPlan(), s);
  const Schedule& sched = p.schedule();
  struct Slide {
    int k, i;
    double moved, minimum;  ///< s (xi_k+1 - xi_k) and w h
  };
  // Every interval's planned slide in a refinement, with the minimum the rule asks.
  auto slides = [&](const OptimizedPlan& r) {
    std::vector<Slide> out;
    for (int k = 0; k < sched.intervals(); ++k) {
      const PhaseRun& run = sched.runOf(k);
      const double h = r.plan.samples[k + 1].t - r.plan.samples[k].t;
      for (int i = 0; i < test::defaultModel().numFingers(); ++i) {
        if (sched.role(k, i) != ContactRole::kSlide || run.slide_direction[i] == 0) continue;
        const double w = std::min(s.min_slip_rate, 0.5 * run.slide_rate[i]);
        out.push_back({k, i, run.slide_direction[i] * (r.xi[k + 1][i] - r.xi[k][i]), w * h});
      }
    }
    return out;
  };
  auto slowest = [](const std::vector<Slide>& all) {  // least ratio of slide to its minimum
    double least = 1e9;
    for (const Slide& x : all) least = std::min(least, x.moved / x.minimum);
    return least;
  };
  const std::vector<Slide> held = slides(out);
  for (const Slide& x : held)
    EXPECT_GE(x.moved, x.minimum - 1e-7) << "interval " << x.k << " finger " << x.i;
  EXPECT_GT(held.size(), 0u);
  // Without the minimum the same plan's refinement lets some slide nearly stop.
  const OptimizedPlan free =
      PlanOptimizer(test::defaultModel(), testSettings()).optimize(test::shortPlan());
  ASSERT_TRUE(free.success);
  EXPECT_LT(slowest(slides(free)), 1.0 - 1e-3) << "the minimum would constrain nothing here";
  EXPECT_GE(slowest(held), 1.0 - 1e-5);
}

TEST(TrajoptRefinement, AFailedSolveIsRetriedOnceWithAMinimumSlipRate) {
  // One Ipopt iteration never converges: both solves fail, the reason names both, and the
  // planner's plan is written with its own certificate; with the retry switched off there
  // is one solve.
  OptimizerSettings s = testSettings();
  s.max_iterations = 1;
  const plan::Plan& plan = test::shortPlan();
  plan::CertificateSettings few;
  few.trials = 4;
  const planner::RefinementResult twice =
      planner::refineAndCertify(PlanRefiner(test::defaultModel(), s), plan, {}, few);
  EXPECT_FALSE(twice.refined);
  EXPECT_EQ(twice.solves, 2);
  EXPECT_NE(twice.reason.find("Maximum_Iterations_Exceeded"), std::string::npos) << twice.reason;
  EXPECT_NE(twice.reason.find("retry with min_slip_rate 0.100000: optimisation failed"),
            std::string::npos)
      << twice.reason;
  EXPECT_EQ(twice.record.optimization.message, twice.reason);
  EXPECT_FALSE(twice.record.optimization.chosen);
  EXPECT_EQ(twice.record.plan.segments.size(), plan.segments.size());  // the planner's, kept
  ASSERT_TRUE(twice.record.certificate.ran);
  EXPECT_EQ(twice.record.certificate.trials, 4);
  EXPECT_EQ(twice.record.certificate.successes, twice.planner_certificate.successes);
  RefineSettings no_retry;
  no_retry.retry_min_slip_rate = 0.0;
  const planner::RefinementResult once =
      planner::refineAndCertify(PlanRefiner(test::defaultModel(), s, no_retry), plan, {}, few);
  EXPECT_EQ(once.solves, 1);
  EXPECT_EQ(once.reason.find("retry"), std::string::npos) << once.reason;
}

TEST(TrajoptRefinement, TheBetterCertificateIsWritten) {
  // A converged refinement is certified beside the planner's plan, and the plan written
  // carries the certificate of the one chosen: never fewer successes than the other's.
  const plan::Plan& plan = test::shortPlan();
  plan::CertificateSettings few;
  few.trials = 4;
  RefineSettings no_retry;
  no_retry.retry_min_slip_rate = 0.0;
  const planner::RefinementResult out = planner::refineAndCertify(
      PlanRefiner(test::defaultModel(), testSettings(), no_retry), plan, {}, few);
  ASSERT_EQ(out.solves, 1);
  struct {
    const plan::Plan& plan;
    const plan::OptimizationSummary& optimization;
    const plan::Certificate& certificate;
  } r_plan{out.record.plan, out.record.optimization, out.record.certificate};
  const planner::RefinementResult& r = out;
  ASSERT_TRUE(r_plan.certificate.ran);
  const double refined_rate = r_plan.optimization.refined_success_rate;
  ASSERT_GE(refined_rate, 0.0) << r_plan.optimization.message;
  EXPECT_GE(r_plan.certificate.success_rate, r.planner_certificate.success_rate);
  EXPECT_GE(r_plan.certificate.success_rate, refined_rate);
  EXPECT_EQ(r.refined, r_plan.optimization.chosen);
  if (r.refined) {
    EXPECT_EQ(r_plan.certificate.success_rate, refined_rate);
  } else {
    EXPECT_EQ(r_plan.plan.segments.size(), plan.segments.size());
    EXPECT_EQ(r_plan.certificate.successes, r.planner_certificate.successes);
  }
}

TEST(TrajoptFailure, TooFewKnotsForThePhaseRunsIsReported) {
  OptimizerSettings s;
  s.knots = 3;  // fewer than 2 per run
  const PlanOptimizer opt(test::defaultModel(), s);
  const OptimizedPlan out = opt.optimize(test::shortPlan());
  EXPECT_FALSE(out.success);
  EXPECT_EQ(out.summary.status, plan::SolverStatus::kNotSolved);
  EXPECT_NE(out.summary.message.find("knots"), std::string::npos);
  EXPECT_EQ(out.plan.segments.size(), test::shortPlan().segments.size());
}

TEST(TrajoptFailure, InfeasibleGoalIsReportedAndThePlanKept) {
  // A goal 1 m away cannot be reached within the strokes: Ipopt fails, the plan is kept.
  plan::Plan far = test::shortPlan();
  far.goal.x += 1.0;
  OptimizerSettings s = testSettings();
  s.knots = 20;
  s.max_iterations = 100;
  const PlanOptimizer opt(test::defaultModel(), s);
  const OptimizedPlan out = opt.optimize(far);
  EXPECT_FALSE(out.success);
  EXPECT_NE(out.summary.status, plan::SolverStatus::kSolveSucceeded);
  EXPECT_NE(out.summary.message.find("did not converge"), std::string::npos) << out.summary.message;
  EXPECT_EQ(out.plan.segments.size(), far.segments.size());
  EXPECT_TRUE(out.f_t.empty());
}

TEST(TrajoptFailure, BadSettingsAndMismatchedPlansThrow) {
  OptimizerSettings s;
  s.knots = 1;
  EXPECT_THROW(PlanOptimizer(test::defaultModel(), s), InputError);
  s = OptimizerSettings{};
  s.cone_margin = 1.5;
  EXPECT_THROW(PlanOptimizer(test::defaultModel(), s), InputError);
  s = OptimizerSettings{};
  s.duration_max_scale = 0.5;
  EXPECT_THROW(PlanOptimizer(test::defaultModel(), s), InputError);
  plan::Plan bad = test::shortPlan();
  bad.q0 = VecQ::Zero(3);
  EXPECT_THROW(PlanOptimizer(test::defaultModel()).optimize(bad), InputError);
}

}  // namespace
}  // namespace rbsf::trajopt
