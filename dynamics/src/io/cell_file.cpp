/// \file
/// \brief The YAML cell loader (docs/model.md "Files").
///
/// The parser checks structure (known keys, types, finite numbers) and builds a Cell;
/// every range check lives in Cell::validate(), so a cell from a file and one built in
/// code are held to the same rules and get the same messages (key paths as in a file).

#include "rbsf/dynamics/io/cell_file.h"

#include <charconv>
#include <cmath>
#include <initializer_list>
#include <set>
#include <string_view>
#include <tuple>

#include <yaml-cpp/yaml.h>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/dynamics/core/types.h"
#include "rbsf/dynamics/io/input_file.h"
#include "rbsf/dynamics/io/yaml_reader.h"

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

/// Section `faults` (faults.h); keys left out keep the values already in `f`.
void readFaults(const YamlReader& rd, const YAML::Node& n, Faults& f) {
  const std::string p = "faults";
  rd.mapping(n, p, {"pose_dropouts", "joint_spikes", "missed_ticks", "force_cut", "mass_error"});
  if (const YAML::Node d = rd.get(n, p, "pose_dropouts", false); d.IsDefined()) {
    rd.mapping(d, p + ".pose_dropouts", {"rate", "length"});
    f.pose_dropouts.rate = rd.number(d, p + ".pose_dropouts", "rate", f.pose_dropouts.rate, false);
    f.pose_dropouts.length =
        rd.number(d, p + ".pose_dropouts", "length", f.pose_dropouts.length, false);
  }
  if (const YAML::Node s = rd.get(n, p, "joint_spikes", false); s.IsDefined()) {
    const std::string q = p + ".joint_spikes";
    rd.mapping(s, q, {"rate", "size", "nan"});
    f.joint_spikes.rate = rd.number(s, q, "rate", f.joint_spikes.rate, false);
    f.joint_spikes.size = rd.number(s, q, "size", f.joint_spikes.size, false);
    f.joint_spikes.nan_share = rd.number(s, q, "nan", f.joint_spikes.nan_share, false);
  }
  if (const YAML::Node m = rd.get(n, p, "missed_ticks", false); m.IsDefined()) {
    rd.mapping(m, p + ".missed_ticks", {"rate"});
    f.missed_tick_rate = rd.number(m, p + ".missed_ticks", "rate", f.missed_tick_rate, false);
  }
  if (const YAML::Node c = rd.get(n, p, "force_cut", false); c.IsDefined()) {
    rd.mapping(c, p + ".force_cut", {"chance", "to"});
    f.force_cut_chance = rd.number(c, p + ".force_cut", "chance", f.force_cut_chance, false);
    f.force_cut_to = rd.number(c, p + ".force_cut", "to", f.force_cut_to, false);
  }
  f.mass_error = rd.number(n, p, "mass_error", f.mass_error, false);
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

Cell parseCell(const std::string& yaml_text, const std::string& label) {
  const YamlReader rd{{messagePrefix(label)}};
  const YAML::Node root = rd.load(yaml_text);
  if (root.IsNull()) rd.fail("the cell is empty (expected keys base, fingers, object, friction)");
  rd.mapping(root, "",
             {"gravity", "base", "fingers", "object", "friction", "sensing", "uncertainty",
              "motion_limits", "faults"},
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
  const YAML::Node faults = rd.get(root, "", "faults", false);
  if (faults.IsDefined()) readFaults(rd, faults, cell.faults);

  cell.validate();
  return cell;
}

Cell loadCell(const std::string& path) { return parseCell(readInputFile(path, "cell file"), path); }

}  // namespace rbsf
