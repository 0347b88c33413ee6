// Pictures of a motion: the animated SVG draws what the model says (poses, fingertips,
// contact normals), one value per sample at the samples' own times; the HTML report plots
// every quantity; nothing non-finite is ever drawn.
#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "rbsf/dynamics/core/holding.h"
#include "rbsf/dynamics/core/model_data.h"
#include "rbsf/dynamics/core/placement.h"
#include "rbsf/dynamics/core/simulator.h"
#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/tools/html_report.h"
#include "rbsf/tools/svg_animation.h"
#include "rbsf/tools/svg_time_plot.h"

namespace rbsf::tools {
namespace {

const std::string kDefaultCell = std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml";

/// The value list of the element with this id (an <animate> or <animateTransform>).
std::vector<std::string> animatedValues(const std::string& svg, const std::string& id,
                                        const char* attribute = "values") {
  const std::string key = "id=\"" + id + "\"";
  const std::size_t at = svg.find(key);
  if (at == std::string::npos) return {};
  const std::size_t end = svg.find("/>", at);
  const std::string element = svg.substr(at, end - at);
  const std::string attr = std::string(" ") + attribute + "=\"";
  const std::size_t v = element.find(attr) + attr.size();
  std::vector<std::string> out;
  std::stringstream list(element.substr(v, element.find('"', v) - v));
  for (std::string item; std::getline(list, item, ';');) out.push_back(item);
  return out;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

class PicturesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // The default part held, then the base pushed: it turns with the base and then slides.
    // Samples at irregular times (every 7 steps and at the push), as collocation knots are.
    const VecQ q0 = restingConfiguration(model, {0.1, 0.40, 0.0}, 0.0);
    ModelData data(model.numFingers());
    model.updateContacts(q0, data);
    const HoldingSolution hold = holdingTorques(model, q0, data);
    ASSERT_TRUE(hold.feasible);
    const Simulator sim(model);
    SimulatorWorkspace ws(model.numFingers());
    SimState state(q0, VecQ::Zero(q0.size()));
    StepReport report;
    for (int k = 1; k <= 900; ++k) {
      VecU tau = hold.tau;
      if (k > 200) tau[layout::kTauTheta] += 8.0;
      sim.step(state, tau, ws, &report);
      if (k % 7 == 0 || k == 201 || k == 1) {
        TrajectorySample s;
        s.t = state.t, s.q = state.q, s.v = state.v, s.tau = tau, s.phase = report.phase;
        s.f_n = VecC(model.numFingers());
        for (int i = 0; i < model.numFingers(); ++i) s.f_n[i] = report.contacts[i].f_n;
        frames.push_back(s);
      }
    }
  }
  RbsfModel model{loadCell(kDefaultCell)};
  std::vector<TrajectorySample> frames;
};

TEST_F(PicturesTest, PartTransformHasOneValuePerSampleAndEqualsThePoses) {
  SvgAnimationOptions o;
  o.id_prefix = "a";
  const std::string svg = SvgAnimation(model, frames, o).render();
  const auto at = animatedValues(svg, "a-part-translate");
  const auto phi = animatedValues(svg, "a-part-rotate");
  const auto theta = animatedValues(svg, "a-base-rotate");
  ASSERT_EQ(at.size(), frames.size());
  ASSERT_EQ(phi.size(), frames.size());
  ASSERT_EQ(theta.size(), frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k) {
    double x = 0, y = 0;
    ASSERT_EQ(std::sscanf(at[k].c_str(), "%lf %lf", &x, &y), 2) << at[k];
    EXPECT_NEAR(x / 1000, frames[k].q[layout::kX], 1e-5);  // mm, 2 decimals
    EXPECT_NEAR(y / 1000, frames[k].q[layout::kY], 1e-5);
    EXPECT_NEAR(std::stod(phi[k]) * M_PI / 180, frames[k].q[layout::kPhi], 1e-5);
    EXPECT_NEAR(std::stod(theta[k]) * M_PI / 180, frames[k].q[layout::kTheta], 1e-5);
  }
  // The static transform (what a non-animating viewer shows) is the first frame.
  EXPECT_NE(svg.find("class=\"part\" transform=\"translate(" + at[0] + ")\""), std::string::npos);
}

TEST_F(PicturesTest, KeyTimesAreTheSampleTimesOverTheDuration) {
  const SvgAnimation anim(model, frames, {});
  const std::string svg = anim.render();
  const auto times = animatedValues(svg, "a-part-translate", "keyTimes");
  ASSERT_EQ(times.size(), frames.size());
  EXPECT_EQ(times.front(), "0");
  EXPECT_EQ(times.back(), "1");
  const double T = frames.back().t - frames.front().t;
  EXPECT_DOUBLE_EQ(anim.duration(), T);
  for (std::size_t k = 0; k < frames.size(); ++k)
    EXPECT_NEAR(std::stod(times[k]), (frames[k].t - frames.front().t) / T, 1e-6);
}

TEST_F(PicturesTest, DrawnFingertipsAndNormalsAgreeWithTheModel) {
  // Rods are drawn in the base frame (r_i, l_i) rotated by theta; contact normals in the
  // world frame from the model's contact frames. Both must put the tip at p_i (eq. 2).
  const std::string svg = SvgAnimation(model, frames, {}).render();
  const auto theta = animatedValues(svg, "a-base-rotate");
  ModelData data(model.numFingers());
  for (int i = 0; i < model.numFingers(); ++i) {
    const std::string c = "a-contact" + std::to_string(i + 1);
    const auto l = animatedValues(svg, "a-finger" + std::to_string(i + 1) + "-stroke");
    const auto x1 = animatedValues(svg, c + "-normal-x1"),
               y1 = animatedValues(svg, c + "-normal-y1");
    const auto x2 = animatedValues(svg, c + "-normal-x2"),
               y2 = animatedValues(svg, c + "-normal-y2");
    ASSERT_EQ(l.size(), frames.size());
    ASSERT_EQ(x2.size(), frames.size());
    const double r = model.cell().fingers[i].r;
    for (std::size_t k = 0; k < frames.size(); k += 5) {
      const double th = std::stod(theta[k]) * M_PI / 180, li = std::stod(l[k]) / 1000;
      const Vec2 drawn(std::cos(th) * r - std::sin(th) * li, std::sin(th) * r + std::cos(th) * li);
      const Vec2 tip = model.fingertip(frames[k].q, i);
      EXPECT_NEAR((drawn - tip).norm(), 0.0, 2e-5) << "finger " << i << " frame " << k;
      EXPECT_NEAR(std::stod(x1[k]) / 1000, tip.x(), 1e-5);
      EXPECT_NEAR(std::stod(y1[k]) / 1000, tip.y(), 1e-5);
      model.updateContacts(frames[k].q, data);
      const Vec2 n((std::stod(x2[k]) - std::stod(x1[k])) / 1000,
                   (std::stod(y2[k]) - std::stod(y1[k])) / 1000);
      if (std::abs(data.contacts[i].gap) < 1e-3) {  // drawn: 4 cm along the inward normal
        EXPECT_NEAR((n - 0.04 * data.contacts[i].normal).norm(), 0.0, 3e-5);
      } else {
        EXPECT_EQ(n.norm(), 0.0);
      }
    }
  }
}

TEST_F(PicturesTest, PhaseAndTimeLabelsCoverEverySampleOnce) {
  const std::string svg = SvgAnimation(model, frames, {}).render();
  // Held (C) first; the push makes it slide later: both labels exist.
  EXPECT_NE(svg.find("phase C: every contact sticks"), std::string::npos);
  std::size_t time_labels = 0;
  std::string previous;
  for (const TrajectorySample& f : frames) {
    char label[32];
    std::snprintf(label, sizeof label, ">t = %.2f s<", f.t);
    if (label == previous) continue;
    previous = label;
    ++time_labels;
    EXPECT_EQ(count(svg, label), 1u) << label;
  }
  EXPECT_EQ(count(svg, ">t = "), time_labels);
}

TEST_F(PicturesTest, NonFiniteSampleIsRefusedAndBadFramesAreRejected) {
  auto bad = frames;
  bad[3].q[layout::kY] = NAN;
  EXPECT_THROW(SvgAnimation(model, bad, {}).render(), std::exception);
  EXPECT_THROW(SvgAnimation(model, {}, {}), std::invalid_argument);
  auto backwards = frames;
  std::swap(backwards[1], backwards[2]);
  EXPECT_THROW(SvgAnimation(model, backwards, {}), std::invalid_argument);
}

TEST_F(PicturesTest, SingleFrameIsAStillWithoutAnimation) {
  const std::string svg = SvgAnimation(model, {frames.front()}, {}).render();
  EXPECT_EQ(svg.find("<animate"), std::string::npos);
  EXPECT_NE(svg.find("class=\"part\""), std::string::npos);
}

TEST_F(PicturesTest, ReportHasTheAnimationAndFivePlotsOfEverySample) {
  SvgAnimationOptions o;
  o.title = "a <test> & more";
  const std::string html = HtmlReport(model, frames, o, {{"status", "exact"}}).render();
  EXPECT_EQ(count(html, "<svg "), 6u);  // animation + phi/theta, strokes, tau_theta, tau_i, f_n
  EXPECT_NE(html.find("a &lt;test&gt; &amp; more"), std::string::npos);
  EXPECT_EQ(html.find("<test>"), std::string::npos);
  EXPECT_EQ(html.find("http://"), html.find("http://www.w3.org/"));  // no external resource
  EXPECT_EQ(html.find("<script"), std::string::npos);
  // Series: 2 angles + m strokes + 1 + m finger forces + m normal forces, each a polyline
  // with one point per sample.
  const int m = model.numFingers();
  EXPECT_EQ(count(html, "<polyline class=\"series\""), static_cast<std::size_t>(3 + 3 * m));
  // Each over a white halo of the same points (visible on every phase's shading).
  EXPECT_EQ(count(html, "<polyline"), static_cast<std::size_t>(2 * (3 + 3 * m)));
  const std::size_t p = html.find("<polyline class=\"series\" points=\"");
  const std::string pts = html.substr(p + 33, html.find('"', p + 33) - p - 33);
  EXPECT_EQ(count(pts, ","), frames.size());
}

TEST_F(PicturesTest, PicturesCarryScaleAxesStartLegendGoalBandAndLimits) {
  SvgAnimationOptions o;
  o.goal = Pose{0.1, 0.40, -2 * M_PI + 0.3};  // goals compare modulo a turn
  o.angle_tolerance = 2.0 * M_PI / 180;
  const std::string svg = SvgAnimation(model, frames, o).render();
  for (const char* what : {"class=\"scale-bar\"", ">0.1 m<", "class=\"world-axes\"",
                           "class=\"start\"", "class=\"force-legend\"", ">goal<", ">start<"})
    EXPECT_EQ(count(svg, what), 1u) << what;
  // The force legend: a round number of newtons and each contact's peak, in newtons.
  const std::size_t legend = svg.find("class=\"force-legend\"");
  const std::string text = svg.substr(legend, svg.find("</g>", legend) - legend);
  EXPECT_NE(text.find(" N; peaks 1: "), std::string::npos) << text;
  double peak = 0.0;
  for (const TrajectorySample& f : frames) peak = std::max(peak, f.f_n[0]);
  EXPECT_NE(text.find("1: " + std::to_string(static_cast<long>(std::lround(peak))) + " N"),
            std::string::npos)
      << text << " peak " << peak;

  const std::string html = HtmlReport(model, frames, o, {}).render();
  // The angle plot's goal band sits at the turn nearest the part's last angle, in degrees.
  const std::size_t band = html.find("goal phi +- 2.0 deg");
  ASSERT_NE(band, std::string::npos);
  // Limit lines: base torque and finger forces at the cell's limits, strokes at their ends.
  const Cell& cell = model.cell();
  EXPECT_NE(html.find("limit +" + std::to_string(static_cast<long>(cell.base.torque_limit))),
            std::string::npos);
  EXPECT_NE(html.find("limit -" + std::to_string(static_cast<long>(cell.fingers[0].force_limit))),
            std::string::npos);
  EXPECT_GE(count(html, ">stroke limit<"), 2u);
}

TEST(NiceTicks, HugeOrFarFromZeroRangesStayFinite) {
  for (const auto& [lo, hi] : std::vector<std::pair<double, double>>{
           {1e300, 1.0000001e300}, {-1e308, 1e308}, {1e19, 1e19 + 4096}}) {
    const auto t = niceTicks(lo, hi, 5);
    ASSERT_GE(t.size(), 2u);
    EXPECT_LE(t.size(), 101u);
    EXPECT_LE(t.front(), lo);
    EXPECT_GE(t.back(), hi);
  }
}

TEST(NiceTicks, CoverTheRangeWithOneTwoOrFiveSteps) {
  for (const auto& [lo, hi] : std::vector<std::pair<double, double>>{
           {0.0, 2.34}, {-57.3, 8.2}, {0.05, 0.55}, {3.0, 3.0}, {-1e-3, 2e-3}}) {
    const auto t = niceTicks(lo, hi, 5);
    ASSERT_GE(t.size(), 2u);
    EXPECT_LE(t.front(), lo);
    EXPECT_GE(t.back(), hi);
    EXPECT_LE(t.size(), 12u);
    const double step = t[1] - t[0];
    const double mant = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
    EXPECT_TRUE(std::abs(mant - 1) < 1e-6 || std::abs(mant - 2) < 1e-6 || std::abs(mant - 5) < 1e-6)
        << step;
  }
}

}  // namespace
}  // namespace rbsf::tools
