// Simple turns (pivot_turn_search.h): the default cell's +5 degree turn in one pivot with
// one sliding tip (lift first, then break loose); every waypoint a valid support, the pivot
// keeping its tip on its point of the part, rigid runs keeping the part's pose on the base,
// the end exactly on the goal; runs that break away where their sliders first slip, sliders
// that keep sliding (at least 1 mm a step) and never turn back, pivots that never turn back.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/planner/support/pivot_turn_search.h"
#include "rbsf/planner/support/support_planner.h"
#include "support_path_checks.h"
#include "test_support.h"

namespace rbsf::planner {
namespace {

const RbsfModel& defaultModel() {
  static const RbsfModel model(loadCell(std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml"));
  return model;
}

SupportSearchSettings searchAt(double friction_use) {
  SupportSearchSettings s = SupportPlannerSettings::defaultSearch();
  s.support.balance.friction_use = friction_use;
  return s;
}

/// Budget-bound: the expansions end the search, never the clock (none is set).
PivotTurnSettings budgetOnly() { return test::withoutClock(PivotTurnSettings{}); }

const Pose kStart{0.1, 0.40, 0.0};
/// A +5 degree turn: finger 1 lifted, the pivot on finger 3 with finger 2 sliding, then the
/// base turns at rest.
const Pose kTurn{0.1, 0.40, 5.0 * M_PI / 180};
/// A -20 degree turn: two pivots, finger 2 sliding one way, then the other.
const Pose kTwoPivots{0.1, 0.40, -20.0 * M_PI / 180};
/// The friction use of the turns below.
constexpr double kUse = 0.6;

/// Part-frame point xi in the world at configuration q.
Vec2 partPoint(const RbsfModel& model, const VecQ& q, double xi) {
  const Vec2 c = model.shape().point(xi);
  const double p = q[layout::kPhi];
  return Vec2(q[layout::kX] + std::cos(p) * c.x() - std::sin(p) * c.y(),
              q[layout::kY] + std::sin(p) * c.x() + std::cos(p) * c.y());
}

/// The +5 degree turn, searched once for the tests below.
const SupportPath& oneTurn() {
  static const SupportPath path = [] {
    SupportSearch search(defaultModel(), searchAt(kUse));
    return PivotTurnSearch(search, budgetOnly()).search(kStart, 0.0, kTurn);
  }();
  return path;
}

TEST(PivotTurnSearch, TheDefaultCellsPlus5DegreeTurnIsOnePivotWithOneSliderAndARigidTurn) {
  const RbsfModel& model = defaultModel();
  SupportSearch search(model, searchAt(kUse));
  PivotTurnSearch simple(search, budgetOnly());
  const SupportPath path = simple.search(kStart, 0.0, kTurn);
  ASSERT_TRUE(path.found) << path.message;
  EXPECT_LE(path.expansions, simple.settings().max_expansions);
  EXPECT_LE(phaseRuns(path.steps), 3);
  EXPECT_EQ(pivotRuns(path.steps), 1);
  SupportGeometry& geometry = search.geometry();
  const PivotTurnSettings& s = simple.settings();
  int pivot_runs = 0, pivot_finger = -1;
  for (std::size_t k = 0; k < path.steps.size(); ++k) {
    const SupportStep& st = path.steps[k];
    EXPECT_TRUE(geometry.check(st.pose, st.set).valid) << "step " << k;
    if (st.set.pivot() >= 0) {
      pivot_finger = st.set.pivot();
      EXPECT_EQ(st.set.count(), 2) << "one slider, every other finger lifted: step " << k;
    }
    if (k == 0) {
      pivot_runs += st.set.pivot() >= 0 ? 1 : 0;
      continue;
    }
    const SupportStep& prev = path.steps[k - 1];
    if (st.set != prev.set) {  // at rest, in place
      EXPECT_NEAR(st.pose.psi, prev.pose.psi, 1e-12);
      EXPECT_NEAR(st.pose.X, prev.pose.X, 1e-12);
      EXPECT_NEAR(st.pose.theta, prev.pose.theta, 1e-12);
      pivot_runs += st.set.pivot() >= 0 ? 1 : 0;  // a new pivot: its set begins here
      continue;
    }
    EXPECT_LE(std::abs(st.pose.psi - prev.pose.psi), s.angle_step + 1e-9) << "step " << k;
    EXPECT_LE(std::abs(st.pose.theta - prev.pose.theta), s.angle_step + 1e-9) << "step " << k;
    if (st.set.pivot() >= 0) {
      EXPECT_EQ(st.anchor.xi, prev.anchor.xi);
      EXPECT_LE(std::abs(st.anchor.stroke - prev.anchor.stroke), s.stroke_step + 1e-9);
      EXPECT_LT(
          (model.fingertip(st.q, st.set.pivot()) - partPoint(model, st.q, st.anchor.xi)).norm(),
          1e-9);
    } else {  // rigid with the base
      EXPECT_NEAR(st.pose.psi, prev.pose.psi, 1e-12);
      EXPECT_NEAR(st.pose.X, prev.pose.X, 1e-12);
      EXPECT_NEAR(st.pose.Y, prev.pose.Y, 1e-12);
    }
  }
  EXPECT_EQ(pivot_runs, pivotRuns(path.steps));
  EXPECT_GE(pivot_finger, 0);
  const Pose end = path.steps.back().pose.world();
  EXPECT_NEAR(end.x, kTurn.x, 1e-9);
  EXPECT_NEAR(end.y, kTurn.y, 1e-9);
  EXPECT_NEAR(std::remainder(end.phi - kTurn.phi, 2 * M_PI), 0.0, 1e-9);

  // Deterministic: the same search again gives the same path.
  const SupportPath& second = oneTurn();
  ASSERT_EQ(second.steps.size(), path.steps.size());
  EXPECT_EQ(second.expansions, path.expansions);
  for (std::size_t k = 0; k < path.steps.size(); ++k)
    EXPECT_EQ(second.steps[k].q, path.steps[k].q) << "step " << k;
}

TEST(PivotTurnSearch, RunsBreakAwayWhereTheirSlidersFirstSlipAndNoSliderOrPivotTurnsBack) {
  const RbsfModel& model = defaultModel();
  SupportGeometry geometry(model, searchAt(kUse).support);
  for (const Pose& goal : {kTurn, kTwoPivots}) {
    SupportPath path = oneTurn();
    if (goal.phi != kTurn.phi) {
      SupportSearch search(model, searchAt(kUse));
      path = PivotTurnSearch(search, budgetOnly()).search(kStart, 0.0, goal);
    }
    ASSERT_TRUE(path.found) << path.message;
    EXPECT_TRUE(runStartsThatStayStuck(geometry, path).empty()) << goal.phi;
    // Each run turns the part one way on the base.
    for (std::size_t k = 1; k + 1 < path.steps.size(); ++k) {
      const SupportStep &a = path.steps[k - 1], &b = path.steps[k], &c = path.steps[k + 1];
      if (a.set != b.set || b.set != c.set || b.set.pivot() < 0) continue;
      EXPECT_GE((b.pose.psi - a.pose.psi) * (c.pose.psi - b.pose.psi), -1e-12) << "step " << k;
    }
    for (std::size_t k = 1; k + 1 < path.steps.size(); ++k) {
      const SupportStep &a = path.steps[k - 1], &b = path.steps[k], &c = path.steps[k + 1];
      if (a.set != b.set || b.set != c.set) continue;
      const VecC before = geometry.slipDirections(a.q, b.q);
      const VecC after = geometry.slipDirections(b.q, c.q);
      for (int i = 0; i < model.numFingers(); ++i) {
        if (!b.set.touches(i) || b.set.sticks(i)) continue;
        if (std::abs(before[i]) > 1e-4 && std::abs(after[i]) > 1e-4) {
          EXPECT_GT(before[i] * after[i], 0.0) << "finger " << i << " turns back at step " << k;
        }
        if (b.set.pivot() >= 0 && !b.rest && k + 2 < path.steps.size() &&
            path.steps[k + 2].set == b.set) {  // a lattice step (the finish may be shorter)
          EXPECT_GE(std::abs(after[i]), 1e-3) << "finger " << i << " at step " << k;
        }
      }
    }
  }
}

TEST(PivotTurnSearch, AGoalNoPivotCanReachIsRefusedWithoutASearch) {
  SupportSearch search(defaultModel(), searchAt(kUse));
  PivotTurnSearch simple(search, budgetOnly());
  // Far above the jig: every finger's stroke would have to pass its limit.
  const SupportPath path = simple.search(kStart, 0.0, Pose{0.1, 1.5, 90.0 * M_PI / 180});
  EXPECT_FALSE(path.found);
  EXPECT_EQ(path.expansions, 0);
  EXPECT_NE(path.message.find("no pivot finger"), std::string::npos) << path.message;
}

}  // namespace
}  // namespace rbsf::planner
