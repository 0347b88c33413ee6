// plan-reorientation's and rbsf-simulate's pictures (--svg, --report), runs stopped by
// SIGINT, reproducible files, and failing runs that leave no file.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli_support.h"

namespace {

using namespace rbsf::cli_test;

const std::string kPlanExe = RBSF_PLAN_EXE;
const std::string kSimulateExe = RBSF_SIMULATE_EXE;
const std::string kCellDir = std::string(RBSF_SOURCE_DIR) + "/cells/";
const std::string kSmall = kPlanExe + " --cell " + kCellDir +
                           "default.yaml --start 0.1,0.40,0 --goal 0.1,0.40,-15deg --seed 4"
                           " --time-limit 3600 --max-propagations 200000 --quiet"
                           " --planner KPIECE1 --attempts 1";
// The optimiser, bounded by iterations (not wall time) so that its result is deterministic.
const std::string kOptimised = " --knots 30 --optimize-time-limit 600 --optimize-iterations 150";

std::string temp(const std::string& name) {
  const std::string path = ::testing::TempDir() + std::to_string(getpid()) + "_" + name;
  std::remove(path.c_str());
  return path;
}

bool exists(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0;
}

bool wellFormed(const std::string& path) { return run("xmllint --noout " + path).status == 0; }

/// The `values` list of the animation element with this id.
std::vector<std::string> animatedValues(const std::string& svg, const std::string& id) {
  const std::size_t at = svg.find("id=\"" + id + "\"");
  if (at == std::string::npos) return {};
  const std::size_t v = svg.find(" values=\"", at) + 9;
  std::vector<std::string> out;
  std::stringstream list(svg.substr(v, svg.find('"', v) - v));
  for (std::string item; std::getline(list, item, ';');) out.push_back(item);
  return out;
}

TEST(PlanPictures, SvgAndReportAreWellFormedAndFollowThePlan) {
  const std::string out = temp("pic.json"), svg = temp("pic.svg"), html = temp("pic.html");
  const Result r = run(kSmall + " --no-optimize --trials 4 --out " + out + " --svg " + svg +
                       " --report " + html);
  ASSERT_TRUE(r.status == 0 || r.status == 4) << r.err;  // a plan written
  EXPECT_TRUE(wellFormed(svg));
  EXPECT_TRUE(wellFormed(html));
  const auto plan = nlohmann::json::parse(slurp(out));
  const std::string text = slurp(svg);
  const auto at = animatedValues(text, "a-part-translate");
  const auto phi = animatedValues(text, "a-part-rotate");
  ASSERT_EQ(at.size(), plan["samples"].size());  // one frame value per sample
  ASSERT_EQ(phi.size(), plan["samples"].size());
  double x = 0, y = 0;
  ASSERT_EQ(std::sscanf(at.front().c_str(), "%lf %lf", &x, &y), 2);
  EXPECT_NEAR(x / 1000, plan["q0"][0].get<double>(), 1e-5);  // first frame: the start pose
  EXPECT_NEAR(y / 1000, plan["q0"][1].get<double>(), 1e-5);
  EXPECT_NEAR(std::stod(phi.front()), plan["q0"][2].get<double>() * 180 / M_PI, 1e-3);
  const auto& last = plan["samples"].back()["q"];
  ASSERT_EQ(std::sscanf(at.back().c_str(), "%lf %lf", &x, &y), 2);
  EXPECT_NEAR(x / 1000, last[0].get<double>(), 1e-5);
  EXPECT_NEAR(y / 1000, last[1].get<double>(), 1e-5);
  // The report inlines the same animation and its plots; nothing is fetched. Its verdict
  // box says whether the plan earned its certificate, in the certificate's own words.
  const std::string page = slurp(html);
  const bool certified = plan["certificate"]["certified"].get<bool>();
  EXPECT_NE(page.find(certified ? "class=\"verdict good\"" : "class=\"verdict bad\""),
            std::string::npos);
  EXPECT_NE(page.find(certified ? "certified: " : "NOT certified: "), std::string::npos);
  EXPECT_NE(page.find(text.substr(text.find("<svg"), 2000)), std::string::npos);
  EXPECT_EQ(page.find("src="), std::string::npos);
  EXPECT_EQ(page.find("href="), std::string::npos);
}

TEST(PlanPictures, SameSeedWithReproducibleGivesByteIdenticalFiles) {
  std::vector<std::string> runs[2];
  for (int k = 0; k < 2; ++k) {
    const std::string tag = "repro" + std::to_string(k);
    const std::string files[] = {temp(tag + ".json"), temp(tag + ".csv"), temp(tag + ".svg"),
                                 temp(tag + ".html")};
    const Result r = run(kSmall + kOptimised + " --reproducible --out " + files[0] + " --csv " +
                         files[1] + " --svg " + files[2] + " --report " + files[3]);
    ASSERT_TRUE(r.status == 0 || r.status == 4) << r.err;  // optimised plan accepted or kept
    ASSERT_NE(slurp(files[0]).find("\"optimization\""), std::string::npos);
    for (const std::string& f : files) runs[k].push_back(slurp(f));
  }
  for (std::size_t f = 0; f < runs[0].size(); ++f) {
    EXPECT_FALSE(runs[0][f].empty());
    EXPECT_TRUE(runs[0][f] == runs[1][f]) << "file " << f << " differs between the runs";
  }
  EXPECT_EQ(runs[0][0].find("planning_time"), std::string::npos);
  EXPECT_EQ(runs[0][0].find("solve_time"), std::string::npos);
  EXPECT_EQ(runs[0][3].find("planning time"), std::string::npos);
}

TEST(PlanPictures, SigintWritesTheBestPlanSoFarAndExits130) {
  // A goal the search does not reach within seconds; SIGINT after about a second.
  const std::string out = temp("sigint.json"), svg = temp("sigint.svg");
  const Stopped r =
      runAndSignal({kPlanExe, "--cell", kCellDir + "default.yaml", "--start", "0.1,0.40,0",
                    "--goal", "0.3,0.40,90deg", "--time-limit", "600", "--planner", "KPIECE1",
                    "--quiet", "--no-optimize", "--out", out, "--svg", svg},
                   SIGINT, std::chrono::milliseconds(1500));
  EXPECT_EQ(r.status, 130);
  const pid_t pid = r.pid;
  const auto plan = nlohmann::json::parse(slurp(out));  // complete, valid JSON
  EXPECT_EQ(plan["status"], "approximate");
  EXPECT_GT(plan["goal_distance"].get<double>(), 1.0);
  EXPECT_TRUE(wellFormed(svg));
  EXPECT_FALSE(exists(out + ".tmp." + std::to_string(pid)));
}

TEST(PlanPictures, FailingRunsLeaveNoFile) {
  const std::string out = temp("fail.json"), csv = temp("fail.csv"), svg = temp("fail.svg"),
                    html = temp("fail.html");
  const std::string all = " --out " + out + " --csv " + csv + " --svg " + svg + " --report " + html;
  const std::string base = kPlanExe + " --cell " + kCellDir + "default.yaml --quiet ";
  struct Case {
    std::string args, needle;
  };
  const Case cases[] = {
      {"--start 0.1,0.40,0 --goal 0.1,3.0,0" + all, "out of reach"},
      {"--start 0.1,2.0,0 --goal 0.1,0.4,0" + all, "cannot hold the start pose"},
      {"--start 0.1,0.40,0 --goal 0.1,0.4,0 --svg-still -1" + all, "--svg-still"},
      {"--start 0.1,0.40,0 --goal 0.1,0.4,0 --out " + out + " --csv " + csv + " --report " + html +
           " --svg /nonexistent_rbsf_dir/x.svg",
       "--svg: cannot write '/nonexistent_rbsf_dir/x.svg': no directory"},
      {"--start 0.1,0.40,0 --goal 0.1,0.4,0 --out " + out + " --svg " + out,
       "is also given to --out"},
  };
  for (const Case& c : cases) {
    const Result r = run(base + c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << c.args << "\n" << r.err;
    for (const std::string& f : {out, csv, svg, html}) EXPECT_FALSE(exists(f)) << c.args << f;
  }
}

TEST(SimulatePictures, SvgIsWellFormedWithAFrameEvery10ms) {
  const std::string svg = temp("sim.svg");
  const Result r =
      run(kSimulateExe + " --cell " + kCellDir + "default.yaml --start 0.1,0.40,0 --controls " +
          kCellDir + "default_controls.csv --svg " + svg);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(wellFormed(svg));
  const std::string text = slurp(svg);
  EXPECT_EQ(animatedValues(text, "a-part-translate").size(), 251u);  // t = 0, then 2.5 s / 10 ms
  EXPECT_NE(text.find(" dur=\"2.500000s\""), std::string::npos);
}

TEST(SimulatePictures, BadInputLeavesNoSvg) {
  const std::string svg = temp("simbad.svg");
  const Result r = run(kSimulateExe + " --cell " + kCellDir +
                       "default.yaml --start 0.1,0.40,0 --controls /nonexistent.csv --svg " + svg);
  EXPECT_EQ(r.status, 2);
  EXPECT_FALSE(exists(svg));
  const Result d =
      run(kSimulateExe + " --cell " + kCellDir + "default.yaml --start 0.1,0.40,0 --controls " +
          kCellDir + "default_controls.csv --svg /nonexistent_rbsf_dir/s.svg");
  EXPECT_EQ(d.status, 2);
  EXPECT_NE(d.err.find("--svg: cannot write"), std::string::npos) << d.err;
}

}  // namespace

namespace {

/// The page as headless Chromium (Debian's chromium, installed by scripts/install-deps.sh)
/// builds it: its DOM on stdout, the console on stderr.
Result renderInChromium(const std::string& page, const std::string& screenshot = "") {
  const std::string profile = temp("chromium_profile");
  std::system(("mkdir -p " + profile).c_str());
  return run("chromium --headless --no-sandbox --disable-gpu --user-data-dir=" + profile +
             " --enable-logging=stderr --v=0 --window-size=1000,1400 " +
             (screenshot.empty() ? "--dump-dom" : "--screenshot=" + screenshot) + " file://" +
             page);
}

}  // namespace

TEST(PlanPictures, TheReportLoadsInChromiumWithItsVerdictScaleLegendGoalBandAndLimits) {
  ASSERT_EQ(std::system("command -v chromium >/dev/null"), 0)
      << "chromium is missing: scripts/install-deps.sh installs it";
  const std::string html = temp("chromium_report.html"), png = temp("chromium_report.png");
  const Result plan = run(kPlanExe + " --cell " + kCellDir +
                          "default.yaml --start 0.1,0.40,0 --goal 0.1,0.40,-15deg --quiet "
                          "--trials 4 --required-rate 0.4 --report " +
                          html);
  ASSERT_EQ(plan.status, 0) << plan.out << plan.err;
  const Result dom = renderInChromium(html);
  ASSERT_EQ(dom.status, 0) << dom.err;
  // Loaded without a script error (the page has no script; an error would say otherwise).
  EXPECT_EQ(dom.err.find("Uncaught"), std::string::npos) << dom.err;
  EXPECT_EQ(dom.err.find(":CONSOLE:"), std::string::npos) << dom.err;
  for (const char* what :
       {"id=\"verdict\" class=\"verdict good\"", "certified: 4/4 trials", "class=\"scale-bar\"",
        "class=\"world-axes\"", "class=\"start\"", "class=\"force-legend\"", "goal phi +- 2.0 deg",
        "limit +", "stroke limit", "<polyline class=\"series\""})
    EXPECT_NE(dom.out.find(what), std::string::npos) << what;
  const Result shot = renderInChromium(html, png);
  ASSERT_EQ(shot.status, 0) << shot.err;
  EXPECT_GT(slurp(png).size(), 20000u);  // a drawn page, not a blank one
  EXPECT_EQ(slurp(png).substr(1, 3), "PNG");
}
