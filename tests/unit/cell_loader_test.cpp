// Cell loading (MODEL.md "Files"): the example cells, every rejected input with a message
// naming the key path, defaults, and Cell::validate() on cells built in code.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "rbsf/dynamics/cell.h"
#include "rbsf/dynamics/errors.h"

namespace rbsf {
namespace {

const std::string kCells = std::string(RBSF_SOURCE_DIR) + "/cells/";

constexpr const char* kFingers =
    "  - {r: -0.2, stroke: [0.05, 0.45], mass: 2.0, force_limit: 600.0}\n"
    "  - {r: 0.0, stroke: [0.05, 0.45], mass: 2.0, force_limit: 600.0}\n"
    "  - {r: 0.2, stroke: [0.05, 0.45], mass: 2.0, force_limit: 600.0}\n";

/// A valid cell in block style, so single keys can be replaced by text substitution.
std::string goodYaml() {
  return std::string(
             "gravity: 9.81\n"
             "base:\n"
             "  inertia: 5.0\n"
             "  theta_limits: [-0.7, 0.7]\n"
             "  torque_limit: 300.0\n"
             "fingers:\n") +
         kFingers +
         "object:\n"
         "  shape: {type: ellipse, a: 0.3, b: 0.15, center: [-0.1, 0.0]}\n"
         "  mass: 20.0\n"
         "  inertia: 0.5625\n"
         "friction: {static: 0.5, kinetic: 0.0}\n";
}

/// goodYaml() with the first occurrence of `from` replaced by `to` (from must occur).
std::string with(const std::string& from, const std::string& to) {
  std::string s = goodYaml();
  const auto pos = s.find(from);
  if (pos == std::string::npos) throw std::logic_error("test bug: '" + from + "' not in YAML");
  return s.replace(pos, from.size(), to);
}

std::string errorOf(const std::string& yaml, const std::string& label = "cells/x.yaml") {
  try {
    parseCell(yaml, label);
  } catch (const InputError& e) {
    return e.what();
  }
  return "<no InputError>";
}

// ---------------------------------------------------------------------------------------
// Example cells.

TEST(CellLoader, GoodYamlParses) {
  const Cell c = parseCell(goodYaml(), "good");
  EXPECT_EQ(c.name, "good");
  EXPECT_EQ(c.numFingers(), 3);
  EXPECT_NO_THROW(c.validate());
}

TEST(CellLoader, DefaultCellHasTheFileValues) {
  const Cell c = loadCell(kCells + "default.yaml");
  EXPECT_EQ(c.name, kCells + "default.yaml");
  EXPECT_DOUBLE_EQ(c.gravity, 9.81);
  EXPECT_DOUBLE_EQ(c.base.inertia, 5.0);
  EXPECT_DOUBLE_EQ(c.base.theta_min, -0.785398);
  EXPECT_DOUBLE_EQ(c.base.theta_max, 0.785398);
  EXPECT_DOUBLE_EQ(c.base.torque_limit, 400.0);
  ASSERT_EQ(c.numFingers(), 3);
  const double r[] = {-0.2, 0.0, 0.2};
  for (int i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(c.fingers[i].r, r[i]);
    EXPECT_DOUBLE_EQ(c.fingers[i].stroke_min, 0.05);
    EXPECT_DOUBLE_EQ(c.fingers[i].stroke_max, 0.55);
    EXPECT_DOUBLE_EQ(c.fingers[i].mass, 2.0);
    EXPECT_DOUBLE_EQ(c.fingers[i].force_limit, 800.0);
    EXPECT_DOUBLE_EQ(c.fingers[i].com_offset, 0.0);
    EXPECT_DOUBLE_EQ(c.fingers[i].inertia, 0.0);
  }
  const auto* e = dynamic_cast<const EllipseShape*>(c.object.shape.get());
  ASSERT_NE(e, nullptr);
  EXPECT_EQ(e->type(), "ellipse");
  EXPECT_DOUBLE_EQ(e->a(), 0.30);
  EXPECT_DOUBLE_EQ(e->b(), 0.15);
  EXPECT_DOUBLE_EQ(e->center().x(), -0.10);
  EXPECT_DOUBLE_EQ(e->center().y(), 0.0);
  EXPECT_DOUBLE_EQ(c.object.mass, 24.0);
  EXPECT_DOUBLE_EQ(c.object.inertia, 0.675);
  EXPECT_DOUBLE_EQ(c.friction.mu_static, 0.5);
  EXPECT_DOUBLE_EQ(c.friction.mu_kinetic, 0.0);
}

TEST(CellLoader, CircleCellHasTheFileValues) {
  const Cell c = loadCell(kCells + "circle.yaml");
  EXPECT_DOUBLE_EQ(c.base.torque_limit, 250.0);
  ASSERT_EQ(c.numFingers(), 3);
  EXPECT_DOUBLE_EQ(c.fingers[0].r, -0.10);
  EXPECT_DOUBLE_EQ(c.fingers[2].force_limit, 500.0);
  const auto* s = dynamic_cast<const CircleShape*>(c.object.shape.get());
  ASSERT_NE(s, nullptr);
  EXPECT_DOUBLE_EQ(s->radius(), 0.16);
  EXPECT_EQ(s->center(), Vec2::Zero());
  EXPECT_DOUBLE_EQ(c.object.mass, 12.0);
  EXPECT_DOUBLE_EQ(c.object.inertia, 0.1536);
  EXPECT_DOUBLE_EQ(c.friction.mu_static, 0.4);
  EXPECT_DOUBLE_EQ(c.friction.mu_kinetic, 0.0);  // omitted in the file: default
}

TEST(CellLoader, Box4CellHasTheFileValues) {
  const Cell c = loadCell(kCells + "box4.yaml");
  ASSERT_EQ(c.numFingers(), 4);
  EXPECT_DOUBLE_EQ(c.fingers[1].r, -0.06);
  EXPECT_DOUBLE_EQ(c.fingers[3].r, 0.18);
  const auto* s = dynamic_cast<const SuperellipseShape*>(c.object.shape.get());
  ASSERT_NE(s, nullptr);
  EXPECT_DOUBLE_EQ(s->a(), 0.25);
  EXPECT_DOUBLE_EQ(s->b(), 0.12);
  EXPECT_DOUBLE_EQ(s->exponent(), 4.0);
  EXPECT_DOUBLE_EQ(c.object.mass, 18.0);
  EXPECT_DOUBLE_EQ(c.object.inertia, 0.4146);
  EXPECT_DOUBLE_EQ(c.friction.mu_static, 0.6);
  EXPECT_DOUBLE_EQ(c.friction.mu_kinetic, 0.3);
}

TEST(CellLoader, HeavyCellHasTheFileValues) {
  const Cell c = loadCell(kCells + "heavy.yaml");
  EXPECT_DOUBLE_EQ(c.base.inertia, 12.0);
  EXPECT_DOUBLE_EQ(c.base.theta_min, -0.6);
  EXPECT_DOUBLE_EQ(c.base.theta_max, 0.6);
  EXPECT_DOUBLE_EQ(c.base.torque_limit, 1500.0);
  ASSERT_EQ(c.numFingers(), 3);
  for (const auto& f : c.fingers) {
    EXPECT_DOUBLE_EQ(f.mass, 4.0);
    EXPECT_DOUBLE_EQ(f.force_limit, 2500.0);
    EXPECT_DOUBLE_EQ(f.com_offset, -0.05);
    EXPECT_DOUBLE_EQ(f.inertia, 0.02);
  }
  const auto* e = dynamic_cast<const EllipseShape*>(c.object.shape.get());
  ASSERT_NE(e, nullptr);
  EXPECT_DOUBLE_EQ(e->a(), 0.35);
  EXPECT_DOUBLE_EQ(e->center().x(), 0.06);
  EXPECT_DOUBLE_EQ(c.object.mass, 80.0);
  EXPECT_DOUBLE_EQ(c.object.inertia, 3.098);
}

/// Lowest boundary point of `shape` (object frame) at abscissa x: its height and inward
/// normal. Uses only c(xi) (dense sampling, linear interpolation), so it does not depend
/// on the shape's closest-point or line-entry queries. False when x misses the shape.
bool underside(const Shape& shape, double x, double& y, Vec2& normal) {
  constexpr int kN = 20000;
  bool hit = false;
  Vec2 prev = shape.point(0.0);
  for (int k = 1; k <= kN; ++k) {
    const double xi = 2 * M_PI * k / kN;
    const Vec2 cur = shape.point(xi);
    if ((prev.x() - x) * (cur.x() - x) <= 0 && prev.x() != cur.x()) {
      const double t = (x - prev.x()) / (cur.x() - prev.x());
      const double yy = prev.y() + t * (cur.y() - prev.y());
      if (!hit || yy < y) {
        y = yy;
        normal = shape.boundary(xi - (1 - t) * 2 * M_PI / kN).normal;
      }
      hit = true;
    }
    prev = cur;
  }
  return hit;
}

/// Every cell in cells/ loads, and is physically plausible: at theta = 0 there is an
/// object position (phi = 0) where every fingertip touches the underside of the part
/// within its stroke, with the COM between the outer fingers and no contact normal
/// steeper than 60 degrees; the fingers can carry the part with margin, and the base
/// can hold the loaded mechanism at its angle limits.
TEST(CellLoader, EveryExampleCellLoadsAndCanRestOnItsFingers) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kCells)) {
    if (entry.path().extension() != ".yaml") continue;
    ++count;
    SCOPED_TRACE(entry.path().string());
    Cell c;
    ASSERT_NO_THROW(c = loadCell(entry.path().string()));
    const int m = c.numFingers();
    double r_min = 1e9, r_max = -1e9;
    for (const auto& f : c.fingers) r_min = std::min(r_min, f.r), r_max = std::max(r_max, f.r);
    bool found = false;
    for (double x = -0.15; x <= 0.15 + 1e-12 && !found; x += 0.005) {
      if (x <= r_min || x >= r_max) continue;  // COM above the support
      // The COM sits at (x, y); finger i touches at object-frame height yc[i]: l_i = y + yc[i].
      std::vector<double> yc(m);
      double lo = -1e9, hi = 1e9;
      bool ok = true;
      for (int i = 0; i < m && ok; ++i) {
        Vec2 n = Vec2::Zero();
        ok = underside(*c.object.shape, c.fingers[i].r - x, yc[i], n) && n.y() > 0.5;
        lo = std::max(lo, c.fingers[i].stroke_min - yc[i]);
        hi = std::min(hi, c.fingers[i].stroke_max - yc[i]);
      }
      if (!ok || lo > hi) continue;
      found = true;
      const double y = 0.5 * (lo + hi);
      double carriage_weight = 0, force_sum = 0;
      for (const auto& f : c.fingers) {
        carriage_weight += f.mass * c.gravity;
        force_sum += f.force_limit;
      }
      EXPECT_LE(c.object.mass * c.gravity, 0.5 * (force_sum - carriage_weight));
      for (double th : {c.base.theta_min, c.base.theta_max}) {
        double torque = c.object.mass * c.gravity * rotate(th, Vec2(x, y)).x();
        for (int i = 0; i < m; ++i) {
          const Vec2 com(c.fingers[i].r, y + yc[i] + c.fingers[i].com_offset);
          torque += c.fingers[i].mass * c.gravity * rotate(th, com).x();
        }
        EXPECT_LE(1.5 * std::abs(torque), c.base.torque_limit) << "theta " << th;
      }
    }
    EXPECT_TRUE(found) << "no resting pose within the strokes";
  }
  EXPECT_GE(count, 4);
}

