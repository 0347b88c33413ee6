#pragma once
/// \file
/// \brief One self-contained HTML page about a sampled motion: a summary table, the
///        animation (svg_animation.h) and plots over time with the phases shaded
///        (svg_time_plot.h): object angle phi and base angle theta [deg], finger strokes
///        l_i [m], base torque tau_theta [N m], finger forces tau_i [N] and contact normal
///        forces f_n,i [N]. Inline SVG and CSS only: no script, no network. The page is
///        well-formed XML (XHTML syntax), so XML tools can check it.

#include <string>
#include <utility>
#include <vector>

#include "rbsf/dynamics/core/model.h"
#include "rbsf/tools/svg_animation.h"
#include "rbsf/tools/trajectory_writer.h"

namespace rbsf::tools {

/// \brief The verdict box at the top of the page (a plan's certificate).
struct ReportVerdict {
  bool shown = false;    ///< false: no box
  bool good = false;     ///< green (certified) or red (not)
  std::string headline;  ///< e.g. "certified: 31/32 trials succeeded"
  std::string detail;    ///< e.g. the worst trial
};

/// \brief A section below the summary: a heading and a paragraph (element id `id`).
struct ReportSection {
  std::string id;
  std::string title;
  std::string text;
};

/// \brief The report page.
class HtmlReport {
 public:
  /// \brief `summary`: (key, value) rows shown above the pictures, in order; `verdict`
  ///        the box above them (id "verdict", class "verdict good" or "verdict bad").
  /// \throws std::invalid_argument as SvgAnimation does.
  HtmlReport(const RbsfModel& model, std::vector<TrajectorySample> frames,
             SvgAnimationOptions animation,
             std::vector<std::pair<std::string, std::string>> summary, ReportVerdict verdict = {});

  /// \brief Add a section below the summary table, in the order added.
  void addSection(ReportSection section) { sections_.push_back(std::move(section)); }

  /// \brief The whole page.
  /// \throws std::runtime_error if a sample holds a NaN or an infinity.
  std::string render() const;

 private:
  std::string plots() const;

  const RbsfModel& model_;
  std::vector<TrajectorySample> frames_;
  SvgAnimationOptions animation_;
  std::vector<std::pair<std::string, std::string>> summary_;
  ReportVerdict verdict_;
  std::vector<ReportSection> sections_;
};

}  // namespace rbsf::tools
