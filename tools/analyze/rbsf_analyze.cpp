// rbsf-analyze: the model's view of one state of a cell (kinematics, phase-U LCP, phase
// classification, conditions for turning the part, static holding).
//
// Exit status: 0 success, 2 bad input (cell, option value, finger off the boundary, a
// tau beyond the cell's limits, a state whose analysis is not finite), 1 internal error.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/core/placement.h"
#include "rbsf/dynamics/core/state_analysis.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/tools/cli_values.h"
#include "rbsf/tools/tool_main.h"

namespace rbsf::tools {
namespace {

struct Options {
  std::string cell, q, pose, theta = "0", v, tau;
  bool json = false;
};

nlohmann::json toJson(const VecQ& q, const StateAnalysis& a) {
  using nlohmann::json;
  json contacts = json::array();
  for (const ContactReport& c : a.contacts) {
    contacts.push_back({{"xi", c.xi},
                        {"gap", c.gap},
                        {"normal", {c.normal.x(), c.normal.y()}},
                        {"f_n", c.f_n},
                        {"delta_n", c.delta_n},
                        {"alpha_t", c.arms.alpha_t},
                        {"alpha_n", c.arms.alpha_n}});
  }
  json signs = json::array();
  if (a.omega_dot.positive) signs.push_back("+");
  if (a.omega_dot.negative) signs.push_back("-");
  json regions = json::array();
  for (const auto& [i, j] : a.com_regions) regions.push_back({i + 1, j + 1});
  const StickSolution& s = a.phase.stick;
  const bool sticks = a.phase.phase == Phase::kC || a.phase.phase == Phase::kP;
  json out = {
      {"q", vectorJson(q)},
      {"contacts", contacts},
      {"accel", vectorJson(a.accel)},
      {"sigma_min", a.sigma_min},
      {"determinate", a.determinate},
      {"phase_c_feasible", a.phase_c_feasible},
      {"omega_dot_signs", signs},
      {"omega_dot_range",
       a.omega_dot.feasible ? json{a.omega_dot.min, a.omega_dot.max} : json(nullptr)},
      {"com_between_normals", regions},
      {"com_in_end_region", a.com_in_end_region},
      {"holding_tau", a.holding.feasible ? vectorJson(a.holding.tau) : json(nullptr)},
      {"phase", std::string(toString(a.phase.phase))},
      {"phase_accel", sticks ? vectorJson(s.vdot) : vectorJson(a.accel)},
  };
  return out;
}

void printTable(const StateAnalysis& a, const RbsfModel& model) {
  std::printf("contacts (world frame, phase-U LCP forces)\n");
  std::printf("  %-3s %10s %11s %17s %11s %12s %10s %10s\n", "#", "xi", "gap[m]", "normal",
              "f_n[N]", "delta_n", "alpha_t", "alpha_n");
  for (size_t i = 0; i < a.contacts.size(); ++i) {
    const ContactReport& c = a.contacts[i];
    std::printf("  %-3zu %10.5f %11.3e  (%6.3f,%6.3f) %11.4f %12.4e %10.5f %10.5f\n", i + 1, c.xi,
                c.gap, c.normal.x(), c.normal.y(), c.f_n, c.delta_n, c.arms.alpha_t,
                c.arms.alpha_n);
  }
  std::printf("accelerations (phase U, order x y phi theta l1..l%d)\n ", model.numFingers());
  for (int k = 0; k < a.accel.size(); ++k) std::printf(" %.6g", a.accel[k]);
  std::printf("\nsigma_min(G1)        %.6g (%s)\n", a.sigma_min,
              a.determinate ? "determinate" : "NOT determinate");
  std::printf("phase                %s\n", std::string(toString(a.phase.phase)).c_str());
  std::printf("phase C feasible     %s\n", a.phase_c_feasible ? "yes" : "no");
  if (a.omega_dot.feasible) {
    std::printf("omega_o' range       [%.6g, %.6g] rad/s^2, signs:%s%s\n", a.omega_dot.min,
                a.omega_dot.max, a.omega_dot.positive ? " +" : "",
                a.omega_dot.negative ? " -" : "");
  } else {
    std::printf("omega_o' range       none: no tau within limits keeps every contact closed\n");
  }
  std::printf("COM between normals  ");
  if (a.com_regions.empty()) std::printf("no pair");
  for (const auto& [i, j] : a.com_regions) std::printf("(%d,%d) ", i + 1, j + 1);
  std::printf("%s\n", a.com_in_end_region ? " [end fingers]" : "");
  if (a.holding.feasible) {
    std::printf("holding tau         ");
    for (int k = 0; k < a.holding.tau.size(); ++k) std::printf(" %.6g", a.holding.tau[k]);
    std::printf("\n");
  } else {
    std::printf("holding tau          none: the part cannot be held at rest within limits\n");
  }
}

int run(int argc, char** argv) {
  CLI::App app{
      "The RBSF model's analysis of one state: contacts, phase-U LCP, phase, "
      "conditions for turning the part (paper 3), static holding. SI units; angles "
      "in radians or with a deg suffix.",
      "rbsf-analyze"};
  app.footer(kExitStatusHelp);
  Options o;
  app.add_option("--cell", o.cell, "cell YAML file")->required();
  auto* q_opt = app.add_option("--q", o.q, "configuration x,y,phi,theta,l1,...,lm");
  auto* pose_opt = app.add_option("--pose", o.pose, "object pose x,y,phi; fingers placed");
  app.add_option("--theta", o.theta, "base angle with --pose (default 0)")->needs(pose_opt);
  app.add_option("--v", o.v, "velocity, order of q (default 0)");
  app.add_option("--tau", o.tau, "input tau_theta,tau_1,...,tau_m (default 0)");
  app.add_flag("--json", o.json, "print one JSON object");
  q_opt->excludes(pose_opt);
  parseCommandLine(app, argc, argv);
  if (o.q.empty() && o.pose.empty()) throw InputError("one of --q or --pose is required");

  const RbsfModel model(loadCell(o.cell));
  const int m = model.numFingers();
  VecQ q;
  if (!o.q.empty()) {
    q = parseConfig(o.q, "--q", m);
  } else {
    q = restingConfiguration(model, parsePose(o.pose, "--pose"), parseAngle(o.theta, "--theta"));
  }
  const VecQ v = o.v.empty() ? VecQ(VecQ::Zero(m + 4)) : parseVelocity(o.v, "--v", m);
  const VecU tau =
      o.tau.empty() ? VecU(VecU::Zero(m + 1))
                    : VecU(Eigen::Map<const Eigen::VectorXd>(
                          parseVector(o.tau, "--tau", m + 1, "tau_theta,tau_1..").data(), m + 1));
  checkInputLimits(model.cell(), tau, "--tau: ");
  const StateAnalysis a = analyzeState(model, q, v, tau);
  const nlohmann::json j = toJson(q, a);
  if (!allFinite(j))  // e.g. a state so far off that the model's quantities overflow
    throw InputError(std::string(o.q.empty() ? "--pose" : "--q") +
                     "/--v: the model gives "
                     "non-finite values at this state (is it physical?)");
  if (o.json) {
    std::cout << j.dump(2) << "\n";
  } else {
    printTable(a, model);
  }
  return 0;
}

}  // namespace
}  // namespace rbsf::tools

int main(int argc, char** argv) {
  return rbsf::tools::toolMain("rbsf-analyze", argc, argv, rbsf::tools::run);
}
