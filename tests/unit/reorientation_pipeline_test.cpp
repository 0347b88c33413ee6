// The pipeline (reorientation_pipeline.h): the support planner first; a certified plan ends
// the run; otherwise seed after seed, each plan judged, the best kept; the refinement hook
// sees exact kinodynamic plans only; a cancel stops it. A written certified plan keeps the
// cell's motion limits at every sample, ends at rest and, on a blind cell, is held by the
// joints.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <variant>
#include <vector>

#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/plan/confidence.h"
#include "rbsf/plan/plan_holding.h"
#include "rbsf/planner/pipeline/reorientation_pipeline.h"

namespace rbsf::planner {
using namespace rbsf::plan;  // the plan the planner makes
namespace {

Cell defaultCell() { return loadCell(std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml"); }

const RbsfModel& defaultModel() {
  static const RbsfModel model(defaultCell());
  return model;
}

Problem turn(double degrees) {
  Problem p;
  p.start = {0.1, 0.40, 0.0};
  p.goal = {0.1, 0.40, degrees * M_PI / 180};
  return p;
}

/// Few trials: the tests are about the composition, not the rates. 4 of 4 bound the rate at
/// 0.47 (95 % confidence), so a plan that passes them certifies at 0.4.
PipelineSettings fewTrials(PipelineMethod method) {
  PipelineSettings s;
  s.method = method;
  s.planner.time_limit = 60.0;
  s.certificate.trials = 4;
  s.certificate.required_rate = 0.4;
  return s;
}

/// Every sample within the cell's motion limits and the last one at rest, from the samples
/// themselves (not from the certificate's own measurement).
void expectHandledNotThrown(const Plan& plan, const MotionLimits& limits) {
  ASSERT_FALSE(plan.samples.empty());
  for (const PlanSample& s : plan.samples) {
    EXPECT_LE(std::hypot(s.v[0], s.v[1]), limits.part_speed) << "t = " << s.t;
    EXPECT_LE(std::abs(s.v[2]), limits.angular_speed) << "t = " << s.t;
  }
  const PlanSample& end = plan.samples.back();
  EXPECT_LE(std::hypot(end.v[0], end.v[1]), limits.rest_speed);
  EXPECT_LE(std::abs(end.v[2]), limits.rest_angular_speed);
}

TEST(ReorientationPipeline, AutoTriesSupportsFirstAndACertifiedPlanEndsTheRun) {
  const RbsfModel& model = defaultModel();
  const PipelineSettings s = fewTrials(PipelineMethod::kAuto);
  std::vector<PipelineStage> stages;
  int found = 0, judged = 0, refined = 0;
  Certificate judged_certificate;
  RunContext context;
  context.on_event = [&](const PipelineEvent& e) {
    if (const auto* st = std::get_if<StageStarted>(&e)) stages.push_back(st->stage);
    if (std::holds_alternative<PlanFound>(e)) ++found;
    if (std::holds_alternative<PlanRefined>(e)) ++refined;
    if (const auto* j = std::get_if<AttemptJudged>(&e)) {
      EXPECT_EQ(found, 1) << "a plan is judged after it is found";
      judged_certificate = j->record.certificate;
      ++judged;
    }
  };
  const PipelineOutcome out = ReorientationPipeline(model, s).run(turn(-15), context);
  ASSERT_EQ(out.status, PipelineStatus::kCertified) << verdictText(out.record.certificate);
  ASSERT_EQ(out.attempts.size(), 1u);
  EXPECT_EQ(out.chosen, 0);
  EXPECT_EQ(out.attempts[0].search, SearchKind::kSupport);
  EXPECT_EQ(out.attempts[0].method(), "support");
  EXPECT_EQ(out.record.plan.planner, "support");
  // Not optimised: certified as found, the certificate the event carried is the result's.
  EXPECT_EQ(stages, (std::vector<PipelineStage>{PipelineStage::kSupportSearch,
                                                PipelineStage::kCertifying}));
  EXPECT_EQ(refined, 0);
  EXPECT_EQ(judged, 1);
  EXPECT_EQ(certificateJsonText(judged_certificate), certificateJsonText(out.record.certificate));
  EXPECT_FALSE(out.record.optimization.ran);
  EXPECT_TRUE(out.record.certificate.certified);
  EXPECT_FALSE(std::isfinite(out.best_distance));  // no kinodynamic search ran
  expectHandledNotThrown(out.record.plan, model.cell().motion_limits);
}

TEST(ReorientationPipeline, OnABlindCellTheWrittenPlanIsHeldByTheJoints) {
  Cell blind = defaultCell();
  blind.sensing.part_pose.present = false;
  const RbsfModel model(blind);
  const PipelineOutcome out =
      ReorientationPipeline(model, fewTrials(PipelineMethod::kAuto)).run(turn(-30));
  ASSERT_EQ(out.status, PipelineStatus::kCertified) << verdictText(out.record.certificate);
  EXPECT_EQ(out.record.certificate.law, TrialLaw::kJointFeedback);
  // Measured again from the plan: at least 3 independent rows but for short transitions.
  const PlanHolding h = measureHolding(model, out.record.plan, HoldingSettings{});
  ASSERT_TRUE(h.measured);
  EXPECT_LE(h.longest_free, HoldingSettings{}.max_free_time);
  expectHandledNotThrown(out.record.plan, model.cell().motion_limits);
}

TEST(ReorientationPipeline, UncertifiedPlansGoOnSeedAfterSeedAndTheBestIsKept) {
  // Kinodynamic plans of the default cell throw the part (beyond its motion limits): none
  // certifies, so both attempts run, with consecutive seeds, each judged once.
  const RbsfModel& model = defaultModel();
  PipelineSettings s = fewTrials(PipelineMethod::kKinodynamic);
  s.planner.seed = 3;
  s.max_attempts = 2;
  std::vector<std::uint32_t> judged_seeds;
  RunContext context;
  context.on_event = [&](const PipelineEvent& e) {
    if (const auto* j = std::get_if<AttemptJudged>(&e)) {
      judged_seeds.push_back(j->attempt.seed);
      EXPECT_EQ(j->record.plan.seed, j->attempt.seed);
      EXPECT_EQ(j->record.certificate.trials, 4);
    }
  };
  const PipelineOutcome out = ReorientationPipeline(model, s).run(turn(-15), context);
  ASSERT_EQ(out.attempts.size(), 2u);
  EXPECT_EQ(out.attempts[0].seed, 3u);
  EXPECT_EQ(out.attempts[1].seed, 4u);
  EXPECT_EQ(out.status, PipelineStatus::kNotCertified);
  EXPECT_FALSE(out.record.certificate.certified);
  EXPECT_FALSE(out.record.certificate.motion.ok());
  for (const PipelineAttempt& a : out.attempts) ASSERT_TRUE(a.exact);
  EXPECT_EQ(judged_seeds, (std::vector<std::uint32_t>{3, 4}));
  // The kept plan is the chosen attempt's, and no other attempt's certificate is better.
  ASSERT_GE(out.chosen, 0);
  EXPECT_EQ(out.record.plan.seed, out.attempts[out.chosen].seed);
  for (const PipelineAttempt& a : out.attempts)
    EXPECT_FALSE(betterCertificate(a.certificate, out.record.certificate));
  EXPECT_TRUE(std::isfinite(out.best_distance));
}

TEST(ReorientationPipeline, ACancelBeforeTheRunStopsItWithNothingCertified) {
  std::atomic<bool> cancel{true};
  RunContext context;
  context.cancel = &cancel;
  const PipelineOutcome out =
      ReorientationPipeline(defaultModel(), fewTrials(PipelineMethod::kAuto))
          .run(turn(-15), context);
  EXPECT_EQ(out.status, PipelineStatus::kCancelled);
  EXPECT_FALSE(out.record.certificate.ran);
}

TEST(ReorientationPipeline, BadSettingsAndProblemsAreInputErrors) {
  const RbsfModel& model = defaultModel();
  PipelineSettings s;
  s.planner.time_limit = 0.0;
  EXPECT_THROW(ReorientationPipeline(model, s), InputError);
  s.planner.time_limit = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(ReorientationPipeline(model, s), InputError);
  s.planner.time_limit = std::numeric_limits<double>::infinity();  // no clock: accepted
  EXPECT_NO_THROW(ReorientationPipeline(model, s));
  s = {};
  s.planner.planner = static_cast<KinodynamicPlanner>(99);
  EXPECT_THROW(ReorientationPipeline(model, s), InputError);
  s = {};
  s.support_share = 0.0;
  EXPECT_THROW(ReorientationPipeline(model, s), InputError);
  // Every stage's settings are checked when the pipeline is made, before any search: a bad
  // certificate or decisive-modes setting never costs a plan.
  s = {};
  s.certificate.trials = -1;
  EXPECT_THROW(ReorientationPipeline(model, s), InputError);
  s = {};
  s.certificate.max_trials = s.certificate.batch - 1;
  EXPECT_THROW(ReorientationPipeline(model, s), InputError);
  s = {};
  s.planner.decisive_modes.cone_margin = 1.5;
  EXPECT_THROW(ReorientationPipeline(model, s), InputError);
  s = {};
  s.planner.max_control_steps = 0;
  EXPECT_THROW(ReorientationPipeline(model, s), InputError);
  Problem far = turn(0);
  far.goal.y = 3.0;  // no finger reaches it
  ReorientationPipeline pipeline(model, PipelineSettings{});
  EXPECT_THROW(pipeline.run(far), InputError);
}

TEST(BetterCertificate, CertifiedBeforeAHigherLowerBoundBeforeSmallerError) {
  Certificate a, b;
  a.ran = b.ran = true;
  a.position_tolerance = b.position_tolerance = 0.01;
  a.angle_tolerance = b.angle_tolerance = 0.035;
  a.worst.index = b.worst.index = 0;
  auto counts = [](Certificate& c, int successes, int trials) {
    c.successes = successes;
    c.trials = trials;
    c.success_rate = static_cast<double>(successes) / trials;
    c.lower_bound = clopperPearsonLower(successes, trials, 0.95);
  };
  counts(a, 10, 12);
  counts(b, 12, 12);  // more successes, but its plan breaks the motion limits
  a.certified = true;
  EXPECT_TRUE(betterCertificate(a, b));
  EXPECT_FALSE(betterCertificate(b, a));
  a.certified = false;
  EXPECT_TRUE(betterCertificate(b, a));
  // The bound, not the count nor the rate: 120 of 128 (0.94) is stronger evidence than 4 of
  // 4 (1.0), and 60 of 64 than 110 of 128.
  counts(a, 120, 128);
  counts(b, 4, 4);
  EXPECT_GT(a.lower_bound, b.lower_bound);
  EXPECT_TRUE(betterCertificate(a, b));
  EXPECT_FALSE(betterCertificate(b, a));
  counts(a, 60, 64);
  counts(b, 110, 128);
  EXPECT_TRUE(betterCertificate(a, b));
  // Equal bounds: the smaller error of the worst trial.
  counts(a, 12, 12);
  counts(b, 12, 12);
  a.worst.position_error = 0.002;
  b.worst.position_error = 0.004;
  EXPECT_TRUE(betterCertificate(a, b));
  b.worst.dropped = true;
  a.worst.position_error = 0.009;
  EXPECT_TRUE(betterCertificate(a, b));
  EXPECT_FALSE(betterCertificate(a, a));
  // No success in either (bound 0 whatever the count): the error decides.
  counts(a, 0, 64);
  counts(b, 0, 512);
  EXPECT_TRUE(betterCertificate(a, b));
  EXPECT_FALSE(betterCertificate(b, a));
  Certificate never;
  EXPECT_TRUE(betterCertificate(b, never));
}

}  // namespace
}  // namespace rbsf::planner
