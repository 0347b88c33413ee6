// Cell loading (docs/model.md "Files"): the example cells, every rejected input with a message
// naming the key path, defaults, and Cell::validate() on cells built in code.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "rbsf/dynamics/core/cell.h"
#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/io/cell_file.h"

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
// Sections sensing and uncertainty (sensing.h).

void expectSensingEq(const Sensing& a, const Sensing& b) {
  EXPECT_DOUBLE_EQ(a.joints.angle_noise, b.joints.angle_noise);
  EXPECT_DOUBLE_EQ(a.joints.stroke_noise, b.joints.stroke_noise);
  EXPECT_EQ(a.part_pose.present, b.part_pose.present);
  EXPECT_DOUBLE_EQ(a.part_pose.rate, b.part_pose.rate);
  EXPECT_DOUBLE_EQ(a.part_pose.latency, b.part_pose.latency);
  EXPECT_DOUBLE_EQ(a.part_pose.position_noise, b.part_pose.position_noise);
  EXPECT_DOUBLE_EQ(a.part_pose.angle_noise, b.part_pose.angle_noise);
}

void expectUncertaintyEq(const Uncertainty& a, const Uncertainty& b) {
  EXPECT_DOUBLE_EQ(a.mass, b.mass);
  EXPECT_DOUBLE_EQ(a.inertia, b.inertia);
  EXPECT_DOUBLE_EQ(a.com, b.com);
  EXPECT_DOUBLE_EQ(a.static_friction, b.static_friction);
  EXPECT_DOUBLE_EQ(a.kinetic_friction_min, b.kinetic_friction_min);
  EXPECT_DOUBLE_EQ(a.kinetic_friction_max, b.kinetic_friction_max);
  EXPECT_DOUBLE_EQ(a.initial_position, b.initial_position);
  EXPECT_DOUBLE_EQ(a.initial_angle, b.initial_angle);
  EXPECT_DOUBLE_EQ(a.actuator_gain, b.actuator_gain);
}

TEST(CellLoader, AbsentSensingAndUncertaintyTakeTheDefaults) {
  for (const std::string& extra : {std::string(""), std::string("sensing: {}\nuncertainty: {}\n"),
                                   std::string("sensing: {joints: {}, part_pose: {}}\n")}) {
    SCOPED_TRACE(extra);
    const Cell c = parseCell(goodYaml() + extra);
    expectSensingEq(c.sensing, Sensing{});
    expectUncertaintyEq(c.uncertainty, Uncertainty{});
  }
  // The documented defaults (sensing.h), so a changed default is a deliberate change.
  const Cell c = parseCell(goodYaml());
  EXPECT_TRUE(c.sensing.part_pose.present);
  EXPECT_DOUBLE_EQ(c.sensing.part_pose.rate, 100.0);
  EXPECT_DOUBLE_EQ(c.sensing.part_pose.latency, 0.01);
  EXPECT_DOUBLE_EQ(c.uncertainty.kinetic_friction_max, 0.05);
}

TEST(CellLoader, EverySensingAndUncertaintyKeyIsRead) {
  const Cell c = parseCell(goodYaml() +
                           "sensing:\n"
                           "  joints: {noise: [2.0e-4, 3.0e-5]}\n"
                           "  part_pose: {rate: 250, latency: 0.04, noise: [0.002, 0.01]}\n"
                           "uncertainty:\n"
                           "  mass: 0.25\n"
                           "  inertia: 0.3\n"
                           "  com: 0.004\n"
                           "  static_friction: 0.35\n"
                           "  kinetic_friction: [0.02, 0.08]\n"
                           "  initial_position: 0.003\n"
                           "  initial_angle: 0.02\n"
                           "  actuator_gain: 0.07\n");
  const Sensing& s = c.sensing;
  EXPECT_DOUBLE_EQ(s.joints.angle_noise, 2.0e-4);
  EXPECT_DOUBLE_EQ(s.joints.stroke_noise, 3.0e-5);
  EXPECT_TRUE(s.part_pose.present);
  EXPECT_DOUBLE_EQ(s.part_pose.rate, 250.0);
  EXPECT_DOUBLE_EQ(s.part_pose.latency, 0.04);
  EXPECT_DOUBLE_EQ(s.part_pose.position_noise, 0.002);
  EXPECT_DOUBLE_EQ(s.part_pose.angle_noise, 0.01);
  const Uncertainty& u = c.uncertainty;
  EXPECT_DOUBLE_EQ(u.mass, 0.25);
  EXPECT_DOUBLE_EQ(u.inertia, 0.3);
  EXPECT_DOUBLE_EQ(u.com, 0.004);
  EXPECT_DOUBLE_EQ(u.static_friction, 0.35);
  EXPECT_DOUBLE_EQ(u.kinetic_friction_min, 0.02);
  EXPECT_DOUBLE_EQ(u.kinetic_friction_max, 0.08);
  EXPECT_DOUBLE_EQ(u.initial_position, 0.003);
  EXPECT_DOUBLE_EQ(u.initial_angle, 0.02);
  EXPECT_DOUBLE_EQ(u.actuator_gain, 0.07);
}

