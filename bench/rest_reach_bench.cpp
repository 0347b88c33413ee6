// What the cell reaches at rest (a program, not a timed test): two independent answers to
// "can the part be turned to world angle phi?", for the decision records.
//   --mode walk: breadth-first over every simple turn of at most --depth pivots from the start
//     at rest, with the simple-turn search's moves and checks (pivot_turn_search.h: pivots'
//     26 lattice neighbours, rigid base steps, switches at rest with at most one slider; every
//     support valid by SupportSearch::stepTo, so the balance, breakaway and the law's own
//     check) but none of its rules of way (a pivot may turn back, a slider may slip under
//     1 mm): a superset of the simple turns on the lattice. Prints the world angles where the
//     part rests after each depth, and the rests within half a lattice step of each --target.
//   --mode rests: the goal alone, every rest at world angle --target on the jig: base angles
//     every 1.25 deg within the limits, positions along the base every 5 mm, every set of two
//     or more sticking fingers, the height where the strokes are mid-range; counts the valid
//     ones (SupportGeometry::check) and gives each set's base-angle range.
//   --mode pivot: one pivot's band: from --from (X,Y,psi,theta in the base frame, degrees), the
//     pivot about finger --pivot with finger --slider sliding (the others lifted), every psi
//     step of 2.5 deg: the base angles (every 1.25 deg) and anchor strokes (every 5 mm) whose
//     support is valid, and the world angles psi + theta they span.
//   build/bench/rbsf_rest_reach_bench [--cell cells/default.yaml] [--friction-use 0.6]
//       [--normal-margin 0.08] [--mode walk] [--depth 1] [--target 82.5] ...
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <map>
#include <string>
#include <unordered_set>
#include <vector>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/planner/support/pivot_turn_search.h"
#include "rbsf/planner/support/support_planner.h"
#include "rbsf/planner/support/support_search.h"
#include "rbsf/tools/cli_values.h"
#include "rbsf/tools/tool_main.h"

