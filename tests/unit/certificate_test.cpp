// The certificate (plan/certificate.h): its draws stay within the cell's uncertainty,
// it is the same bits for a seed (whatever the threads) and differs across seeds, it
// travels in plan files, and it tells the laws apart where the physics does: a part sliding
// on two frictionless tips is held only with part feedback.
#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <string>

#include "law_support.h"
#include "rbsf/dynamics/errors.h"
#include "rbsf/dynamics/state_layout.h"
#include "rbsf/plan/certificate.h"

namespace rbsf::plan {
namespace {

const RbsfModel& twoTipsModel() {
  static const RbsfModel model(test::twoTipsCell());
  return model;
}

const Plan& twoTipsPlan() {
  static const Plan plan = test::twoTipsPlan(twoTipsModel());
  return plan;
}

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
  EXPECT_EQ(fed.law, "part feedback");
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
  EXPECT_EQ(jc.law, "joint feedback");
  for (const TrialOutcome& o : joint) EXPECT_TRUE(o.dropped) << "trial " << o.index;
  s.open_loop = true;
  const Certificate oc = certify(twoTipsModel(), plan, s, &open);
  EXPECT_EQ(oc.law, "open loop");
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
  Plan plan = twoTipsPlan();
  plan.certificate = certify(twoTipsModel(), plan, s);
  const std::string path = ::testing::TempDir() + std::to_string(getpid()) + "_cert_plan.json";
  writePlanJson(plan, path);
  const Plan back = readPlanJson(path);
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
  s.trials = 0;
  EXPECT_THROW(certify(twoTipsModel(), twoTipsPlan(), s), InputError);
  s = {};
  s.required_rate = 1.5;
  EXPECT_THROW(certify(twoTipsModel(), twoTipsPlan(), s), InputError);
  s = {};
  s.trial.rest_speed = 0.0;
  EXPECT_THROW(certify(twoTipsModel(), twoTipsPlan(), s), InputError);
  const RbsfModel three(test::makeCell(test::ShapeKind::kEllipse, 3));
  EXPECT_THROW(certify(three, twoTipsPlan(), CertificateSettings{}), InputError);
}

}  // namespace
}  // namespace rbsf::plan