TEST(CellLoader, MotionLimitsAreReadAndDefaultToTheDocumentedValues) {
  const MotionLimits d = parseCell(goodYaml()).motion_limits;
  EXPECT_DOUBLE_EQ(d.part_speed, 0.25);  // motion_limits.h
  EXPECT_DOUBLE_EQ(d.angular_speed, 1.0);
  EXPECT_DOUBLE_EQ(d.rest_speed, 1e-3);
  EXPECT_DOUBLE_EQ(d.rest_angular_speed, 1e-3);
  const MotionLimits l =
      parseCell(goodYaml() + "motion_limits: {part_speed: 0.1, rest: [0.002, 0.003]}\n")
          .motion_limits;
  EXPECT_DOUBLE_EQ(l.part_speed, 0.1);
  EXPECT_DOUBLE_EQ(l.angular_speed, d.angular_speed);
  EXPECT_DOUBLE_EQ(l.rest_speed, 0.002);
  EXPECT_DOUBLE_EQ(l.rest_angular_speed, 0.003);
}

TEST(CellLoader, OmittedKeysInsideASectionKeepTheirDefaults) {
  const Cell c = parseCell(goodYaml() +
                           "sensing: {part_pose: {latency: 0.05}}\n"
                           "uncertainty: {com: 0.01}\n");
  const Sensing d;
  EXPECT_DOUBLE_EQ(c.sensing.part_pose.latency, 0.05);
  EXPECT_DOUBLE_EQ(c.sensing.part_pose.rate, d.part_pose.rate);
  EXPECT_DOUBLE_EQ(c.sensing.part_pose.position_noise, d.part_pose.position_noise);
  EXPECT_DOUBLE_EQ(c.sensing.part_pose.angle_noise, d.part_pose.angle_noise);
  EXPECT_DOUBLE_EQ(c.sensing.joints.angle_noise, d.joints.angle_noise);
  Uncertainty expected;
  expected.com = 0.01;
  expectUncertaintyEq(c.uncertainty, expected);
}

TEST(CellLoader, PartPoseNoneMeansOnlyTheJointsAreSensed) {
  const Cell c = parseCell(goodYaml() + "sensing:\n  joints: {noise: [0, 0]}\n  part_pose: none\n");
  EXPECT_FALSE(c.sensing.part_pose.present);
  EXPECT_DOUBLE_EQ(c.sensing.joints.angle_noise, 0.0);  // noise-free encoders are allowed
  EXPECT_DOUBLE_EQ(c.sensing.joints.stroke_noise, 0.0);
  EXPECT_NO_THROW(c.validate());
}

TEST(CellLoader, TheFaultsSectionIsReadKeyByKeyAndAbsentMeansNone) {
  EXPECT_FALSE(parseCell(goodYaml()).faults.any());
  const Cell c = parseCell(goodYaml() +
                           "faults:\n  pose_dropouts: {rate: 0.5}\n"
                           "  joint_spikes: {rate: 2, size: 0.002, nan: 1}\n"
                           "  missed_ticks: {rate: 5}\n  force_cut: {chance: 0.25, to: 0.5}\n"
                           "  mass_error: 0.1\n");
  const Faults& f = c.faults;
  EXPECT_DOUBLE_EQ(f.pose_dropouts.rate, 0.5);
  EXPECT_DOUBLE_EQ(f.pose_dropouts.length, Faults{}.pose_dropouts.length);  // its default
  EXPECT_DOUBLE_EQ(f.joint_spikes.size, 0.002);
  EXPECT_DOUBLE_EQ(f.joint_spikes.nan_share, 1.0);
  EXPECT_DOUBLE_EQ(f.missed_tick_rate, 5.0);
  EXPECT_DOUBLE_EQ(f.force_cut_chance, 0.25);
  EXPECT_DOUBLE_EQ(f.force_cut_to, 0.5);
  EXPECT_DOUBLE_EQ(f.mass_error, 0.1);
  EXPECT_TRUE(f.any());
  EXPECT_TRUE(loadCell(std::string(RBSF_SOURCE_DIR) + "/cells/default_faults.yaml").faults.any());
}