namespace {

using rbsf::ContactSet;
using rbsf::planner::JigPose;
using rbsf::planner::PivotAnchor;
using rbsf::planner::SupportStep;

constexpr double kDeg = M_PI / 180.0;
/// The simple turns' lattice (PivotTurnSettings' defaults).
const rbsf::planner::PivotTurnSettings kLattice;
const double kAngleStep = kLattice.angle_step;
const double kStrokeStep = kLattice.stroke_step;
const double kXyStep = kLattice.xy_step;

/// One state of the walk: its support and pivots so far.
struct WalkNode {
  SupportStep step;
  int pivots = 0;
};

/// The walk's lattice cell (as PivotTurnSearch::Run::key).
std::uint64_t cellOf(const WalkNode& n) {
  auto idx = [](double v, double s) {
    return static_cast<std::uint64_t>(std::lround(v / s) + 512) & 1023u;
  };
  const JigPose& p = n.step.pose;
  return idx(p.psi, kAngleStep) | idx(p.theta, kAngleStep) << 10 | idx(p.X, kXyStep) << 20 |
         idx(p.Y, kXyStep) << 30 | static_cast<std::uint64_t>(n.step.set.touching) << 40 |
         static_cast<std::uint64_t>(n.step.set.sticking) << 48 |
         static_cast<std::uint64_t>(n.pivots) << 56;
}

void walk(rbsf::planner::SupportSearch& search, const rbsf::Pose& start, int depth,
          const std::vector<double>& targets) {
  rbsf::planner::SupportGeometry& g = search.geometry();
  const int m = g.model().numFingers();
  const JigPose p0 = JigPose::fromWorld(start, 0.0);
  std::vector<WalkNode> nodes;
  std::unordered_set<std::uint64_t> seen;
  std::deque<int> open;
  auto push = [&](const WalkNode& n) {
    if (!seen.insert(cellOf(n)).second) return;
    nodes.push_back(n);
    open.push_back(static_cast<int>(nodes.size()) - 1);
  };
  for (const ContactSet& set : rbsf::planner::restSetsWithin(g.placedSet(p0).touching, m, 1)) {
    WalkNode n;
    n.pivots = set.pivot() >= 0 ? 1 : 0;
    if (search.restAt(p0, set, n.step)) push(n);
  }
  std::map<int, std::map<long, int>> rests;  // pivots -> world angle index -> rests
  std::map<double, int> printed;
  long expansions = 0;
  while (!open.empty()) {
    const WalkNode cur = nodes[open.front()];
    open.pop_front();
    ++expansions;
    const SupportStep& s = cur.step;
    const double world = s.pose.psi + s.pose.theta;
    if (s.set.stickingCount() == s.set.count() && s.set.count() >= 2) {
      ++rests[cur.pivots][std::lround(world / kAngleStep)];
      for (double t : targets)
        if (std::abs(world - t * kDeg) < 0.5 * kAngleStep && printed[t]++ < 3) {
          const rbsf::Pose w = s.pose.world();
          std::printf(
              "rest at %.2f deg after %d pivots: world (%.4f, %.4f), psi %.2f, base %.2f deg, "
              "fingers %x, margin %.3f\n",
              t, cur.pivots, w.x, w.y, s.pose.psi / kDeg, s.pose.theta / kDeg, s.set.touching,
              s.margin);
        }
    }
    WalkNode next;
    next.pivots = cur.pivots;
    if (s.set.pivot() >= 0) {
      for (int di = -1; di <= 1; ++di)
        for (int dj = -1; dj <= 1; ++dj)
          for (int dl = -1; dl <= 1; ++dl) {
            if (di == 0 && dj == 0 && dl == 0) continue;
            PivotAnchor a = s.anchor;
            a.stroke += dl * kStrokeStep;
            const JigPose pose =
                g.pivotPose(a, s.pose.psi + di * kAngleStep, s.pose.theta + dj * kAngleStep);
            if (search.stepTo(s, pose, s.set, a, next.step)) push(next);
          }
    } else if (s.set.stickingCount() >= 2) {
      for (int dj : {1, -1}) {
        JigPose pose = s.pose;
        pose.theta += dj * kAngleStep;
        if (search.stepTo(s, pose, s.set, PivotAnchor{}, next.step)) push(next);
      }
    }
    for (const ContactSet& set :
         rbsf::planner::restSetsWithin(s.set.touching | g.placedSet(s.pose).touching, m, 1)) {
      if (set == s.set) continue;
      next.pivots = cur.pivots + (set.pivot() >= 0 ? 1 : 0);
      if (next.pivots > depth) continue;
      PivotAnchor a;
      if (search.anchorFor(s.pose, set, a) && search.stepTo(s, s.pose, set, a, next.step))
        push(next);
    }
  }
  std::printf("%ld states expanded (every one within %d pivots)\n", expansions, depth);
  for (const auto& [pivots, angles] : rests) {
    std::printf("after %d pivots, rests at world angles [deg]:", pivots);
    for (const auto& [idx, count] : angles) std::printf(" %.2f", idx * kAngleStep / kDeg);
    std::printf("\n");
  }
}

void restsAt(rbsf::planner::SupportGeometry& g, double phi) {
  const rbsf::Cell& cell = g.model().cell();
  const int m = g.model().numFingers();
  long geometries = 0, valid = 0;
  for (std::uint32_t t = 1; t < (1u << m); ++t) {
    if (ContactSet::bitCount(t) < 2) continue;
    const ContactSet set{t, t};
    double lo_th = 1e9, hi_th = -1e9, best = -1.0;
    for (double th = cell.base.theta_min; th <= cell.base.theta_max + 1e-9; th += 1.25 * kDeg)
      for (double X = -0.45; X <= 0.45 + 1e-9; X += 0.005) {
        JigPose p{X, 0.0, phi - th, th};
        const auto q = g.configuration(p, set, false);
        if (!q) continue;
        double lo = -1e9, hi = 1e9;  // the height's range that keeps the strokes in limits
        for (int i = 0; i < m; ++i)
          if ((t >> i) & 1u) {
            const double l = (*q)[q->size() - m + i];
            lo = std::max(lo, cell.fingers[i].stroke_min + 0.02 - l);
            hi = std::min(hi, cell.fingers[i].stroke_max - 0.02 - l);
          }
        if (lo > hi) continue;
        p.Y = 0.5 * (lo + hi);
        ++geometries;
        const rbsf::planner::Support s = g.check(p, set);
        if (!s.valid) continue;
        ++valid;
        lo_th = std::min(lo_th, th);
        hi_th = std::max(hi_th, th);
        best = std::max(best, s.margin);
      }
    if (best >= 0)
      std::printf("  fingers %x: rests at base angles %.2f..%.2f deg, best margin %.3f\n", t,
                  lo_th / kDeg, hi_th / kDeg, best);
  }
  std::printf("world angle %.2f deg: %ld geometries, %ld valid rests\n", phi / kDeg, geometries,
              valid);
}

void pivotBand(rbsf::planner::SupportSearch& search, const JigPose& from, int k, int slider) {
  rbsf::planner::SupportGeometry& g = search.geometry();
  const rbsf::Cell& cell = g.model().cell();
  const ContactSet set{(1u << k) | (1u << slider), 1u << k};
  PivotAnchor a;
  if (!search.anchorFor(from, set, a)) {
    std::printf("finger %d does not hold the part there\n", k + 1);
    return;
  }
  std::printf("pivot on finger %d (point %.3f rad, stroke %.3f m), finger %d sliding\n", k + 1,
              a.xi, a.stroke, slider + 1);
  for (double psi = from.psi / kDeg - 60.0; psi <= from.psi / kDeg + 60.0 + 1e-9; psi += 2.5) {
    double lo = 1e9, hi = -1e9;
    for (double th = cell.base.theta_min; th <= cell.base.theta_max + 1e-9; th += 1.25 * kDeg)
      for (double l = cell.fingers[k].stroke_min; l <= cell.fingers[k].stroke_max + 1e-9;
           l += 0.005) {
        PivotAnchor b = a;
        b.stroke = l;
        if (!g.check(g.pivotPose(b, psi * kDeg, th), set).valid) continue;
        lo = std::min(lo, th);
        hi = std::max(hi, th);
      }
    if (lo <= hi)
      std::printf("  psi %6.2f deg (X %+.4f m): base %.2f..%.2f deg, world %.2f..%.2f deg\n", psi,
                  g.pivotPose(a, psi * kDeg, 0.0).X, lo / kDeg, hi / kDeg, psi + lo / kDeg,
                  psi + hi / kDeg);
  }
}

int run(int argc, char** argv) {
  std::string cell_path = std::string(RBSF_SOURCE_DIR) + "/cells/default.yaml";
  std::string mode = "walk", start_text = "0.1,0.40,0", from_text = "0,0.4,0,0";
  std::vector<double> targets;
  int depth = 1, pivot = 3, slider = 1;
  rbsf::planner::SupportSearchSettings ss = rbsf::planner::SupportPlannerSettings::defaultSearch();
  ss.support.balance.friction_use = 0.6;
  CLI::App app{
      "What the cell reaches at rest: a walk over simple turns, the rests at a world "
      "angle, or one pivot's band.",
      "rbsf_rest_reach_bench"};
  app.footer(rbsf::tools::kExitStatusHelp);
  app.add_option("--cell", cell_path, "cell file (default cells/default.yaml)");
  app.add_option("--mode", mode, "walk, rests or pivot (default walk)")
      ->check(CLI::IsMember({"walk", "rests", "pivot"}));
  app.add_option("--friction-use", ss.support.balance.friction_use,
                 "the supports' friction use (default 0.6)")
      ->check(CLI::Range(0.05, 1.0));
  app.add_option("--normal-margin", ss.support.balance.normal_margin,
                 "the supports' normal-force floor, times the weight (default 0.08)")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--depth", depth, "walk: pivots at most (default 1)")->check(CLI::Range(0, 4));
  app.add_option("--target", targets, "world angles [deg] (walk: rests printed; rests: scanned)");
  app.add_option("--start", start_text, "walk: the start x,y,phi (default 0.1,0.40,0)");
  app.add_option("--from", from_text, "pivot: X,Y,psi,theta in the base frame [m, m, deg, deg]");
  app.add_option("--pivot", pivot, "pivot: the sticking finger, 1-based (default 3)")
      ->check(CLI::Range(1, 8));
  app.add_option("--slider", slider, "pivot: the sliding finger, 1-based (default 1)")
      ->check(CLI::Range(1, 8));
  rbsf::tools::parseCommandLine(app, argc, argv);

  const rbsf::RbsfModel model(rbsf::loadCell(cell_path));
  ss.time_limit = INFINITY;
  rbsf::planner::SupportSearch search(model, ss);
  std::printf("friction use %.2f, normal margin %.3f\n", ss.support.balance.friction_use,
              ss.support.balance.normal_margin);
  if (mode == "walk") {
    walk(search, rbsf::tools::parsePose(start_text, "--start"), depth, targets);
  } else if (mode == "rests") {
    for (double t : targets) restsAt(search.geometry(), t * kDeg);
  } else {
    const std::vector<double> f = rbsf::tools::parseVector(from_text, "--from", 4, "X,Y,psi,theta");
    if (pivot > model.numFingers() || slider > model.numFingers() || pivot == slider)
      throw rbsf::InputError("--pivot and --slider: two different fingers of the cell");
    pivotBand(search, JigPose{f[0], f[1], f[2] * kDeg, f[3] * kDeg}, pivot - 1, slider - 1);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return rbsf::tools::toolMain("rbsf_rest_reach_bench", argc, argv, run);
}