// ---------------------------------------------------------------------------------------
// Defaults.

TEST(CellLoader, OptionalKeysTakeTheirDefaults) {
  const std::string yaml =
      "base: {inertia: 0, theta_limits: [-0.5, 0.5], torque_limit: 100}\n"
      "fingers:\n"
      "  - {r: -0.1, stroke: [0.0, 0.3], mass: 1, force_limit: 100}\n"
      "  - {r: 0.1, stroke: [0.0, 0.3], mass: 1, force_limit: 100}\n"
      "object: {shape: {type: circle, radius: 0.1}, mass: 1, inertia: 0.005}\n"
      "friction: {static: 0.3}\n";
  const Cell c = parseCell(yaml);
  EXPECT_EQ(c.name, "<cell>");
  EXPECT_DOUBLE_EQ(c.gravity, 9.81);
  EXPECT_DOUBLE_EQ(c.base.inertia, 0.0);  // zero base inertia is allowed
  EXPECT_DOUBLE_EQ(c.friction.mu_static, 0.3);
  EXPECT_DOUBLE_EQ(c.friction.mu_kinetic, 0.0);
  for (const auto& f : c.fingers) {
    EXPECT_DOUBLE_EQ(f.com_offset, 0.0);
    EXPECT_DOUBLE_EQ(f.inertia, 0.0);
  }
  const auto* s = dynamic_cast<const CircleShape*>(c.object.shape.get());
  ASSERT_NE(s, nullptr);
  EXPECT_EQ(s->center(), Vec2::Zero());
}

