/// \file
/// \brief Time plots for the HTML report (see svg_time_plot.h).

#include "rbsf/tools/svg_time_plot.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "rbsf/tools/svg_format.h"

namespace rbsf::tools {

std::vector<double> niceTicks(double lo, double hi, int target) {
  if (!(hi > lo)) {  // a constant: a unit-wide band around it
    const double pad = std::max(1.0, std::abs(lo)) * 0.5;
    lo -= pad, hi += pad;
  }
  if (!std::isfinite(hi - lo)) return {lo, hi};
  const double raw = (hi - lo) / std::max(1, target);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10 * p;
  for (const double f : {1.0, 2.0, 5.0}) {
    if (f * p >= raw) {
      step = f * p;
      break;
    }
  }
  std::vector<double> ticks;
  const double first = std::floor(lo / step + 1e-9), last = std::ceil(hi / step - 1e-9);
  // In doubles: a range far from zero would overflow an integer index. Far beyond the
  // resolution of a double (or beyond 100 ticks) the ends alone are the ticks.
  if (!(last - first <= 100.0) || first + 1.0 == first) return {lo, hi};
  for (double k = first; k <= last; k += 1.0) ticks.push_back(k * step);
  return ticks;
}

SvgTimePlot::SvgTimePlot(std::string title, std::string unit, std::vector<double> times,
                         std::vector<Phase> phases)
    : title_(std::move(title)),
      unit_(std::move(unit)),
      times_(std::move(times)),
      phases_(std::move(phases)) {
  if (times_.empty() || times_.size() != phases_.size())
    throw std::invalid_argument("SvgTimePlot: times and phases must be non-empty and match");
}

void SvgTimePlot::add(PlotSeries series) {
  if (series.values.size() != times_.size())
    throw std::invalid_argument("SvgTimePlot: series '" + series.name + "' has " +
                                std::to_string(series.values.size()) + " values for " +
                                std::to_string(times_.size()) + " times");
  series_.push_back(std::move(series));
}

void SvgTimePlot::addReference(PlotReference reference) {
  if (!std::isfinite(reference.lo) || !std::isfinite(reference.hi) || reference.hi < reference.lo)
    throw std::invalid_argument("SvgTimePlot: reference '" + reference.label +
                                "' needs finite lo <= hi");
  references_.push_back(std::move(reference));
}

/// \brief The plot's area in pixels and its ranges: t in [t0, t1], values in [lo, hi].
struct SvgTimePlot::Frame {
  double left, right, top, bottom, t0, t1, lo, hi;
  double X(double t) const { return left + (t - t0) / (t1 - t0) * (right - left); }
  double Y(double v) const { return bottom - (v - lo) / (hi - lo) * (bottom - top); }
};

namespace {
std::string f1(double x) { return fixedNumber(x, 1); }
}  // namespace

void SvgTimePlot::phaseWindows(const Frame& f, std::string& s) const {
  // Sample k's phase holds from t_k to t_(k+1).
  for (std::size_t a = 0; a < times_.size();) {
    std::size_t b = a;
    while (b + 1 < times_.size() && phases_[b + 1] == phases_[a]) ++b;
    const double end = b + 1 < times_.size() ? times_[b + 1] : f.t1;
    s += "<rect x=\"" + f1(f.X(times_[a])) + "\" y=\"" + f1(f.top) + "\" width=\"" +
         f1(std::max(0.0, f.X(end) - f.X(times_[a]))) + "\" height=\"" + f1(f.bottom - f.top) +
         "\" fill=\"" + phaseColor(phases_[a]) + "\"><title>" +
         escapeXml(phaseDescription(phases_[a])) + "</title></rect>";
    a = b + 1;
  }
}

void SvgTimePlot::referenceLines(const Frame& f, std::string& s) const {
  for (const PlotReference& r : references_) {
    const bool band = r.hi > r.lo;
    s += "<g class=\"reference\">";
    if (band)
      s += "<rect x=\"" + f1(f.left) + "\" y=\"" + f1(f.Y(r.hi)) + "\" width=\"" +
           f1(f.right - f.left) + "\" height=\"" + f1(std::max(0.5, f.Y(r.lo) - f.Y(r.hi))) +
           "\" fill=\"" + r.color + "\" fill-opacity=\"0.25\"/>";
    const double at = band ? 0.5 * (r.lo + r.hi) : r.lo;
    s += "<line x1=\"" + f1(f.left) + "\" x2=\"" + f1(f.right) + "\" y1=\"" + f1(f.Y(at)) +
         "\" y2=\"" + f1(f.Y(at)) + "\" stroke=\"" + r.color +
         "\" stroke-width=\"1.5\" stroke-dasharray=\"6 4\"/><text x=\"" + f1(f.right - 4) +
         "\" y=\"" + f1(f.Y(at) - 4) + "\" text-anchor=\"end\" fill=\"" + r.color + "\">" +
         escapeXml(r.label) + "</text></g>";
  }
}

void SvgTimePlot::axes(const Frame& f, const std::vector<double>& value_ticks, int height,
                       std::string& s) const {
  for (const double v : value_ticks) {
    s += "<line x1=\"" + f1(f.left) + "\" x2=\"" + f1(f.right) + "\" y1=\"" + f1(f.Y(v)) +
         "\" y2=\"" + f1(f.Y(v)) + "\" stroke=\"#aab7b8\" stroke-width=\"0.5\"/>";
    char label[32];
    std::snprintf(label, sizeof label, "%g", std::abs(v) < 1e-12 ? 0.0 : v);
    s += "<text x=\"" + f1(f.left - 5) + "\" y=\"" + f1(f.Y(v) + 4) + "\" text-anchor=\"end\">" +
         label + "</text>";
  }
  for (const double t : niceTicks(f.t0, f.t1, 8)) {
    if (t < f.t0 - 1e-9 || t > f.t1 + 1e-9) continue;
    char label[32];
    std::snprintf(label, sizeof label, "%g", t);
    s += "<line x1=\"" + f1(f.X(t)) + "\" x2=\"" + f1(f.X(t)) + "\" y1=\"" + f1(f.bottom) +
         "\" y2=\"" + f1(f.bottom + 4) + "\" stroke=\"#17202a\"/><text x=\"" + f1(f.X(t)) +
         "\" y=\"" + f1(f.bottom + 16) + "\" text-anchor=\"middle\">" + label + "</text>";
  }
  s += "<rect x=\"" + f1(f.left) + "\" y=\"" + f1(f.top) + "\" width=\"" + f1(f.right - f.left) +
       "\" height=\"" + f1(f.bottom - f.top) + "\" fill=\"none\" stroke=\"#17202a\"/>";
  s += "<text x=\"" + f1(f.left) + "\" y=\"16\" font-size=\"13\" font-weight=\"bold\">" +
       escapeXml(title_) + " [" + escapeXml(unit_) + "]</text>";
  s += "<text x=\"" + f1(f.right) + "\" y=\"" + f1(height - 4.0) +
       "\" text-anchor=\"end\">t [s]</text>";
}

void SvgTimePlot::seriesLines(const Frame& f, std::string& s) const {
  double legend_x = f.right;
  for (auto it = series_.rbegin(); it != series_.rend(); ++it) {
    const double w = 28 + 7.0 * static_cast<double>(it->name.size());
    legend_x -= w;
    s += "<line x1=\"" + f1(legend_x) + "\" x2=\"" + f1(legend_x + 18) + "\" y1=\"12\" y2=\"12\" " +
         "stroke=\"" + it->color + "\" stroke-width=\"2.5\"/><text x=\"" + f1(legend_x + 22) +
         "\" y=\"16\">" + escapeXml(it->name) + "</text>";
  }
  for (const PlotSeries& ser : series_) {
    std::string pts;
    for (std::size_t k = 0; k < times_.size(); ++k) {
      if (k) pts += ' ';
      pts += f1(f.X(times_[k])) + "," + f1(f.Y(ser.values[k]));
    }
    s += "<polyline points=\"" + pts +
         "\" fill=\"none\" stroke=\"#ffffff\" stroke-width=\"4.5\" stroke-opacity=\"0.9\"/>";
    s += "<polyline class=\"series\" points=\"" + pts + "\" fill=\"none\" stroke=\"" + ser.color +
         "\" stroke-width=\"1.8\"><title>" + escapeXml(ser.name) + "</title></polyline>";
  }
}

std::string SvgTimePlot::render(int width, int height) const {
  Frame f{64, width - 12.0, 26, height - 34.0, times_.front(), 0.0, INFINITY, -INFINITY};
  f.t1 = std::max(times_.back(), f.t0 + 1e-9);
  for (const PlotSeries& s : series_)
    for (const double v : s.values) {
      if (!std::isfinite(v)) throw std::runtime_error("plot '" + title_ + "' holds a NaN");
      f.lo = std::min(f.lo, v), f.hi = std::max(f.hi, v);
    }
  if (series_.empty()) f.lo = 0, f.hi = 1;
  for (const PlotReference& r : references_)
    f.lo = std::min(f.lo, r.lo), f.hi = std::max(f.hi, r.hi);
  const std::vector<double> yt = niceTicks(f.lo, f.hi, 5);
  f.lo = yt.front(), f.hi = yt.back();

  std::string s = "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 " +
                  std::to_string(width) + " " + std::to_string(height) + "\" width=\"" +
                  std::to_string(width) + "\" height=\"" + std::to_string(height) +
                  "\" font-family=\"sans-serif\" font-size=\"11\">";
  phaseWindows(f, s);
  referenceLines(f, s);
  axes(f, yt, height, s);
  seriesLines(f, s);
  // A cursor in step with the animation (one play = the sample time span).
  s += "<line x1=\"" + f1(f.left) + "\" x2=\"" + f1(f.left) + "\" y1=\"" + f1(f.top) + "\" y2=\"" +
       f1(f.bottom) + "\" stroke=\"#17202a\" stroke-width=\"1\" stroke-dasharray=\"3 3\">";
  if (times_.back() > f.t0) {
    const std::string dur = fixedNumber(times_.back() - f.t0, 6);
    for (const char* attr : {"x1", "x2"})
      s += std::string("<animate attributeName=\"") + attr + "\" dur=\"" + dur +
           "s\" repeatCount=\"indefinite\" keyTimes=\"0;1\" values=\"" + f1(f.left) + ";" +
           f1(f.right) + "\"/>";
  }
  return s + "</line></svg>";
}

}  // namespace rbsf::tools