TEST(CellLoader, BoundaryValuesOfSensingAndUncertaintyAreAccepted) {
  const Cell c = parseCell(goodYaml() +
                           "sensing: {part_pose: {rate: 10000, latency: 1, noise: [0, 0]}}\n"
                           "uncertainty: {mass: 0, inertia: 0.999, com: 0.1, static_friction: 0,\n"
                           "  kinetic_friction: [0.1, 0.1], initial_position: 0.1,\n"
                           "  initial_angle: 0.7853981633974483, actuator_gain: 0}\n");
  EXPECT_DOUBLE_EQ(c.sensing.part_pose.rate, 10000.0);
  EXPECT_DOUBLE_EQ(c.uncertainty.kinetic_friction_min, 0.1);  // min == max is allowed
  EXPECT_DOUBLE_EQ(c.uncertainty.kinetic_friction_max, 0.1);
  EXPECT_DOUBLE_EQ(c.uncertainty.initial_angle, M_PI / 4);
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
      // sensing
      {"UnknownSensingKey",
       goodYaml() + "sensing: {camera: {rate: 10}}\n",
       {"unknown key sensing.camera (expected one of: joints, part_pose)"}},
      {"UnknownJointsKey",
       goodYaml() + "sensing: {joints: {nois: [0, 0]}}\n",
       {"unknown key sensing.joints.nois (expected one of: noise)"}},
      {"UnknownPartPoseKey",
       goodYaml() + "sensing: {part_pose: {delay: 0.01}}\n",
       {"unknown key sensing.part_pose.delay (expected one of: rate, latency, noise)"}},
      {"SensingNotAMapping",
       goodYaml() + "sensing: none\n",
       {"sensing must be a mapping (got 'none')"}},
      {"JointsNotAMapping",
       goodYaml() + "sensing: {joints: [0, 0]}\n",
       {"sensing.joints must be a mapping (got a list)"}},
      {"PartPoseSometimes",
       goodYaml() + "sensing: {part_pose: sometimes}\n",
       {"sensing.part_pose must be a mapping or none (got 'sometimes')"}},
      {"PartPoseEmpty",
       goodYaml() + "sensing:\n  part_pose:\n",
       {"sensing.part_pose must be a mapping or none (got an empty value)"}},
      {"NegativeJointNoise",
       goodYaml() + "sensing: {joints: {noise: [1.0e-5, -0.5]}}\n",
       {"sensing.joints.noise[1] must not be negative (got -0.5)"}},
      {"NegativePartPoseNoise",
       goodYaml() + "sensing: {part_pose: {noise: [-0.001, 0.005]}}\n",
       {"sensing.part_pose.noise[0] must not be negative (got -0.001)"}},
      {"PartPoseNoiseThreeEntries",
       goodYaml() + "sensing: {part_pose: {noise: [0.001, 0.002, 0.003]}}\n",
       {"sensing.part_pose.noise must be a list of 2 numbers (got 3 entries)"}},
      {"JointNoiseThreeEntries",
       goodYaml() + "sensing: {joints: {noise: [1, 2, 3]}}\n",
       {"sensing.joints.noise must be a list of 2 numbers (got 3 entries)"}},
      {"JointNoiseNotNumber",
       goodYaml() + "sensing: {joints: {noise: [small, 0]}}\n",
       {"sensing.joints.noise[0] must be a number (got 'small')"}},
      {"ZeroRate",
       goodYaml() + "sensing: {part_pose: {rate: 0}}\n",
       {"sensing.part_pose.rate must be positive (got 0)"}},
      {"RateTooHigh",
       goodYaml() + "sensing: {part_pose: {rate: 20000}}\n",
       {"sensing.part_pose.rate must be at most 10000 Hz (got 20000)"}},
      {"RateNotNumber",
       goodYaml() + "sensing: {part_pose: {rate: fast}}\n",
       {"sensing.part_pose.rate must be a number (got 'fast')"}},
      {"LatencyTooLong",
       goodYaml() + "sensing: {part_pose: {latency: 2}}\n",
       {"sensing.part_pose.latency must be at most 1 s (got 2)"}},
      {"NegativeLatency",
       goodYaml() + "sensing: {part_pose: {latency: -0.01}}\n",
       {"sensing.part_pose.latency must not be negative (got -0.01)"}},
      // uncertainty
      {"UnknownUncertaintyKey",
       goodYaml() + "uncertainty: {friction: 0.1}\n",
       {"unknown key uncertainty.friction (expected one of: mass, inertia, com, static_friction, "
        "kinetic_friction, initial_position, initial_angle, actuator_gain)"}},
      {"UnknownFaultKey",
       goodYaml() + "faults: {dropouts: {rate: 1}}\n",
       {"unknown key faults.dropouts (expected one of: pose_dropouts, joint_spikes, missed_ticks, "
        "force_cut, mass_error)"}},
      {"NegativeDropoutRate",
       goodYaml() + "faults: {pose_dropouts: {rate: -1}}\n",
       {"faults.pose_dropouts.rate must not be negative (got -1)"}},
      {"SpikeNanShareAboveOne",
       goodYaml() + "faults: {joint_spikes: {rate: 2, nan: 1.5}}\n",
       {"faults.joint_spikes.nan must be at most 1 (got 1.5)"}},
      {"UnknownForceCutKey",
       goodYaml() + "faults: {force_cut: {probability: 1}}\n",
       {"unknown key faults.force_cut.probability (expected one of: chance, to)"}},
      {"MassErrorOne",
       goodYaml() + "faults: {mass_error: 1.0}\n",
       {"faults.mass_error must lie in [0, 1) (got 1)"}},
      {"UncertaintyNotAMapping",
       goodYaml() + "uncertainty: 0.05\n",
       {"uncertainty must be a mapping (got '0.05')"}},
      {"MassUncertaintyOne",
       goodYaml() + "uncertainty: {mass: 1.0}\n",
       {"uncertainty.mass must lie in [0, 1) (got 1)"}},
      {"InertiaUncertaintyNegative",
       goodYaml() + "uncertainty: {inertia: -0.1}\n",
       {"uncertainty.inertia must lie in [0, 1) (got -0.1)"}},
      {"StaticFrictionUncertaintyTooLarge",
       goodYaml() + "uncertainty: {static_friction: 1.5}\n",
       {"uncertainty.static_friction must lie in [0, 1) (got 1.5)"}},
      {"ActuatorGainUncertaintyTooLarge",
       goodYaml() + "uncertainty: {actuator_gain: 2}\n",
       {"uncertainty.actuator_gain must lie in [0, 1) (got 2)"}},
      {"ComUncertaintyTooLarge",
       goodYaml() + "uncertainty: {com: 0.5}\n",
       {"uncertainty.com must be at most 0.1 m (got 0.5)"}},
      {"NegativeComUncertainty",
       goodYaml() + "uncertainty: {com: -0.001}\n",
       {"uncertainty.com must not be negative (got -0.001)"}},
      {"InitialPositionTooLarge",
       goodYaml() + "uncertainty: {initial_position: 0.2}\n",
       {"uncertainty.initial_position must be at most 0.1 m (got 0.2)"}},
      {"InitialAngleTooLarge",
       goodYaml() + "uncertainty: {initial_angle: 1.0}\n",
       {"uncertainty.initial_angle must be at most pi/4 rad (got 1)"}},
      {"NegativeInitialAngle",
       goodYaml() + "uncertainty: {initial_angle: -0.01}\n",
       {"uncertainty.initial_angle must not be negative (got -0.01)"}},
      {"KineticFrictionReversed",
       goodYaml() + "uncertainty: {kinetic_friction: [0.1, 0.05]}\n",
       {"uncertainty.kinetic_friction must be [min, max] with min <= max (got [0.1, 0.05])"}},
      {"KineticFrictionNegative",
       goodYaml() + "uncertainty: {kinetic_friction: [-0.1, 0.05]}\n",
       {"uncertainty.kinetic_friction[0] must not be negative (got -0.1)"}},
      {"KineticFrictionNotNumber",
       goodYaml() + "uncertainty: {kinetic_friction: [low, 0.05]}\n",
       {"uncertainty.kinetic_friction[0] must be a number (got 'low')"}},
      // motion_limits
      {"UnknownMotionLimitKey",
       goodYaml() + "motion_limits: {speed: 0.1}\n",
       {"unknown key motion_limits.speed (expected one of: part_speed, angular_speed, rest)"}},
      {"ZeroPartSpeed",
       goodYaml() + "motion_limits: {part_speed: 0}\n",
       {"motion_limits.part_speed must be positive (got 0)"}},
      {"NegativeAngularSpeed",
       goodYaml() + "motion_limits: {angular_speed: -1}\n",
       {"motion_limits.angular_speed must be positive (got -1)"}},
      {"RestNotAPair",
       goodYaml() + "motion_limits: {rest: 0.001}\n",
       {"motion_limits.rest must be a list of 2 numbers"}},
      {"ZeroRestAngularSpeed",
       goodYaml() + "motion_limits: {rest: [0.001, 0]}\n",
       {"motion_limits.rest[1] must be positive (got 0)"}},
      {"KineticFrictionScalar",
       goodYaml() + "uncertainty: {kinetic_friction: 0.05}\n",
       {"uncertainty.kinetic_friction must be a list of 2 numbers (got '0.05')"}},
      {"DuplicateUncertaintyKey",
       goodYaml() + "uncertainty:\n  mass: 0.1\n  mass: 0.2\n",
       {"duplicate key uncertainty.mass"}},
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
    EXPECT_EQ(msg.rfind(path + ": cannot read the cell file", 0), 0u) << msg;
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
      {[](Cell& c) { c.sensing.joints.angle_noise = NAN; },
       "sensing.joints.noise[0] must be a finite number (got nan)"},
      {[](Cell& c) { c.sensing.joints.stroke_noise = -1; },
       "sensing.joints.noise[1] must not be negative (got -1)"},
      {[](Cell& c) { c.sensing.part_pose.rate = -5; },
       "sensing.part_pose.rate must be positive (got -5)"},
      {[](Cell& c) { c.sensing.part_pose.rate = INFINITY; },
       "sensing.part_pose.rate must be a finite number (got inf)"},
      {[](Cell& c) { c.sensing.part_pose.rate = 20000; },
       "sensing.part_pose.rate must be at most 10000 Hz (got 20000)"},
      {[](Cell& c) { c.sensing.part_pose.latency = 1.5; },
       "sensing.part_pose.latency must be at most 1 s (got 1.5)"},
      {[](Cell& c) {  // checked even without a part-pose sensor
         c.sensing.part_pose.present = false;
         c.sensing.part_pose.latency = -1;
       },
       "sensing.part_pose.latency must not be negative (got -1)"},
      {[](Cell& c) { c.sensing.part_pose.position_noise = -1; },
       "sensing.part_pose.noise[0] must not be negative"},
      {[](Cell& c) { c.sensing.part_pose.angle_noise = NAN; },
       "sensing.part_pose.noise[1] must be a finite number"},
      {[](Cell& c) { c.uncertainty.mass = 1.5; }, "uncertainty.mass must lie in [0, 1) (got 1.5)"},
      {[](Cell& c) { c.uncertainty.inertia = 1; },
       "uncertainty.inertia must lie in [0, 1) (got 1)"},
      {[](Cell& c) { c.uncertainty.static_friction = NAN; },
       "uncertainty.static_friction must be a finite number"},
      {[](Cell& c) { c.uncertainty.actuator_gain = -0.1; },
       "uncertainty.actuator_gain must lie in [0, 1) (got -0.1)"},
      {[](Cell& c) { c.uncertainty.com = 0.2; }, "uncertainty.com must be at most 0.1 m (got 0.2)"},
      {[](Cell& c) { c.uncertainty.initial_position = -1e-3; },
       "uncertainty.initial_position must not be negative"},
      {[](Cell& c) { c.uncertainty.initial_angle = M_PI / 2; },
       "uncertainty.initial_angle must be at most pi/4 rad"},
      {[](Cell& c) { c.uncertainty.kinetic_friction_max = INFINITY; },
       "uncertainty.kinetic_friction[1] must be a finite number (got inf)"},
      {[](Cell& c) { c.uncertainty.kinetic_friction_min = 0.1; },
       "uncertainty.kinetic_friction must be [min, max] with min <= max (got [0.1, 0.05])"},
  };
  for (const auto& m : muts) {
    Cell c = codeCell();
    m.apply(c);
    EXPECT_EQ(validateError(c).rfind(m.expect, 0), 0u) << validateError(c);
  }
}

}  // namespace
}  // namespace rbsf
