// The certificate (plan/certificate.h): its draws stay within the cell's uncertainty,
// it is the same bits for a seed (whatever the threads) and differs across seeds, it
// travels in plan files, and it tells the laws apart where the physics does: a part sliding
// on two frictionless tips is held only with part feedback. The sequential rule on given
// outcome sequences (runTrials) and on a real plan; the settings' rules; the reports.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "law_support.h"
#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/plan/certificate.h"
#include "rbsf/plan/confidence.h"
#include "rbsf/plan/plan_file.h"

namespace rbsf::plan {
namespace {

const RbsfModel& twoTipsModel() { return test::sharedTwoTipsModel(); }
const Plan& twoTipsPlan() { return test::sharedTwoTipsPlan(); }

TEST(Certificate, DrawsStayWithinTheCellsUncertainty) {
  const Cell cell = test::makeCell(test::ShapeKind::kEllipse, 3);
  const RbsfModel model(cell);
  const Plan plan = test::holdPlan(model, restingConfiguration(model, Pose{0.1, 0.4, 0.0}, 0.0), 1);
  const Uncertainty& u = cell.uncertainty;
  for (int i = 0; i < 50; ++i) {
    const TrialDraw d = drawTrial(cell, plan, 7, i);
    EXPECT_LE(std::abs(d.cell.object.mass / cell.object.mass - 1.0), u.mass + 1e-12);
    EXPECT_LE(std::abs(d.cell.object.inertia / cell.object.inertia - 1.0), u.inertia + 1e-12);
    EXPECT_LE(d.com_offset.cwiseAbs().maxCoeff(), u.com + 1e-12);
    EXPECT_LE(std::abs(d.cell.friction.mu_static / cell.friction.mu_static - 1.0),
              u.static_friction + 1e-12);
    EXPECT_GE(d.cell.friction.mu_kinetic, u.kinetic_friction_min);
    EXPECT_LE(d.cell.friction.mu_kinetic,
              std::min(u.kinetic_friction_max, d.cell.friction.mu_static));
    EXPECT_LE((d.actuator_gain.array() - 1.0).abs().maxCoeff(), u.actuator_gain + 1e-12);
    // The drawn start: the part's frame within +-1 mm, +-0.5 deg, on the fingers.
    const Vec2 frame = Vec2(d.q0[0], d.q0[1]) - rotate(d.q0[2], d.com_offset);
    EXPECT_LE(std::abs(frame.x() - plan.q0[0]), u.initial_position + 1e-9);
    EXPECT_LE(std::abs(frame.y() - plan.q0[1]), u.initial_position + 1e-9);
    EXPECT_LE(std::abs(d.q0[2] - plan.q0[2]), u.initial_angle + 1e-9);
    const RbsfModel plant(d.cell);
    ModelData data(3);
    plant.updateContacts(d.q0, data);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(data.contacts[k].gap, 0.0, 1e-9);
  }
  // Draws differ by index and seed, and repeat.
  EXPECT_NE(drawTrial(cell, plan, 7, 0).cell.object.mass,
            drawTrial(cell, plan, 7, 1).cell.object.mass);
  EXPECT_NE(drawTrial(cell, plan, 7, 0).cell.object.mass,
            drawTrial(cell, plan, 8, 0).cell.object.mass);
  EXPECT_EQ(drawTrial(cell, plan, 7, 3).q0, drawTrial(cell, plan, 7, 3).q0);
  // No uncertainty: the cell itself and the plan's start.
  Cell exact = cell;
  exact.uncertainty = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  const TrialDraw d = drawTrial(exact, plan, 1, 0);
  EXPECT_EQ(d.cell.object.mass, cell.object.mass);
  EXPECT_LT((d.q0 - plan.q0).cwiseAbs().maxCoeff(), 1e-12);
}

bool same(const TrialOutcome& a, const TrialOutcome& b) {
  return a.success == b.success && a.position_error == b.position_error &&
         a.angle_error == b.angle_error && a.speed == b.speed && a.dropped == b.dropped &&
         a.max_deviation == b.max_deviation && a.phases == b.phases && a.min_f_n == b.min_f_n;
}

TEST(Certificate, SameSeedSameBitsWhateverTheThreadsOtherSeedOthers) {
  CertificateSettings s;
  s.trials = 6;
  s.seed = 11;
  s.threads = 1;
  std::vector<TrialOutcome> one, two, other;
  const Certificate a = certify(twoTipsModel(), twoTipsPlan(), s, &one);
  s.threads = 2;
  const Certificate b = certify(twoTipsModel(), twoTipsPlan(), s, &two);
  ASSERT_EQ(one.size(), 6u);
  ASSERT_EQ(two.size(), 6u);
  for (int i = 0; i < 6; ++i) EXPECT_TRUE(same(one[i], two[i])) << "trial " << i;
  EXPECT_EQ(certificateJsonText(a), certificateJsonText(b));
  s.seed = 12;
  certify(twoTipsModel(), twoTipsPlan(), s, &other);
  int differ = 0;
  for (int i = 0; i < 6; ++i) differ += !same(one[i], other[i]);
  EXPECT_GT(differ, 3);
}

TEST(Certificate, APartSlidingOnTwoFrictionlessTipsIsHeldOnlyWithPartFeedback) {
  // The plan slides the part about a centimetre on two frictionless tips: a balance that
  // its open-loop inputs keep only exactly (an inverted pendulum, e-folding ~0.1 s). Same
  // draws for every law: the part-feedback law brings every trial to the goal; a cell
  // that sees only its joints, or the inputs alone, drops the part in every trial.
  const Plan& plan = twoTipsPlan();
  double slide = 0.0;
  for (const PlanSample& s : plan.samples) slide = std::max(slide, std::abs(s.q[0] - plan.q0[0]));
  ASSERT_GT(slide, 0.005) << "the plan must slide the part";
  CertificateSettings s;
  s.trials = 8;
  std::vector<TrialOutcome> part;
  const Certificate fed = certify(twoTipsModel(), plan, s, &part);
  EXPECT_EQ(fed.law, TrialLaw::kPartFeedback);
  for (const TrialOutcome& o : part) {
    EXPECT_FALSE(o.dropped) << "trial " << o.index << ": " << o.failure;
    EXPECT_LE(o.position_error, 0.01) << "trial " << o.index;
    EXPECT_LE(o.angle_error, 2.0 * M_PI / 180) << "trial " << o.index;
  }
  Cell blind = twoTipsModel().cell();
  blind.sensing.part_pose.present = false;
  const RbsfModel joints_only(blind);
  std::vector<TrialOutcome> joint, open;
  const Certificate jc = certify(joints_only, plan, s, &joint);
  EXPECT_EQ(jc.law, TrialLaw::kJointFeedback);
  for (const TrialOutcome& o : joint) EXPECT_TRUE(o.dropped) << "trial " << o.index;
  s.open_loop = true;
  const Certificate oc = certify(twoTipsModel(), plan, s, &open);
  EXPECT_EQ(oc.law, TrialLaw::kOpenLoop);
  for (const TrialOutcome& o : open) EXPECT_TRUE(o.dropped) << "trial " << o.index;
  EXPECT_EQ(jc.successes, 0);
  EXPECT_GT(fed.successes, jc.successes);
  // The worst trial of a law that drops the part says when and where it left the path.
  EXPECT_TRUE(jc.worst.dropped);
  EXPECT_GE(jc.worst.departure_time, 0.0);
  EXPECT_EQ(jc.worst.departure_phase, "U");
}

TEST(Certificate, TravelsInPlanFilesAndIsRefusedWhenMalformed) {
  CertificateSettings s;
  s.trials = 3;
  PlanRecord plan{twoTipsPlan(), {}, {}};
  plan.certificate = certify(twoTipsModel(), plan.plan, s);
  const std::string path = ::testing::TempDir() + std::to_string(getpid()) + "_cert_plan.json";
  writePlanJson(plan, path);
  const PlanRecord back = readPlanJson(path);
  ASSERT_TRUE(back.certificate.ran);
  EXPECT_EQ(certificateJsonText(back.certificate), certificateJsonText(plan.certificate));
  EXPECT_EQ(back.certificate.sensing.part_pose.rate, plan.certificate.sensing.part_pose.rate);
  std::string text = planJsonText(plan);
  const std::string key = "\"successes\": " + std::to_string(plan.certificate.successes);
  ASSERT_NE(text.find(key), std::string::npos);
  text.replace(text.find(key), key.size(), "\"successes\": \"many\"");
  try {
    parsePlanJson(text, "bad.json");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("certificate.successes"), std::string::npos) << e.what();
  }
}

TEST(Certificate, BadSettingsAndAPlanForAnotherCellAreRefused) {
  CertificateSettings s;
  s.trials = -1;
  EXPECT_THROW(certify(twoTipsModel(), twoTipsPlan(), s), InputError);
  s = {};
  s.required_rate = 1.5;
  EXPECT_THROW(certify(twoTipsModel(), twoTipsPlan(), s), InputError);
  s = {};
  s.trial.rest_window = 0.0;
  EXPECT_THROW(certify(twoTipsModel(), twoTipsPlan(), s), InputError);
  const RbsfModel three(test::makeCell(test::ShapeKind::kEllipse, 3));
  EXPECT_THROW(certify(three, twoTipsPlan(), CertificateSettings{}), InputError);
}

// ---- the sequential rule on given outcomes ----

/// A trial that fails where `fails` says, after some busy work that differs by index (so
/// that with several threads the trials complete out of order).
std::function<TrialOutcome(int)> fake(std::function<bool(int)> fails) {
  return [fails = std::move(fails)](int i) {
    volatile double sink = 0.0;
    for (int k = 0; k < (i * 7919) % 20000; ++k) sink = sink + std::sqrt(static_cast<double>(k));
    TrialOutcome o;
    o.success = !fails(i);
    return o;
  };
}

struct Counts {
  int trials = 0, successes = 0;
  bool operator==(const Counts& o) const { return trials == o.trials && successes == o.successes; }
};

Counts runFake(const CertificateSettings& s, const std::function<bool(int)>& fails,
               bool plan_ok = true) {
  std::vector<TrialOutcome> outcomes;
  EXPECT_TRUE(runTrials(s, plan_ok, fake(fails), outcomes));
  Counts r;
  r.trials = static_cast<int>(outcomes.size());
  for (int i = 0; i < r.trials; ++i) {
    EXPECT_EQ(outcomes[i].index, i);
    EXPECT_EQ(outcomes[i].success, !fails(i)) << "trial " << i;
    r.successes += outcomes[i].success;
  }
  return r;
}

double bound(const Counts& r) { return clopperPearsonLower(r.successes, r.trials, 0.95); }

TEST(SequentialTrials, AllSuccessesCertifyAtTheFirstBatch) {
  const Counts r = runFake(CertificateSettings{}, [](int) { return false; });
  EXPECT_EQ(r.trials, 64);
  EXPECT_EQ(r.successes, 64);
  EXPECT_GE(bound(r), 0.95);
}

TEST(SequentialTrials, OneEarlyFailureTakesASecondBatch) {
  // 63 of 64 bound the rate at 0.928: not yet; 127 of 128 at 0.963.
  const Counts r = runFake(CertificateSettings{}, [](int i) { return i == 5; });
  EXPECT_EQ(r.trials, 128);
  EXPECT_EQ(r.successes, 127);
  EXPECT_GE(bound(r), 0.95);
}

TEST(SequentialTrials, ANinetyPercentPlanIsNotCertifiedAndFutilityStopsItEarly) {
  // One failure in ten. 512 trials allow 17 failures for a bound of 0.95; after 192 there
  // are 19, so even 320 more successes could not certify: it stops there, not at the cap.
  const auto fails = [](int i) { return i % 10 == 3; };
  const CertificateSettings s;
  const Counts r = runFake(s, fails);
  EXPECT_EQ(r.trials, 192);
  EXPECT_EQ(r.successes, 173);
  EXPECT_LT(clopperPearsonLower(r.successes + s.max_trials - r.trials, s.max_trials, 0.95), 0.95);
  // The look before could still have been certified by the remaining trials.
  EXPECT_GE(clopperPearsonLower(115 + s.max_trials - 128, s.max_trials, 0.95), 0.95);
}

TEST(SequentialTrials, ABorderlinePlanRunsToTheCap) {
  // One failure in 28 (96.4 %): never futile, never certain enough; at 512, 493 successes
  // bound the rate at 0.946. One in 31: certified only at the cap (495 of 512, 0.9506).
  const Counts r = runFake(CertificateSettings{}, [](int i) { return i % 28 == 0; });
  EXPECT_EQ(r.trials, 512);
  EXPECT_EQ(r.successes, 493);
  EXPECT_LT(bound(r), 0.95);
  const Counts c = runFake(CertificateSettings{}, [](int i) { return i % 31 == 0; });
  EXPECT_EQ(c.trials, 512);
  EXPECT_GE(bound(c), 0.95);
}

TEST(SequentialTrials, APlanThatFailsWhateverTheTrialsStopsAtTheFirstLook) {
  EXPECT_EQ(runFake(
                CertificateSettings{}, [](int) { return false; }, false)
                .trials,
            64);
  CertificateSettings fixed;
  fixed.trials = 100;  // a fixed count runs whole
  EXPECT_EQ(runFake(
                fixed, [](int) { return false; }, false)
                .trials,
            100);
}

TEST(SequentialTrials, AFixedCountRunsExactlyThatMany) {
  CertificateSettings s;
  s.trials = 32;
  const Counts all = runFake(s, [](int) { return false; });
  EXPECT_EQ(all.trials, 32);
  EXPECT_LT(bound(all), 0.95);  // 32 of 32 no longer certify: 0.911
  s.trials = 300;
  EXPECT_EQ(runFake(s, [](int i) { return i % 10 == 3; }).trials, 300);  // no futility stop
}

TEST(SequentialTrials, TheBatchTheCapAndTheConfidenceAreTheSettings) {
  CertificateSettings s;
  s.batch = 10;
  s.max_trials = 25;  // looks at 10, 20 and 25
  s.required_rate = 0.85;
  // 10 of 10 bound the rate at 0.741, 20 of 20 at 0.861.
  EXPECT_EQ(runFake(s, [](int) { return false; }).trials, 20);
  // 9 of 10: even 15 more successes give 24 of 25, bound 0.824: futile at the first look.
  EXPECT_EQ(runFake(s, [](int i) { return i == 0; }).trials, 10);
  // At 0.8 the same failure goes on (19 of 20: 0.784) and certifies at the cap (0.824).
  s.required_rate = 0.8;
  const Counts cap = runFake(s, [](int i) { return i == 0; });
  EXPECT_EQ(cap.trials, 25);
  EXPECT_GE(bound(cap), 0.8);
  // Confidence 0.5 (the median): 10 of 10 bound the rate at 0.933.
  s.required_rate = 0.85;
  s.confidence = 0.5;
  EXPECT_EQ(runFake(s, [](int) { return false; }).trials, 10);
}

TEST(SequentialTrials, TheCountIsTheSameWhateverTheThreads) {
  const std::vector<std::function<bool(int)>> sequences = {
      [](int) { return false; }, [](int i) { return i == 5; }, [](int i) { return i % 10 == 3; },
      [](int i) { return i % 28 == 0; }, [](int i) { return (i * 2654435761u) % 100 < 4; }};
  for (std::size_t k = 0; k < sequences.size(); ++k) {
    CertificateSettings s;
    s.threads = 1;
    const Counts one = runFake(s, sequences[k]);
    for (int threads : {2, 3, 8}) {
      s.threads = threads;
      EXPECT_TRUE(runFake(s, sequences[k]) == one) << "sequence " << k << ", " << threads;
    }
    s.batch = 7;  // looks that do not divide the cap
    s.threads = 1;
    const Counts odd = runFake(s, sequences[k]);
    s.threads = 3;
    EXPECT_TRUE(runFake(s, sequences[k]) == odd) << "sequence " << k << ", batches of 7";
  }
}

TEST(SequentialTrials, ACancelOrAFailingTrialEndsTheRun) {
  std::vector<TrialOutcome> outcomes;
  const std::atomic<bool> cancel{true};
  EXPECT_FALSE(
      runTrials(CertificateSettings{}, true, fake([](int) { return false; }), outcomes, &cancel));
  EXPECT_TRUE(outcomes.empty());
  // One early failure takes the run into its second batch, where trial 70 throws.
  auto throws = [](int i) {
    if (i == 70) throw std::runtime_error("trial 70");
    TrialOutcome o;
    o.success = i != 5;
    return o;
  };
  EXPECT_THROW(runTrials(CertificateSettings{}, true, throws, outcomes), std::runtime_error);
}

// ---- the rule on a real plan ----

/// A plan that holds the part at rest for 0.5 s on the test cell (one finger lifted); with
/// `exact`, a cell without uncertainty (the trials differ by their sensor noise alone), where
/// every trial succeeds.
const Plan& holdPlan(const RbsfModel& model) {
  static const Plan plan =
      test::holdPlan(model, restingConfiguration(model, Pose{0.1, 0.4, 0.0}, 0.0), 0.5);
  return plan;
}
const RbsfModel& holdModel(bool exact) {
  static const RbsfModel uncertain(test::makeCell(test::ShapeKind::kEllipse, 3));
  static const RbsfModel certain = [] {
    Cell cell = test::makeCell(test::ShapeKind::kEllipse, 3);
    cell.uncertainty = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    return RbsfModel(cell);
  }();
  return exact ? certain : uncertain;
}

TEST(Certificate, SixtyFourOfSixtyFourCertifySequentially) {
  // The default certificate stops after its first batch.
  const RbsfModel& model = holdModel(true);
  CertificateSettings s;
  std::vector<TrialOutcome> outcomes;
  const Certificate c = certify(model, holdPlan(model), s, &outcomes);
  ASSERT_EQ(c.successes, c.trials) << verdictText(c);
  EXPECT_TRUE(c.certified) << verdictText(c);
  EXPECT_EQ(c.trials, 64);
  EXPECT_EQ(outcomes.size(), 64u);
  EXPECT_NEAR(c.lower_bound, 0.9543, 5e-5);
  EXPECT_EQ(c.confidence, 0.95);
  EXPECT_TRUE(c.sequential);
  EXPECT_EQ(c.batch, 64);
  EXPECT_EQ(c.max_trials, 512);
  EXPECT_EQ(verdictText(c),
            "certified: 64/64 trials succeeded (100 %; 95 % lower confidence bound 0.954 >= "
            "0.95 required)");
  EXPECT_NE(
      certificateReportText(c).find("  sequential, batches of 64 up to 512 trials: "
                                    "stopped after 64, the bound reached the required rate\n"),
      std::string::npos)
      << certificateReportText(c);
  // The first 32 of those trials as a fixed count: every one succeeds, and that is not enough.
  s.trials = 32;
  const Certificate few = certify(model, holdPlan(model), s);
  EXPECT_EQ(few.successes, 32);
  EXPECT_FALSE(few.certified);
  EXPECT_FALSE(few.sequential);
  EXPECT_NE(verdictText(few).find("32/32 trials succeeded (100 %; 95 % lower confidence bound "
                                  "0.910 < 0.95 required)"),
            std::string::npos)
      << verdictText(few);
  EXPECT_EQ(certificateReportText(few).find("sequential"), std::string::npos);
}

TEST(Certificate, SequentialIsTheSameBitsWhateverTheThreads) {
  // Batches of 4 on the cell with its uncertainty (some trials fail): wherever it stops, it
  // stops there with any number of threads, on the same outcomes.
  const RbsfModel& model = holdModel(false);
  CertificateSettings s;
  s.batch = 4;
  s.max_trials = 16;
  s.required_rate = 0.5;
  s.seed = 5;
  s.threads = 1;
  std::vector<TrialOutcome> one, two;
  const Certificate a = certify(model, holdPlan(model), s, &one);
  s.threads = 2;
  const Certificate b = certify(model, holdPlan(model), s, &two);
  EXPECT_EQ(a.trials % 4, 0) << verdictText(a);
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t i = 0; i < one.size(); ++i) EXPECT_TRUE(same(one[i], two[i])) << "trial " << i;
  EXPECT_EQ(certificateJsonText(a), certificateJsonText(b));
  // Without uncertainty: 4 of 4 (bound 0.47) do not reach 0.6, 8 of 8 (0.69) do.
  s.required_rate = 0.6;
  const Certificate c = certify(holdModel(true), holdPlan(holdModel(true)), s);
  EXPECT_EQ(c.trials, 8) << verdictText(c);
  EXPECT_TRUE(c.certified) << verdictText(c);
}

