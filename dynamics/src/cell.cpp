/// \file
/// \brief Cell validation and the YAML cell loader (docs/model.md "Files").
///
/// The parser checks structure (known keys, types, finite numbers) and builds a Cell;
/// every range check lives in Cell::validate(), so a cell from a file and one built in
/// code are held to the same rules and get the same messages (key paths as in a file).

#include "rbsf/dynamics/cell.h"

#include <charconv>
#include <cmath>
#include <initializer_list>
#include <set>
#include <string_view>
#include <tuple>

#include <yaml-cpp/yaml.h>

#include "rbsf/dynamics/errors.h"
#include "rbsf/dynamics/input_file.h"
#include "rbsf/dynamics/state_layout.h"
#include "rbsf/dynamics/types.h"
#include "rbsf/dynamics/yaml_reader.h"

namespace rbsf {
namespace {

std::shared_ptr<const Shape> readShape(const YamlReader& rd, const YAML::Node& n) {
  const std::string path = "object.shape";
  if (!n.IsMap()) rd.fail(path + " must be a mapping (got " + YamlReader::describe(n) + ")");
  const YAML::Node t = rd.get(n, path, "type");
  if (!t.IsScalar()) rd.fail(path + ".type must be a name (got " + YamlReader::describe(t) + ")");
  const std::string type = t.Scalar();
  // The shape constructors check their arguments too; name the key path if they object.
  auto build = [&](auto make) -> std::shared_ptr<const Shape> {
    try {
      return make();
    } catch (const InputError& e) {
      rd.fail(path + ": " + e.what());
    }
  };
  auto positive = [&](const char* key) {
    const double v = rd.number(n, path, key);
    rd.positive(v, YamlReader::join(path, key));
    return v;
  };
  if (type == "ellipse") {
    rd.mapping(n, path, {"type", "a", "b", "center"});
    const double a = positive("a"), b = positive("b");
    const auto [cx, cy] = rd.pair(n, path, "center", false);
    const Vec2 center(cx, cy);  // a plain variable: clang 14 cannot capture bindings
    return build([&] { return std::make_shared<EllipseShape>(a, b, center); });
  }
  if (type == "circle") {
    rd.mapping(n, path, {"type", "radius", "center"});
    const double r = positive("radius");
    const auto [cx, cy] = rd.pair(n, path, "center", false);
    const Vec2 center(cx, cy);  // a plain variable: clang 14 cannot capture bindings
    return build([&] { return std::make_shared<CircleShape>(r, center); });
  }
  if (type == "superellipse") {
    rd.mapping(n, path, {"type", "a", "b", "exponent", "center"});
    const double a = positive("a"), b = positive("b");
    const double e = rd.number(n, path, "exponent");
    if (e < 2 || e > 20)
      rd.fail(path + ".exponent must lie in [2, 20] (got " + roundTripText(e) + ")");
    const auto [cx, cy] = rd.pair(n, path, "center", false);
    const Vec2 center(cx, cy);  // a plain variable: clang 14 cannot capture bindings
    return build([&] { return std::make_shared<SuperellipseShape>(a, b, e, center); });
  }
  rd.fail(path + ".type '" + type + "' is unknown (expected ellipse, circle or superellipse)");
}

/// Section `sensing` (sensing.h); keys left out keep the values already in `s`.
void readSensing(const YamlReader& rd, const YAML::Node& n, Sensing& s) {
  rd.mapping(n, "sensing", {"joints", "part_pose"});
  const YAML::Node joints = rd.get(n, "sensing", "joints", false);
  if (joints.IsDefined()) {
    const std::string p = "sensing.joints";
    rd.mapping(joints, p, {"noise"});
    std::tie(s.joints.angle_noise, s.joints.stroke_noise) =
        rd.pair(joints, p, "noise", false, {s.joints.angle_noise, s.joints.stroke_noise});
  }
  const YAML::Node pose = rd.get(n, "sensing", "part_pose", false);
  if (!pose.IsDefined()) return;
  const std::string p = "sensing.part_pose";
  PartPoseSensing& pp = s.part_pose;
  if (pose.IsScalar() && pose.Scalar() == "none") {
    pp.present = false;
    return;
  }
  if (!pose.IsMap())
    rd.fail(p + " must be a mapping or none (got " + YamlReader::describe(pose) + ")");
  rd.mapping(pose, p, {"rate", "latency", "noise"});
  pp.present = true;
  pp.rate = rd.number(pose, p, "rate", pp.rate, false);
  pp.latency = rd.number(pose, p, "latency", pp.latency, false);
  std::tie(pp.position_noise, pp.angle_noise) =
      rd.pair(pose, p, "noise", false, {pp.position_noise, pp.angle_noise});
}

/// Section `uncertainty` (sensing.h); keys left out keep the values already in `u`.
void readUncertainty(const YamlReader& rd, const YAML::Node& n, Uncertainty& u) {
  const std::string p = "uncertainty";
  rd.mapping(n, p,
             {"mass", "inertia", "com", "static_friction", "kinetic_friction", "initial_position",
              "initial_angle", "actuator_gain"});
  u.mass = rd.number(n, p, "mass", u.mass, false);
  u.inertia = rd.number(n, p, "inertia", u.inertia, false);
  u.com = rd.number(n, p, "com", u.com, false);
  u.static_friction = rd.number(n, p, "static_friction", u.static_friction, false);
  std::tie(u.kinetic_friction_min, u.kinetic_friction_max) =
      rd.pair(n, p, "kinetic_friction", false, {u.kinetic_friction_min, u.kinetic_friction_max});
  u.initial_position = rd.number(n, p, "initial_position", u.initial_position, false);
  u.initial_angle = rd.number(n, p, "initial_angle", u.initial_angle, false);
  u.actuator_gain = rd.number(n, p, "actuator_gain", u.actuator_gain, false);
}

/// Section `motion_limits` (motion_limits.h); keys left out keep the values in `l`.
void readMotionLimits(const YamlReader& rd, const YAML::Node& n, MotionLimits& l) {
  const std::string p = "motion_limits";
  rd.mapping(n, p, {"part_speed", "angular_speed", "rest"});
  l.part_speed = rd.number(n, p, "part_speed", l.part_speed, false);
  l.angular_speed = rd.number(n, p, "angular_speed", l.angular_speed, false);
  std::tie(l.rest_speed, l.rest_angular_speed) =
      rd.pair(n, p, "rest", false, {l.rest_speed, l.rest_angular_speed});
}

}  // namespace

void Cell::validate() const {
  const InputChecker c{messagePrefix(name)};
  c.nonNegative(gravity, "gravity");
  c.nonNegative(base.inertia, "base.inertia");
  c.interval(base.theta_min, base.theta_max, "base.theta_limits");
  // Angles in cell files are radians; a limit beyond half a turn is almost surely degrees.
  if (std::abs(base.theta_min) > M_PI + 1e-3 || std::abs(base.theta_max) > M_PI + 1e-3)
    c.fail("base.theta_limits must lie within [-pi, pi] radians (got [" +
           roundTripText(base.theta_min) + ", " + roundTripText(base.theta_max) + "])");
  c.positive(base.torque_limit, "base.torque_limit");
  if (fingers.empty()) c.fail("fingers must list at least one finger");
  if (numFingers() > kMaxFingers)
    c.fail("fingers lists " + std::to_string(numFingers()) + " fingers; at most " +
           std::to_string(kMaxFingers) + " are supported");
  for (int i = 0; i < numFingers(); ++i) {
    const FingerParams& f = fingers[i];
    const std::string p = "fingers[" + std::to_string(i) + "].";
    c.finite(f.r, p + "r");
    c.interval(f.stroke_min, f.stroke_max, p + "stroke");
    c.positive(f.mass, p + "mass");
    c.positive(f.force_limit, p + "force_limit");
    c.finite(f.com_offset, p + "com_offset");
    c.nonNegative(f.inertia, p + "inertia");
  }
  if (!object.shape) c.fail("object.shape is missing");
  // A body's COM lies inside its convex hull: the origin must be left of every tangent
  // line (by more than 1 nm, so a COM on the boundary is rejected too).
  for (int k = 0; k < 256; ++k) {
    Vec2 p, dp, ddp;
    object.shape->derivatives(2 * M_PI * k / 256, p, dp, ddp);
    if (!(cross(p, dp) > 1e-9 * dp.norm()))
      c.fail("object.shape.center puts the COM (the object-frame origin) outside the shape");
  }
  c.positive(object.mass, "object.mass");
  c.positive(object.inertia, "object.inertia");
  c.nonNegative(friction.mu_static, "friction.static");
  c.nonNegative(friction.mu_kinetic, "friction.kinetic");
  if (friction.mu_kinetic > friction.mu_static)
    c.fail("friction.kinetic (" + roundTripText(friction.mu_kinetic) +
           ") must not exceed friction.static (" + roundTripText(friction.mu_static) + ")");

  // sensing (sensing.h). part_pose is checked even when absent (`none`): its defaults pass.
  c.nonNegative(sensing.joints.angle_noise, "sensing.joints.noise[0]");
  c.nonNegative(sensing.joints.stroke_noise, "sensing.joints.noise[1]");
  const PartPoseSensing& pp = sensing.part_pose;
  c.positive(pp.rate, "sensing.part_pose.rate");
  c.atMost(pp.rate, 10000.0, "10000 Hz", "sensing.part_pose.rate");
  c.nonNegative(pp.latency, "sensing.part_pose.latency");
  c.atMost(pp.latency, 1.0, "1 s", "sensing.part_pose.latency");
  c.nonNegative(pp.position_noise, "sensing.part_pose.noise[0]");
  c.nonNegative(pp.angle_noise, "sensing.part_pose.noise[1]");

  c.positive(motion_limits.part_speed, "motion_limits.part_speed");
  c.positive(motion_limits.angular_speed, "motion_limits.angular_speed");
  c.positive(motion_limits.rest_speed, "motion_limits.rest[0]");
  c.positive(motion_limits.rest_angular_speed, "motion_limits.rest[1]");

  // uncertainty: a draw must keep masses, inertias, friction and gains positive.
  const Uncertainty& u = uncertainty;
  c.fraction(u.mass, "uncertainty.mass");
  c.fraction(u.inertia, "uncertainty.inertia");
  c.fraction(u.static_friction, "uncertainty.static_friction");
  c.fraction(u.actuator_gain, "uncertainty.actuator_gain");
  c.nonNegative(u.com, "uncertainty.com");
  c.atMost(u.com, 0.1, "0.1 m", "uncertainty.com");
  c.nonNegative(u.initial_position, "uncertainty.initial_position");
  c.atMost(u.initial_position, 0.1, "0.1 m", "uncertainty.initial_position");
  c.nonNegative(u.initial_angle, "uncertainty.initial_angle");
  c.atMost(u.initial_angle, M_PI / 4, "pi/4 rad", "uncertainty.initial_angle");
  c.nonNegative(u.kinetic_friction_min, "uncertainty.kinetic_friction[0]");
  c.finite(u.kinetic_friction_max, "uncertainty.kinetic_friction[1]");
  if (!(u.kinetic_friction_min <= u.kinetic_friction_max))
    c.fail("uncertainty.kinetic_friction must be [min, max] with min <= max (got [" +
           roundTripText(u.kinetic_friction_min) + ", " + roundTripText(u.kinetic_friction_max) +
           "])");
}

Cell parseCell(const std::string& yaml_text, const std::string& label) {
  const YamlReader rd{{messagePrefix(label)}};
  const YAML::Node root = rd.load(yaml_text);
  if (root.IsNull()) rd.fail("the cell is empty (expected keys base, fingers, object, friction)");
  rd.mapping(root, "",
             {"gravity", "base", "fingers", "object", "friction", "sensing", "uncertainty",
              "motion_limits"},
             "the cell");

  Cell cell;
  cell.name = label;
  cell.gravity = rd.number(root, "", "gravity", 9.81, false);

  const YAML::Node base = rd.get(root, "", "base");
  rd.mapping(base, "base", {"inertia", "theta_limits", "torque_limit"});
  cell.base.inertia = rd.number(base, "base", "inertia");
  std::tie(cell.base.theta_min, cell.base.theta_max) = rd.pair(base, "base", "theta_limits");
  cell.base.torque_limit = rd.number(base, "base", "torque_limit");

  const YAML::Node fingers = rd.get(root, "", "fingers");
  if (!fingers.IsSequence())
    rd.fail("fingers must be a list of fingers (got " + YamlReader::describe(fingers) + ")");
  for (std::size_t i = 0; i < fingers.size(); ++i) {
    const std::string p = "fingers[" + std::to_string(i) + "]";
    const YAML::Node f = fingers[i];
    rd.mapping(f, p, {"r", "stroke", "mass", "force_limit", "com_offset", "inertia"});
    FingerParams fp;
    fp.r = rd.number(f, p, "r");
    std::tie(fp.stroke_min, fp.stroke_max) = rd.pair(f, p, "stroke");
    fp.mass = rd.number(f, p, "mass");
    fp.force_limit = rd.number(f, p, "force_limit");
    fp.com_offset = rd.number(f, p, "com_offset", 0.0, false);
    fp.inertia = rd.number(f, p, "inertia", 0.0, false);
    cell.fingers.push_back(fp);
  }

  const YAML::Node object = rd.get(root, "", "object");
  rd.mapping(object, "object", {"shape", "mass", "inertia"});
  cell.object.shape = readShape(rd, rd.get(object, "object", "shape"));
  cell.object.mass = rd.number(object, "object", "mass");
  cell.object.inertia = rd.number(object, "object", "inertia");

  const YAML::Node friction = rd.get(root, "", "friction");
  rd.mapping(friction, "friction", {"static", "kinetic"});
  cell.friction.mu_static = rd.number(friction, "friction", "static");
  cell.friction.mu_kinetic = rd.number(friction, "friction", "kinetic", 0.0, false);

  const YAML::Node sensing = rd.get(root, "", "sensing", false);
  if (sensing.IsDefined()) readSensing(rd, sensing, cell.sensing);
  const YAML::Node uncertainty = rd.get(root, "", "uncertainty", false);
  if (uncertainty.IsDefined()) readUncertainty(rd, uncertainty, cell.uncertainty);
  const YAML::Node limits = rd.get(root, "", "motion_limits", false);
  if (limits.IsDefined()) readMotionLimits(rd, limits, cell.motion_limits);

  cell.validate();
  return cell;
}

Cell loadCell(const std::string& path) { return parseCell(readInputFile(path, "cell file"), path); }

double Cell::inputLimit(int j) const {
  return j == layout::kTauTheta ? base.torque_limit : fingers[j - 1].force_limit;
}

}  // namespace rbsf