TEST(CellLoader, ExplicitOptionalKeysAreRead) {
  const Cell c = parseCell(with("gravity: 9.81", "gravity: 0"));
  EXPECT_DOUBLE_EQ(c.gravity, 0.0);  // zero gravity is allowed
  const Cell d =
      parseCell(with("mass: 2.0, force_limit: 600.0}",
                     "mass: 2.0, force_limit: 600.0, com_offset: -0.03, inertia: 0.01}"));
  EXPECT_DOUBLE_EQ(d.fingers[0].com_offset, -0.03);
  EXPECT_DOUBLE_EQ(d.fingers[0].inertia, 0.01);
  EXPECT_DOUBLE_EQ(d.fingers[1].com_offset, 0.0);
  const Cell e = parseCell(with("kinetic: 0.0", "kinetic: 0.5"));  // mu_k == mu_s is allowed
  EXPECT_DOUBLE_EQ(e.friction.mu_kinetic, 0.5);
  const Cell s =
      parseCell(with("{type: ellipse, a: 0.3, b: 0.15, center: [-0.1, 0.0]}",
                     "{type: superellipse, a: 0.3, b: 0.15, exponent: 6, center: [0.01, -0.02]}"));
  const auto* se = dynamic_cast<const SuperellipseShape*>(s.object.shape.get());
  ASSERT_NE(se, nullptr);
  EXPECT_DOUBLE_EQ(se->exponent(), 6.0);
  EXPECT_DOUBLE_EQ(se->center().y(), -0.02);
}

