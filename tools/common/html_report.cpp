/// \file
/// \brief The HTML report page (see html_report.h).

#include "rbsf/tools/html_report.h"

#include <algorithm>
#include <cmath>

#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/tools/svg_format.h"
#include "rbsf/tools/svg_time_plot.h"

namespace rbsf::tools {
namespace {

constexpr const char* kPalette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728",
                                    "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
                                    "#bcbd22", "#17becf", "#393b79", "#637939"};

const char* color(int i) { return kPalette[i % 12]; }

}  // namespace

HtmlReport::HtmlReport(const RbsfModel& model, std::vector<TrajectorySample> frames,
                       SvgAnimationOptions animation,
                       std::vector<std::pair<std::string, std::string>> summary,
                       ReportVerdict verdict)
    : model_(model),
      frames_(std::move(frames)),
      animation_(std::move(animation)),
      summary_(std::move(summary)),
      verdict_(std::move(verdict)) {
  // Validates the frames (sizes, time order) before anything is drawn.
  SvgAnimation check(model_, frames_, animation_);
}

std::string HtmlReport::plots() const {
  const int m = model_.numFingers();
  std::vector<double> t;
  std::vector<Phase> phases;
  for (const TrajectorySample& f : frames_) t.push_back(f.t), phases.push_back(f.phase);
  auto series = [&](const std::string& name, int c, auto value) {
    PlotSeries s{name, color(c), {}};
    for (const TrajectorySample& f : frames_) s.values.push_back(value(f));
    return s;
  };
  constexpr double kDeg = 180.0 / M_PI;
  SvgTimePlot angles("Angles", "deg", t, phases);
  angles.add(series("phi (part)", 0, [&](const auto& f) { return f.q[layout::kPhi] * kDeg; }));
  angles.add(series("theta (base)", 1, [&](const auto& f) { return f.q[layout::kTheta] * kDeg; }));
  if (animation_.goal) {
    // The goal angle as the turn nearest the part's last angle (goals compare modulo 360).
    const double last = frames_.back().q[layout::kPhi];
    const double goal =
        animation_.goal->phi + 2 * M_PI * std::round((last - animation_.goal->phi) / (2 * M_PI));
    const double tol = animation_.angle_tolerance;
    angles.addReference({"goal phi +- " + fixedNumber(tol * kDeg, 1) + " deg", "#1e8449",
                         (goal - tol) * kDeg, (goal + tol) * kDeg});
  }
  SvgTimePlot strokes("Finger strokes", "m", t, phases);
  SvgTimePlot base("Base torque", "N m", t, phases);
  SvgTimePlot fingers("Finger forces tau_i", "N", t, phases);
  const Cell& cell = model_.cell();
  auto limits = [](SvgTimePlot& plot, double limit, const std::string& what) {
    plot.addReference({what + " +" + fixedNumber(limit, 0), "#c0392b", limit, limit});
    plot.addReference({what + " -" + fixedNumber(limit, 0), "#c0392b", -limit, -limit});
  };
  limits(base, cell.base.torque_limit, "limit");
  std::vector<double> force_limits;
  for (const FingerParams& f : cell.fingers)
    if (std::find(force_limits.begin(), force_limits.end(), f.force_limit) == force_limits.end())
      force_limits.push_back(f.force_limit);
  for (double l : force_limits) limits(fingers, l, force_limits.size() > 1 ? "a limit" : "limit");
  for (int i = 0; i < m; ++i) {
    const FingerParams& f = cell.fingers[i];
    if (i == 0 || f.stroke_min != cell.fingers[0].stroke_min ||
        f.stroke_max != cell.fingers[0].stroke_max) {
      strokes.addReference({"stroke limit", "#c0392b", f.stroke_min, f.stroke_min});
      strokes.addReference({"stroke limit", "#c0392b", f.stroke_max, f.stroke_max});
    }
  }
  SvgTimePlot normal("Contact normal forces f_n", "N", t, phases);
  base.add(series("tau_theta", 0, [&](const auto& f) { return f.tau[layout::kTauTheta]; }));
  for (int i = 0; i < m; ++i) {
    const std::string n = std::to_string(i + 1);
    strokes.add(series("l" + n, i, [&](const auto& f) { return f.q[layout::stroke(i)]; }));
    fingers.add(
        series("tau_" + n, i, [&](const auto& f) { return f.tau[layout::fingerForce(i)]; }));
    normal.add(series("f_n" + n, i, [&](const auto& f) { return f.f_n[i]; }));
  }
  std::string s;
  for (const SvgTimePlot* p : {&angles, &strokes, &base, &fingers, &normal})
    s += "<div class=\"plot\">" + p->render(720, 220) + "</div>\n";
  return s;
}

std::string HtmlReport::render() const {
  std::string s =
      "<!DOCTYPE html>\n<html xmlns=\"http://www.w3.org/1999/xhtml\" lang=\"en\">\n<head>\n"
      "<meta charset=\"utf-8\"/>\n<title>" +
      escapeXml(animation_.title) +
      "</title>\n<style>\nbody { font-family: sans-serif; margin: 1.5em; color: #17202a; }\n"
      "table { border-collapse: collapse; margin-bottom: 1em; }\n"
      "td { padding: 2px 12px 2px 0; } td:first-child { font-weight: bold; }\n"
      ".legend span { display: inline-block; padding: 2px 8px; margin-right: 6px; }\n"
      ".plot { margin: 4px 0; }\n"
      ".verdict { padding: 8px 14px; margin-bottom: 1em; border: 2px solid; max-width: 60em; }\n"
      ".verdict.good { background: #e3f5e1; border-color: #2e7d32; }\n"
      ".verdict.bad { background: #fdecea; border-color: #c62828; }\n"
      ".verdict h2 { margin: 0 0 4px 0; font-size: 1.2em; }\n</style>\n</head>\n<body>\n<h1>" +
      escapeXml(animation_.title) + "</h1>\n";
  if (verdict_.shown)
    s += std::string("<div id=\"verdict\" class=\"verdict ") + (verdict_.good ? "good" : "bad") +
         "\">\n<h2>" + escapeXml(verdict_.headline) + "</h2>\n<p>" + escapeXml(verdict_.detail) +
         "</p>\n</div>\n";
  s += "<table>\n";
  for (const auto& [key, value] : summary_)
    s += "<tr><td>" + escapeXml(key) + "</td><td>" + escapeXml(value) + "</td></tr>\n";
  s += "</table>\n";
  for (const ReportSection& sec : sections_)
    s += "<div id=\"" + escapeXml(sec.id) + "\">\n<h2>" + escapeXml(sec.title) + "</h2>\n<p>" +
         escapeXml(sec.text) + "</p>\n</div>\n";
  s += "<p class=\"legend\">Phases: ";
  for (const Phase p : {Phase::kC, Phase::kP, Phase::kU, Phase::kUnsupported})
    s += std::string("<span style=\"background: ") + phaseColor(p) + "\">" +
         escapeXml(phaseDescription(p)) + "</span>";
  s += "</p>\n<div class=\"animation\">" + SvgAnimation(model_, frames_, animation_).render() +
       "</div>\n<p>The plots' dashed cursors run with the animation; the shading marks each "
       "sample's phase.</p>\n" +
       plots() + "</body>\n</html>\n";
  return s;
}

}  // namespace rbsf::tools
