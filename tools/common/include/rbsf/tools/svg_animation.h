#pragma once
/// \file
/// \brief An animated SVG of a sampled motion of the jig: base, fingers, part outline,
///        contact normals and forces, phase label and time, played by any browser (SMIL
///        <animate>, <animateTransform>; no script, no external resource).
///
/// Drawing (world frame B of docs/model.md, x right, y up; SVG user unit = 1 mm; one group
/// flips y):
///   - base: a bar along the base x axis through the axis at the origin, rotated by theta;
///   - finger i: its rail from (r_i, 0) to (r_i, stroke_max) in the base frame and its rod
///     from (r_i, 0) to the fingertip (r_i, l_i), i.e. p_i = R(theta) (r_i, l_i) (eq. 2);
///   - part: the shape's outline c(xi) in the object frame, translated by (x, y) and rotated
///     by phi, with its COM and object x axis; the goal pose dashed when given;
///   - contact i, while the tip is within 1 mm of the boundary: the inward normal n_i
///     (40 mm, from the tip into the part) and the normal force as an arrow of length
///     f_n,i * force scale ending at the tip (the tip pushes along n_i);
///   - the phase of each sample (C, P, U, unsupported) and the time, top right;
///   - the world axes x and y (100 mm) at the base axis, the start pose dashed grey, and a
///     legend row at the bottom: a 0.1 m scale bar, a force arrow of a round number of
///     newtons at the drawing's force scale with each contact's peak f_n, the normal, the
///     goal and the start.
/// Every animated attribute has exactly one value per sample, at keyTimes t_k / T
/// (T the last sample's time), so samples at irregular times (collocation knots) play at
/// their true times; the animation repeats. The static attribute values are the frame at
/// SvgAnimationOptions::still_time, what a renderer without animation shows.
/// Numbers: millimetres with 2 decimals, degrees with 3, keyTimes with 6: the same
/// samples give the same bytes.

#include <optional>
#include <string>
#include <vector>

#include "rbsf/dynamics/core/model.h"
#include "rbsf/dynamics/core/placement.h"
#include "rbsf/tools/trajectory_writer.h"

namespace rbsf::tools {

/// \brief What the picture shows besides the motion.
struct SvgAnimationOptions {
  std::string title;                          ///< first line, top left
  std::string subtitle;                       ///< second line, top left
  std::optional<Pose> goal;                   ///< goal pose of the COM frame, drawn dashed
  double angle_tolerance = 2.0 * M_PI / 180;  ///< [rad] the goal's band in the report's plot
  double still_time = 0.0;                    ///< [s] the frame of the static attribute values
  std::string id_prefix = "a";                ///< element ids start with it (unique within a page)
  int outline_points = 180;                   ///< boundary points of the part outline
  int width_px = 720;                         ///< displayed width [px]
};

/// \brief Builds the animated SVG of `frames` (samples in time order, t non-decreasing).
class SvgAnimation {
 public:
  /// \throws std::invalid_argument for no frames, frames of the wrong size or time order.
  SvgAnimation(const RbsfModel& model, std::vector<TrajectorySample> frames,
               SvgAnimationOptions options = {});

  /// \brief The <svg> element (for inlining in a page).
  /// \throws std::runtime_error if a sample holds a NaN or an infinity.
  std::string render() const;

  /// \brief A standalone SVG file: the XML declaration and render().
  std::string document() const;

  /// \brief Length of one play [s]: the last sample's time minus the first's.
  double duration() const;

  /// \brief Force scale [m/N]: the largest f_n in the frames is drawn 0.25 m long.
  double forceScale() const { return force_scale_; }

 private:
  struct Contact {
    Vec2 tip, normal;
    bool touching = false;
  };
  std::string keyTimes() const;
  std::string animation(const std::string& attribute, const std::vector<std::string>& values,
                        const std::string& id) const;
  std::string transformAnimation(const std::string& type, const std::vector<std::string>& values,
                                 const std::string& id) const;
  std::string visibilityWindow(std::size_t first, std::size_t last) const;
  std::string drawBase() const;
  std::string drawPart() const;
  std::string drawContacts() const;
  std::string drawLabels() const;
  std::string drawLegend(double font) const;

  const RbsfModel& model_;
  std::vector<TrajectorySample> frames_;
  std::vector<std::vector<Contact>> contacts_;  ///< [frame][finger]
  SvgAnimationOptions options_;
  std::size_t still_ = 0;  ///< frame index of the static values
  double force_scale_ = 0.0;
  std::vector<double> peak_fn_;                           ///< per contact, over the frames [N]
  double min_x_ = 0, max_x_ = 0, min_y_ = 0, max_y_ = 0;  ///< scene bounds [mm]
};

}  // namespace rbsf::tools