// ---------------------------------------------------------------------------------------
// Rejected input: one case per rule; the message names the label and the key path.

struct BadCase {
  const char* name;
  std::string yaml;
  std::vector<std::string> expect;  ///< substrings of the message
};

std::string thirteenFingers() {
  std::string f;
  for (int i = 0; i < 13; ++i)
    f += "  - {r: " + std::to_string(0.05 * i - 0.3) +
         ", stroke: [0.05, 0.45], mass: 1, force_limit: 100}\n";
  return with(kFingers, f);
}

std::vector<BadCase> badCases() {
  const std::string ell = "{type: ellipse, a: 0.3, b: 0.15, center: [-0.1, 0.0]}";
  const std::string f1 = "{r: 0.0, stroke: [0.05, 0.45], mass: 2.0, force_limit: 600.0}";
  return {
      {"MissingObjectInertia", with("  inertia: 0.5625\n", ""), {"missing key object.inertia"}},
      {"MissingBaseTorqueLimit",
       with("  torque_limit: 300.0\n", ""),
       {"missing key base.torque_limit"}},
      {"MissingShape", with("  shape: " + ell + "\n", ""), {"missing key object.shape"}},
      {"MissingFriction",
       with("friction: {static: 0.5, kinetic: 0.0}\n", ""),
       {"missing key friction"}},
      {"MissingStatic",
       with("{static: 0.5, kinetic: 0.0}", "{kinetic: 0.0}"),
       {"missing key friction.static"}},
      {"MissingFingerStroke",
       with("r: 0.0, stroke: [0.05, 0.45], ", "r: 0.0, "),
       {"missing key fingers[1].stroke"}},
      {"NegativeFingerMass",
       with(f1, "{r: 0.0, stroke: [0.05, 0.45], mass: -2, force_limit: 600}"),
       {"cells/x.yaml: fingers[1].mass must be positive (got -2)"}},
      {"ZeroObjectMass", with("mass: 20.0", "mass: 0"), {"object.mass must be positive (got 0)"}},
      {"NegativeObjectInertia",
       with("inertia: 0.5625", "inertia: -1"),
       {"object.inertia must be positive (got -1)"}},
      {"ZeroObjectInertia",
       with("inertia: 0.5625", "inertia: 0.0"),
       {"object.inertia must be positive"}},
      {"NegativeBaseInertia",
       with("inertia: 5.0", "inertia: -0.5"),
       {"base.inertia must not be negative (got -0.5)"}},
      {"NegativeFingerInertia",
       with("mass: 2.0, force_limit: 600.0}", "mass: 2.0, force_limit: 600.0, inertia: -0.1}"),
       {"fingers[0].inertia must not be negative (got -0.1)"}},
      {"ThetaLimitsTooShort",
       with("[-0.7, 0.7]", "[-0.7]"),
       {"base.theta_limits must be a list of 2 numbers", "(got 1 entry)"}},
      {"ThetaLimitsScalar",
       with("[-0.7, 0.7]", "0.7"),
       {"base.theta_limits must be a list of 2 numbers (got '0.7')"}},
      {"ThetaLimitsMapping",
       with("[-0.7, 0.7]", "{lo: -1, hi: 1}"),
       {"base.theta_limits must be a list of 2 numbers (got a mapping)"}},
      {"ThetaLimitsReversed",
       with("[-0.7, 0.7]", "[0.7, -0.7]"),
       {"base.theta_limits must be [lo, hi] with lo < hi (got [0.7, -0.7])"}},
      {"ThetaLimitsEqual", with("[-0.7, 0.7]", "[0.7, 0.7]"), {"base.theta_limits", "lo < hi"}},
      {"ThetaLimitsInDegrees",
       with("[-0.7, 0.7]", "[-45, 45]"),
       {"base.theta_limits must lie within [-pi, pi] radians"}},
      {"StrokeReversed",
       with("{r: 0.2, stroke: [0.05, 0.45]", "{r: 0.2, stroke: [0.45, 0.05]"),
       {"fingers[2].stroke must be [lo, hi] with lo < hi"}},
      {"StrokeEntryNotNumber",
       with("stroke: [0.05, 0.45]", "stroke: [0.05, high]"),
       {"fingers[0].stroke[1] must be a number (got 'high')"}},
      {"ZeroTorqueLimit",
       with("torque_limit: 300.0", "torque_limit: 0"),
       {"base.torque_limit must be positive (got 0)"}},
      {"NegativeForceLimit",
       with("force_limit: 600.0", "force_limit: -5"),
       {"fingers[0].force_limit must be positive (got -5)"}},
      {"NegativeStatic",
       with("static: 0.5", "static: -0.1"),
       {"friction.static must not be negative (got -0.1)"}},
      {"NegativeKinetic",
       with("kinetic: 0.0", "kinetic: -0.1"),
       {"friction.kinetic must not be negative"}},
      {"KineticAboveStatic",
       with("kinetic: 0.0", "kinetic: 0.6"),
       {"friction.kinetic (0.6) must not exceed friction.static (0.5)"}},
      {"NegativeGravity",
       with("gravity: 9.81", "gravity: -9.81"),
       {"gravity must not be negative (got -9.81)"}},
      {"InfiniteGravity",
       with("gravity: 9.81", "gravity: .inf"),
       {"gravity must be a finite number (got '.inf')"}},
      {"NanMass", with("mass: 20.0", "mass: .nan"), {"object.mass must be a finite number"}},
      {"OverflowingNumber",
       with("torque_limit: 300.0", "torque_limit: 1e999"),
       {"base.torque_limit must be a number (got '1e999')"}},
      {"NonNumericMass",
       with("mass: 20.0", "mass: abc"),
       {"object.mass must be a number (got 'abc')"}},
      {"NumberWithUnit",
       with("mass: 20.0", "mass: 20kg"),
       {"object.mass must be a number (got '20kg')"}},
      {"BooleanMass", with("mass: 20.0", "mass: true"), {"object.mass must be a number"}},
      {"EmptyMass",
       with("mass: 20.0", "mass:"),
       {"object.mass must be a number (got an empty value)"}},
      {"ListMass", with("mass: 20.0", "mass: [20]"), {"object.mass must be a number (got a list)"}},
      {"UnknownShapeType",
       with("type: ellipse", "type: hexagon"),
       {"cells/x.yaml: object.shape.type 'hexagon' is unknown (expected ellipse, circle or "
        "superellipse)"}},
      {"ShapeTypeNotAName",
       with("type: ellipse", "type: [ellipse]"),
       {"object.shape.type must be a name"}},
      {"NegativeSemiAxis",
       with("a: 0.3", "a: -0.3"),
       {"object.shape.a must be positive (got -0.3)"}},
      {"ZeroRadius",
       with(ell, "{type: circle, radius: 0}"),
       {"object.shape.radius must be positive (got 0)"}},
      {"MissingRadius", with(ell, "{type: circle}"), {"missing key object.shape.radius"}},
      {"ExponentTooSmall",
       with(ell, "{type: superellipse, a: 0.3, b: 0.15, exponent: 1.5}"),
       {"object.shape.exponent must lie in [2, 20] (got 1.5)"}},
      {"ExponentTooLarge",
       with(ell, "{type: superellipse, a: 0.3, b: 0.15, exponent: 25}"),
       {"object.shape.exponent must lie in [2, 20] (got 25)"}},
      {"MissingExponent",
       with(ell, "{type: superellipse, a: 0.3, b: 0.15}"),
       {"missing key object.shape.exponent"}},
      {"CenterWrongLength",
       with("center: [-0.1, 0.0]", "center: [-0.1]"),
       {"object.shape.center must be a list of 2 numbers"}},
      {"ComOutsideEllipse",
       with("center: [-0.1, 0.0]", "center: [-0.1, 0.2]"),
       {"object.shape.center puts the COM (the object-frame origin) outside the shape"}},
      {"ComOnCircle",
       with(ell, "{type: circle, radius: 0.1, center: [0.1, 0]}"),
       {"object.shape.center puts the COM"}},
      {"ComOutsideSuperellipse",
       with(ell, "{type: superellipse, a: 0.3, b: 0.15, exponent: 4, center: [0.29, 0.149]}"),
       {"object.shape.center puts the COM"}},
      {"CenterNotNumber",
       with("center: [-0.1, 0.0]", "center: [left, 0.0]"),
       {"object.shape.center[0] must be a number (got 'left')"}},
      {"KeyOfAnotherShape",
       with("a: 0.3, b: 0.15,", "a: 0.3, b: 0.15, radius: 0.2,"),
       {"unknown key object.shape.radius"}},
      {"UnknownTopLevelKey", with("gravity: 9.81", "gravty: 9.81"), {"unknown key gravty"}},
      {"UnknownFingerKey",
       with("mass: 2.0, force_limit", "masss: 2.0, force_limit"),
       {"unknown key fingers[0].masss"}},
      {"UnknownBaseKey",
       with("  inertia: 5.0\n", "  inertia: 5.0\n  torque_lim: 3\n"),
       {"unknown key base.torque_lim"}},
      {"UnknownFrictionKey",
       with("kinetic: 0.0", "kinetic: 0.0, dynamic: 0.1"),
       {"unknown key friction.dynamic"}},
      {"DuplicateKey",
       with("  mass: 20.0\n", "  mass: 20.0\n  mass: 2000.0\n"),
       {"duplicate key object.mass"}},
      {"ZeroFingers", with(kFingers, "  []\n"), {"fingers must list at least one finger"}},
      {"TooManyFingers", thirteenFingers(), {"fingers lists 13 fingers; at most 12 are supported"}},
      {"FingersNotAList", with(kFingers, "  {r: 0}\n"), {"fingers must be a list of fingers"}},
      {"FingerNotAMapping",
       with(kFingers, "  - 0.2\n"),
       {"fingers[0] must be a mapping (got '0.2')"}},
      {"BaseNotAMapping",
       with("base:\n  inertia: 5.0\n  theta_limits: [-0.7, 0.7]\n  torque_limit: 300.0\n",
            "base: 5\n"),
       {"base must be a mapping (got '5')"}},
      {"MalformedYaml", with("[-0.7, 0.7]", "[-0.7, 0.7"), {"malformed YAML at line", "column"}},
      {"BadIndentation", with("  mass: 20.0\n", "    mass: 20.0\n"), {"malformed YAML at line 12"}},
      {"EmptyDocument", "", {"cells/x.yaml: the cell is empty"}},
      {"CommentOnlyDocument", "# nothing\n", {"the cell is empty"}},
      {"RootIsAList", "- 1\n- 2\n", {"the cell must be a mapping (got a list)"}},
      {"RootIsAScalar", "hello\n", {"the cell must be a mapping (got 'hello')"}},
  };
}