// ---- settings and reports ----

/// The message of the InputError that checkSettings throws, or "" when it accepts.
std::string refusal(const CertificateSettings& s) {
  try {
    checkSettings(s);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(CertificateSettings, EachRuleNamesItsSetting) {
  EXPECT_EQ(refusal(CertificateSettings{}), "");
  struct Case {
    std::function<void(CertificateSettings&)> set;
    const char* name;
  };
  const Case cases[] = {
      {[](CertificateSettings& s) { s.trials = -1; }, "trials"},
      {[](CertificateSettings& s) { s.trials = 100001; }, "trials"},
      {[](CertificateSettings& s) { s.batch = 0; }, "batch"},
      {[](CertificateSettings& s) { s.batch = 100001; }, "batch"},
      {[](CertificateSettings& s) { s.max_trials = 63; }, "max_trials"},
      {[](CertificateSettings& s) { s.max_trials = 100001; }, "max_trials"},
      {[](CertificateSettings& s) { s.confidence = 0.4; }, "confidence"},
      {[](CertificateSettings& s) { s.confidence = 1.0; }, "confidence"},
      {[](CertificateSettings& s) { s.confidence = std::nan(""); }, "confidence"},
      {[](CertificateSettings& s) { s.required_rate = 1.5; }, "required_rate"},
      {[](CertificateSettings& s) { s.required_rate = -0.1; }, "required_rate"},
      {[](CertificateSettings& s) { s.threads = -1; }, "threads"},
  };
  for (const Case& c : cases) {
    CertificateSettings s;
    c.set(s);
    const std::string message = refusal(s);
    EXPECT_NE(message.find(std::string("certificate: ") + c.name), std::string::npos)
        << c.name << ": " << message;
  }
  // Accepted at the edges: a fixed count of 1 or 100000, a batch of 1, the cap at the batch.
  for (auto set : std::vector<std::function<void(CertificateSettings&)>>{
           [](CertificateSettings& s) { s.trials = 1; },
           [](CertificateSettings& s) { s.trials = 100000; },
           [](CertificateSettings& s) { s.batch = 1; },
           [](CertificateSettings& s) { s.max_trials = s.batch; },
           [](CertificateSettings& s) { s.confidence = 0.5; },
           [](CertificateSettings& s) { s.required_rate = 1.0; }}) {
    CertificateSettings s;
    set(s);
    EXPECT_EQ(refusal(s), "");
  }
}

Certificate counted(int successes, int trials, double required = 0.95) {
  Certificate c;
  c.ran = true;
  c.trials = trials;
  c.successes = successes;
  c.success_rate = static_cast<double>(successes) / trials;
  c.confidence = 0.95;
  c.lower_bound = clopperPearsonLower(successes, trials, 0.95);
  c.required_rate = required;
  return c;
}

TEST(CertificateReport, TheRatesLineStatesTheBoundAndItsComparison) {
  EXPECT_EQ(ratesText(counted(126, 128)),
            "126/128 trials succeeded (98 %; 95 % lower confidence bound 0.951 >= 0.95 required)");
  EXPECT_EQ(ratesText(counted(60, 64)),
            "60/64 trials succeeded (93 %; 95 % lower confidence bound 0.862 < 0.95 required)");
  // Rounded down: 511 of 512 is not shown as 100 %, a bound of 0.9628 not as 0.963.
  EXPECT_EQ(ratesText(counted(511, 512)).substr(0, 28), "511/512 trials succeeded (99");
  // More digits where three would contradict the comparison: 0.954270 >= 0.9542.
  EXPECT_EQ(ratesText(counted(64, 64, 0.9542)),
            "64/64 trials succeeded (100 %; 95 % lower confidence bound 0.954270 >= 0.9542 "
            "required)");
}

TEST(CertificateReport, HowASequentialCertificateStopped) {
  Certificate c = counted(173, 192);
  c.sequential = true;
  c.batch = 64;
  c.max_trials = 512;
  c.motion.measured = true;  // within limits and at rest (the defaults)
  EXPECT_EQ(stopText(c),
            "sequential, batches of 64 up to 512 trials: stopped after 192, even 320 more "
            "successes would leave the bound below the required rate");
  c = counted(493, 512);
  c.sequential = true;
  c.batch = 64;
  c.max_trials = 512;
  c.motion.measured = true;
  EXPECT_EQ(stopText(c), "sequential, batches of 64 up to 512 trials: stopped after 512, the cap");
  c.motion.measured = false;  // a plan without samples fails its motion check
  EXPECT_NE(stopText(c).find("the plan fails its motion limits or holding"), std::string::npos);
  EXPECT_EQ(stopText(counted(64, 64)), "");
}

TEST(Certificate, TheBoundAndTheTrialRuleTravelInPlanFilesAndAreChecked) {
  CertificateSettings s;
  s.trials = 3;
  PlanRecord plan{twoTipsPlan(), {}, {}};
  plan.certificate = certify(twoTipsModel(), plan.plan, s);
  plan.certificate.sequential = true;  // as a sequential certificate would say
  plan.certificate.batch = 2;
  plan.certificate.max_trials = 8;
  const std::string text = planJsonText(plan);
  const PlanRecord back = parsePlanJson(text, "plan.json");
  EXPECT_EQ(back.certificate.lower_bound, plan.certificate.lower_bound);
  EXPECT_EQ(back.certificate.confidence, 0.95);
  EXPECT_TRUE(back.certificate.sequential);
  EXPECT_EQ(back.certificate.batch, 2);
  EXPECT_EQ(back.certificate.max_trials, 8);
  EXPECT_EQ(certificateJsonText(back.certificate), certificateJsonText(plan.certificate));
  plan.certificate.sequential = false;
  EXPECT_FALSE(parsePlanJson(planJsonText(plan), "plan.json").certificate.sequential);
  // Each edit is refused with the key named.
  auto refused = [&](const std::string& from, const std::string& to, const std::string& key) {
    std::string edited = text;
    const auto at = edited.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    edited.replace(at, from.size(), to);
    try {
      parsePlanJson(edited, "bad.json");
      ADD_FAILURE() << "accepted " << to;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("certificate." + key), std::string::npos) << e.what();
    }
  };
  refused("\"lower_bound\"", "\"lower_boundary\"", "lower_bound is missing");
  refused("\"lower_bound\": ", "\"lower_bound\": 0.5, \"x\": ", "lower_bound must be the 95 %");
  refused("\"confidence\": 0.95", "\"confidence\": 1.0", "confidence must be in");
  refused("\"max_trials\": 8", "\"max_trials\": 1", "sequential.max_trials");
  refused("\"batch\": 2", "\"batch\": 0", "sequential.batch");
  refused("\"sequential\": {", "\"sequential\": true, \"y\": {", "sequential must be");
}

}  // namespace
}  // namespace rbsf::plan
