#pragma once
/// \file
/// \brief A static SVG line plot of quantities over time, with the time windows of the
///        motion's phases shaded behind the curves, reference lines and bands (limits, a
///        goal with its tolerance) and a cursor that sweeps the time axis in step with the
///        animation (SMIL, same period), for the HTML report. Each curve is drawn over a
///        white halo, so that every colour stays visible on every phase's shading.

#include <string>
#include <vector>

#include "rbsf/dynamics/core/phase.h"

namespace rbsf::tools {

/// \brief One curve: a value per sample time.
struct PlotSeries {
  std::string name;   ///< legend text
  std::string color;  ///< "#rrggbb"
  std::vector<double> values;
};

/// \brief A horizontal reference: a dashed line at `lo` (a limit, a goal) or, when hi > lo,
///        a band from lo to hi (a tolerance), labelled at the right end.
struct PlotReference {
  std::string label;
  std::string color;  ///< "#rrggbb"
  double lo = 0.0, hi = 0.0;
};

/// \brief A plot of several series against the sample times.
class SvgTimePlot {
 public:
  /// \brief `times` [s], non-decreasing; `phases` the phase of each sample (shaded).
  /// \throws std::invalid_argument when the two differ in length or are empty.
  SvgTimePlot(std::string title, std::string unit, std::vector<double> times,
              std::vector<Phase> phases);

  /// \throws std::invalid_argument when the series has the wrong length.
  void add(PlotSeries series);

  /// \brief A reference line or band, kept inside the value axis.
  /// \throws std::invalid_argument for a non-finite value or hi < lo.
  void addReference(PlotReference reference);

  /// \brief The <svg> element, `width` x `height` pixels. Axes: time [s] and the values in
  ///        `unit`, ticks at 1, 2 or 5 times a power of ten.
  /// \throws std::runtime_error for a NaN or an infinite value.
  std::string render(int width, int height) const;

 private:
  struct Frame;  ///< the plot's area and ranges (svg_time_plot.cpp)
  /// \brief The phases' background windows.
  void phaseWindows(const Frame& f, std::string& s) const;
  /// \brief The reference lines and bands with their labels.
  void referenceLines(const Frame& f, std::string& s) const;
  /// \brief Grid, ticks and labels of both axes, the frame and the title.
  void axes(const Frame& f, const std::vector<double>& value_ticks, int height,
            std::string& s) const;
  /// \brief The legend and each series' line.
  void seriesLines(const Frame& f, std::string& s) const;

  std::string title_, unit_;
  std::vector<double> times_;
  std::vector<Phase> phases_;
  std::vector<PlotSeries> series_;
  std::vector<PlotReference> references_;
};

/// \brief Tick positions covering [lo, hi]: about `target` of them, spaced 1, 2 or 5 times a
///        power of ten, first <= lo and last >= hi (the axis range is widened to them).
std::vector<double> niceTicks(double lo, double hi, int target);

}  // namespace rbsf::tools