class CellLoaderBad : public ::testing::TestWithParam<BadCase> {};

TEST_P(CellLoaderBad, ThrowsInputErrorNamingTheKey) {
  const BadCase& c = GetParam();
  const std::string msg = errorOf(c.yaml);
  EXPECT_EQ(msg.rfind("cells/x.yaml: ", 0), 0u) << msg;
  for (const auto& part : c.expect) EXPECT_NE(msg.find(part), std::string::npos) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << "one-line message: " << msg;
}

INSTANTIATE_TEST_SUITE_P(AllRules, CellLoaderBad, ::testing::ValuesIn(badCases()),
                         [](const auto& info) { return std::string(info.param.name); });

// ---------------------------------------------------------------------------------------
// Files.

TEST(CellLoader, MissingFileNamesThePath) {
  const std::string path = kCells + "no_such_cell.yaml";
  try {
    loadCell(path);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(path + ": cannot open cell file", 0), 0u) << msg;
  }
}

TEST(CellLoader, DirectoryIsRejected) {
  try {
    loadCell(kCells);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("directory"), std::string::npos) << e.what();
  }
}

TEST(CellLoader, FileErrorsCarryThePathAsLabel) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("rbsf_cell_loader_test_" +
                     std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + ".yaml");
  {
    std::ofstream out(path);
    out << with("mass: 20.0", "mass: -3");
  }
  try {
    loadCell(path.string());
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), path.string() + ": object.mass must be positive (got -3)");
  }
  std::filesystem::remove(path);
}

