// Command-line value parsers (tools/common): strict numbers, angles, vectors, states.

#include "rbsf/tools/cli_values.h"

#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/core/state_layout.h"

namespace rbsf::tools {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

template <class F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "<no InputError>";
}

TEST(CliNumber, AcceptsPlainAndScientific) {
  EXPECT_DOUBLE_EQ(parseNumber("1.5", "--v"), 1.5);
  EXPECT_DOUBLE_EQ(parseNumber("-2", "--v"), -2.0);
  EXPECT_DOUBLE_EQ(parseNumber("+3.25", "--v"), 3.25);
  EXPECT_DOUBLE_EQ(parseNumber("1e-3", "--v"), 1e-3);
  EXPECT_DOUBLE_EQ(parseNumber("2.5E2", "--v"), 250.0);
  EXPECT_DOUBLE_EQ(parseNumber(".5", "--v"), 0.5);
  EXPECT_DOUBLE_EQ(parseNumber("0", "--v"), 0.0);
  EXPECT_DOUBLE_EQ(parseNumber("  7 ", "--v"), 7.0);  // surrounding whitespace tolerated
}

TEST(CliNumber, RejectsEverythingElse) {
  EXPECT_EQ(errorOf([] { parseNumber("abc", "--v"); }), "--v: 'abc' is not a number");
  EXPECT_EQ(errorOf([] { parseNumber("", "--v"); }), "--v: empty value (expected a number)");
  EXPECT_EQ(errorOf([] { parseNumber("   ", "--v"); }), "--v: empty value (expected a number)");
  EXPECT_EQ(errorOf([] { parseNumber("nan", "--v"); }), "--v: 'nan' is not finite");
  EXPECT_EQ(errorOf([] { parseNumber("inf", "--v"); }), "--v: 'inf' is not finite");
  EXPECT_EQ(errorOf([] { parseNumber("-infinity", "--v"); }), "--v: '-infinity' is not finite");
  EXPECT_EQ(errorOf([] { parseNumber("1e999", "--v"); }), "--v: '1e999' is out of range");
  EXPECT_EQ(errorOf([] { parseNumber("-1e999", "--v"); }), "--v: '-1e999' is out of range");
  for (const char* bad : {"1.5x", "1,5", "1 2", "0x10", "--1", "+-1", "++1", "+", "-", ".", "e5",
                          "1e", "1.2.3", "30deg", "true"}) {
    SCOPED_TRACE(bad);
    EXPECT_EQ(errorOf([&] { parseNumber(bad, "--v"); }),
              "--v: '" + std::string(bad) + "' is not a number");
  }
}

TEST(CliAngle, RadiansAndDegrees) {
  EXPECT_DOUBLE_EQ(parseAngle("1.2", "--phi"), 1.2);
  EXPECT_DOUBLE_EQ(parseAngle("1.2rad", "--phi"), 1.2);
  EXPECT_DOUBLE_EQ(parseAngle("30deg", "--phi"), 30 * kDeg);
  EXPECT_DOUBLE_EQ(parseAngle("-45deg", "--phi"), -45 * kDeg);
  EXPECT_DOUBLE_EQ(parseAngle("+90deg", "--phi"), std::numbers::pi / 2);
  EXPECT_DOUBLE_EQ(parseAngle(" 10 deg ", "--phi"), 10 * kDeg);
  EXPECT_DOUBLE_EQ(parseAngle("1e1deg", "--phi"), 10 * kDeg);
}

TEST(CliAngle, RejectsBadAngles) {
  const std::string why = "is not an angle (radians, or degrees with a deg suffix)";
  for (const char* bad : {"abc", "deg", "30degrees", "30 d", "30°", "30degdeg", "3 0deg", "rad"}) {
    SCOPED_TRACE(bad);
    EXPECT_EQ(errorOf([&] { parseAngle(bad, "--phi"); }),
              "--phi: '" + std::string(bad) + "' " + why);
  }
  EXPECT_EQ(errorOf([] { parseAngle("", "--phi"); }), "--phi: empty value (expected an angle)");
  EXPECT_EQ(errorOf([] { parseAngle("nandeg", "--phi"); }), "--phi: 'nandeg' is not finite");
  EXPECT_EQ(errorOf([] { parseAngle("1e999deg", "--phi"); }), "--phi: '1e999deg' is out of range");
}