// ---------------------------------------------------------------------------------------
// validate() on cells built in code.

Cell codeCell() {
  Cell c;
  c.base = {1.0, -0.5, 0.5, 100.0};
  FingerParams f;
  f.stroke_min = 0.0;
  f.stroke_max = 0.3;
  f.mass = 1.0;
  f.force_limit = 100.0;
  f.r = -0.1;
  c.fingers.push_back(f);
  f.r = 0.1;
  c.fingers.push_back(f);
  c.object.shape = std::make_shared<CircleShape>(0.1);
  c.object.mass = 1.0;
  c.object.inertia = 0.005;
  return c;
}

std::string validateError(const Cell& c) {
  try {
    c.validate();
  } catch (const InputError& e) {
    return e.what();
  }
  return "<no InputError>";
}

TEST(CellValidate, CodeBuiltCellIsValid) { EXPECT_NO_THROW(codeCell().validate()); }

TEST(CellValidate, MessagesHaveNoPrefixWithoutAName) {
  Cell c = codeCell();
  c.fingers[0].mass = -2;
  EXPECT_EQ(validateError(c), "fingers[0].mass must be positive (got -2)");
  c.name = "mycell";
  EXPECT_EQ(validateError(c), "mycell: fingers[0].mass must be positive (got -2)");
}

TEST(CellValidate, ChecksEveryInvariant) {
  struct Mut {
    void (*apply)(Cell&);
    const char* expect;
  };
  const Mut muts[] = {
      {[](Cell& c) { c.gravity = NAN; }, "gravity must be a finite number (got nan)"},
      {[](Cell& c) { c.gravity = -1; }, "gravity must not be negative (got -1)"},
      {[](Cell& c) { c.base.inertia = -1; }, "base.inertia must not be negative"},
      {[](Cell& c) { c.base.theta_min = 0.6; }, "base.theta_limits must be [lo, hi] with lo < hi"},
      {[](Cell& c) { c.base.theta_max = INFINITY; },
       "base.theta_limits[1] must be a finite number (got inf)"},
      {[](Cell& c) { c.base.torque_limit = 0; }, "base.torque_limit must be positive (got 0)"},
      {[](Cell& c) { c.fingers.clear(); }, "fingers must list at least one finger"},
      {[](Cell& c) { c.fingers.resize(kMaxFingers + 1, c.fingers[0]); },
       "fingers lists 13 fingers; at most 12 are supported"},
      {[](Cell& c) { c.fingers[1].r = NAN; }, "fingers[1].r must be a finite number"},
      {[](Cell& c) { c.fingers[1].stroke_max = -1; }, "fingers[1].stroke must be [lo, hi]"},
      {[](Cell& c) { c.fingers[1].force_limit = -1; }, "fingers[1].force_limit must be positive"},
      {[](Cell& c) { c.fingers[1].com_offset = INFINITY; },
       "fingers[1].com_offset must be a finite"},
      {[](Cell& c) { c.fingers[1].inertia = -1; }, "fingers[1].inertia must not be negative"},
      {[](Cell& c) { c.object.shape.reset(); }, "object.shape is missing"},
      {[](Cell& c) { c.object.shape = std::make_shared<CircleShape>(0.1, Vec2(0.0, -0.2)); },
       "object.shape.center puts the COM (the object-frame origin) outside the shape"},
      {[](Cell& c) { c.object.mass = 0; }, "object.mass must be positive (got 0)"},
      {[](Cell& c) { c.object.inertia = NAN; }, "object.inertia must be a finite number"},
      {[](Cell& c) { c.friction.mu_static = -0.5; }, "friction.static must not be negative"},
      {[](Cell& c) { c.friction.mu_kinetic = 0.7; },
       "friction.kinetic (0.7) must not exceed friction.static (0.5)"},
  };
  for (const auto& m : muts) {
    Cell c = codeCell();
    m.apply(c);
    EXPECT_EQ(validateError(c).rfind(m.expect, 0), 0u) << validateError(c);
  }
}

}  // namespace
}  // namespace rbsf