TEST(CliVector, ParsesCommaSeparatedNumbers) {
  EXPECT_EQ(parseVector("1,2,3", "--f", 3), (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(parseVector(" 1 , -2.5 ,3e1 ", "--f", 3), (std::vector<double>{1, -2.5, 30}));
  EXPECT_EQ(parseVector("4", "--f", 1), (std::vector<double>{4}));
}

TEST(CliVector, LengthErrorNamesExpectedAndGot) {
  EXPECT_EQ(errorOf([] { parseVector("1,2,3,4,5", "--q", 7, "x,y,phi,theta,l1..l3"); }),
            "--q: expected 7 numbers (x,y,phi,theta,l1..l3), got 5");
  EXPECT_EQ(errorOf([] { parseVector("1,2", "--f", 3); }), "--f: expected 3 numbers, got 2");
  EXPECT_EQ(errorOf([] { parseVector("1,2", "--f", 1); }), "--f: expected 1 number, got 2");
}

TEST(CliVector, RejectsEmptyEntriesAndBadNumbers) {
  EXPECT_EQ(errorOf([] { parseVector("", "--f", 3); }), "--f: empty value (expected 3 numbers)");
  EXPECT_EQ(errorOf([] { parseVector("1,2,3,", "--f", 3); }),
            "--f: entry 4 is empty (stray comma?)");
  EXPECT_EQ(errorOf([] { parseVector(",1,2", "--f", 3); }), "--f: entry 1 is empty (stray comma?)");
  EXPECT_EQ(errorOf([] { parseVector("1,,2", "--f", 3); }), "--f: entry 2 is empty (stray comma?)");
  EXPECT_EQ(errorOf([] { parseVector("1, ,2", "--f", 3); }),
            "--f: entry 2 is empty (stray comma?)");
  EXPECT_EQ(errorOf([] { parseVector("1,x,2", "--f", 3); }), "--f entry 2: 'x' is not a number");
  EXPECT_EQ(errorOf([] { parseVector("1,2,nan", "--f", 3); }), "--f entry 3: 'nan' is not finite");
  EXPECT_EQ(errorOf([] { parseVector("1,2,inf", "--f", 3); }), "--f entry 3: 'inf' is not finite");
  EXPECT_EQ(errorOf([] { parseVector("1e999,2,3", "--f", 3); }),
            "--f entry 1: '1e999' is out of range");
  EXPECT_EQ(errorOf([] { parseVector("1;2;3", "--f", 3); }), "--f: expected 3 numbers, got 1");
}

TEST(CliList, TakesOneOrMoreNumbersWithTheVectorsRules) {
  EXPECT_EQ(parseList("0.45", "--u"), (std::vector<double>{0.45}));
  EXPECT_EQ(parseList(" 0.45 , 0.6,1e-1 ", "--u"), (std::vector<double>{0.45, 0.6, 0.1}));
  EXPECT_EQ(errorOf([] { parseList("", "--u"); }),
            "--u: empty value (expected one or more numbers)");
  EXPECT_EQ(errorOf([] { parseList("0.45,", "--u"); }), "--u: entry 2 is empty (stray comma?)");
  EXPECT_EQ(errorOf([] { parseList("0.45,x", "--u"); }), "--u entry 2: 'x' is not a number");
}

TEST(CliFields, SplitsWithoutParsingAndCountsLikeAVector) {
  EXPECT_EQ(parseFields(" 2.5deg , 0.01", "--l", 2),
            (std::vector<std::string_view>{"2.5deg", "0.01"}));
  EXPECT_EQ(errorOf([] { parseFields("2.5deg", "--l", 2, "angle,position"); }),
            "--l: expected 2 numbers (angle,position), got 1");
  EXPECT_EQ(errorOf([] { parseFields("2.5deg,,1", "--l", 3); }),
            "--l: entry 2 is empty (stray comma?)");
}

TEST(CliPose, PhiAcceptsDegrees) {
  const Pose p = parsePose("0.1, -0.2, 30deg", "--pose");
  EXPECT_DOUBLE_EQ(p.x, 0.1);
  EXPECT_DOUBLE_EQ(p.y, -0.2);
  EXPECT_DOUBLE_EQ(p.phi, 30 * kDeg);
  EXPECT_DOUBLE_EQ(parsePose("0,0,0.5", "--pose").phi, 0.5);
  EXPECT_EQ(errorOf([] { parsePose("1deg,0,0", "--pose"); }),
            "--pose entry 1 (x): '1deg' is not a number");
  EXPECT_EQ(errorOf([] { parsePose("0,0", "--pose"); }),
            "--pose: expected 3 numbers (x,y,phi), got 2");
}

TEST(CliConfig, AnglesAtTheLayoutIndices) {
  const VecQ q = parseConfig("0.01,0.4,10deg,-5deg,0.3,0.31,0.32", "--q", 3);
  ASSERT_EQ(q.size(), layout::configDim(3));
  EXPECT_DOUBLE_EQ(q[layout::kX], 0.01);
  EXPECT_DOUBLE_EQ(q[layout::kY], 0.4);
  EXPECT_DOUBLE_EQ(q[layout::kPhi], 10 * kDeg);
  EXPECT_DOUBLE_EQ(q[layout::kTheta], -5 * kDeg);
  EXPECT_DOUBLE_EQ(q[layout::stroke(0)], 0.3);
  EXPECT_DOUBLE_EQ(q[layout::stroke(2)], 0.32);
  const VecQ r = parseConfig("0,0.4,0.1,0.2,0.3", "--q", 1);
  EXPECT_DOUBLE_EQ(r[layout::kTheta], 0.2);
}

TEST(CliConfig, ErrorsNameTheEntry) {
  EXPECT_EQ(errorOf([] { parseConfig("0,0.4,0,0,0.3", "--q", 3); }),
            "--q: expected 7 numbers (x,y,phi,theta,l1..l3), got 5");
  EXPECT_EQ(errorOf([] { parseConfig("0,0.4,0", "--q", 1); }),
            "--q: expected 5 numbers (x,y,phi,theta,l1), got 3");
  EXPECT_EQ(errorOf([] { parseConfig("0,0.4,0", "--q", 2); }),
            "--q: expected 6 numbers (x,y,phi,theta,l1,l2), got 3");
  EXPECT_EQ(errorOf([] { parseConfig("0,0.4,0,0,0.3,0.3deg,0.3", "--q", 3); }),
            "--q entry 6 (l2): '0.3deg' is not a number");
  EXPECT_EQ(errorOf([] { parseConfig("0,0.4,abc,0,0.3,0.3,0.3", "--q", 3); }),
            "--q entry 3 (phi): 'abc' is not an angle (radians, or degrees with a deg suffix)");
  EXPECT_EQ(errorOf([] { parseConfig("0,0.4,0,0,0.3,0.3,0.3,", "--q", 3); }),
            "--q: entry 8 is empty (stray comma?)");
  EXPECT_EQ(errorOf([] { parseConfig("0,0,0,0", "--q", 0); }),
            "--q: finger count 0 is outside 1..12");
  EXPECT_EQ(errorOf([] { parseConfig("0,0,0,0", "--q", kMaxFingers + 1); }),
            "--q: finger count 13 is outside 1..12");
}

TEST(CliVelocity, PlainNumbersOnly) {
  const VecQ v = parseVelocity("0.1,0,-0.2,0.05,0,0,0.01", "--v", 3);
  ASSERT_EQ(v.size(), 7);
  EXPECT_DOUBLE_EQ(v[layout::kPhi], -0.2);
  EXPECT_DOUBLE_EQ(v[layout::stroke(2)], 0.01);
  EXPECT_EQ(errorOf([] { parseVelocity("0,0,1deg,0,0,0,0", "--v", 3); }),
            "--v entry 3 (dphi): '1deg' is not a number");
  EXPECT_EQ(errorOf([] { parseVelocity("0,0,0", "--v", 3); }),
            "--v: expected 7 numbers (dx,dy,dphi,dtheta,dl1..dl3), got 3");
}

TEST(CliLayout, DescribesTheStateOrder) {
  EXPECT_EQ(configLayout(1), "x,y,phi,theta,l1");
  EXPECT_EQ(configLayout(2), "x,y,phi,theta,l1,l2");
  EXPECT_EQ(configLayout(5), "x,y,phi,theta,l1..l5");
  EXPECT_EQ(configLayout(3, true), "dx,dy,dphi,dtheta,dl1..dl3");
}

}  // namespace
}  // namespace rbsf::tools
