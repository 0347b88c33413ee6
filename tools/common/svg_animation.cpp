/// \file
/// \brief The animated SVG of a sampled motion (see svg_animation.h).

#include "rbsf/tools/svg_animation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "rbsf/dynamics/core/model_data.h"
#include "rbsf/dynamics/core/state_layout.h"
#include "rbsf/tools/svg_format.h"
#include "rbsf/tools/svg_time_plot.h"

namespace rbsf::tools {
namespace {

constexpr double kMm = 1000.0;          // SVG user units per metre
constexpr double kTouching = 1e-3;      // [m] a contact is drawn within this gap
constexpr double kNormalLength = 0.04;  // [m]
constexpr double kLongestForce = 0.25;  // [m] length of the largest f_n arrow
constexpr double kRadToDeg = 180.0 / M_PI;

std::string mm(double metres) { return fixedNumber(metres * kMm, 2); }
std::string deg(double radians) { return fixedNumber(radians * kRadToDeg, 3); }

std::string join(const std::vector<std::string>& values) {
  std::string s;
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (k) s += ';';
    s += values[k];
  }
  return s;
}

std::string outlinePath(const Shape& shape, int points) {
  std::string d;
  for (int k = 0; k < points; ++k) {
    const Vec2 c = shape.point(2.0 * M_PI * k / points);
    d += (k ? " L" : "M") + mm(c.x()) + "," + mm(c.y());
  }
  return d + " Z";
}

}  // namespace

SvgAnimation::SvgAnimation(const RbsfModel& model, std::vector<TrajectorySample> frames,
                           SvgAnimationOptions options)
    : model_(model), frames_(std::move(frames)), options_(std::move(options)) {
  const int m = model_.numFingers();
  if (frames_.empty()) throw std::invalid_argument("SvgAnimation: no samples to draw");
  for (std::size_t k = 0; k < frames_.size(); ++k) {
    const TrajectorySample& f = frames_[k];
    if (f.q.size() != layout::configDim(m) || f.f_n.size() != m)
      throw std::invalid_argument("SvgAnimation: sample " + std::to_string(k) +
                                  " does not fit the cell's " + std::to_string(m) + " fingers");
    if (k > 0 && !(f.t >= frames_[k - 1].t))
      throw std::invalid_argument("SvgAnimation: sample times must not decrease");
  }
  // Contact frames of every sample (closest points tracked from frame to frame).
  ModelData data(m);
  double max_fn = 0.0;
  peak_fn_.assign(m, 0.0);
  contacts_.resize(frames_.size());
  for (std::size_t k = 0; k < frames_.size(); ++k) {
    model_.updateContacts(frames_[k].q, data);
    for (int i = 0; i < m; ++i) {
      const ContactFrame& c = data.contacts[i];
      contacts_[k].push_back({c.tip, c.normal, std::abs(c.gap) <= kTouching});
      if (contacts_[k].back().touching) {
        max_fn = std::max(max_fn, frames_[k].f_n[i]);
        peak_fn_[i] = std::max(peak_fn_[i], frames_[k].f_n[i]);
      }
    }
  }
  force_scale_ = max_fn > 0.0 ? kLongestForce / max_fn : 0.0;
  const double t_still = frames_.front().t + options_.still_time;
  while (still_ + 1 < frames_.size() && frames_[still_ + 1].t <= t_still) ++still_;

  // Scene bounds over every frame: part, base bar, rails, force arrows, goal.
  const Cell& cell = model_.cell();
  double r_min = 0.0, r_max = 0.0, stroke = 0.0;
  for (const FingerParams& f : cell.fingers) {
    r_min = std::min(r_min, f.r), r_max = std::max(r_max, f.r);
    stroke = std::max(stroke, f.stroke_max);
  }
  const double reach = std::max({std::hypot(r_min, stroke), std::hypot(r_max, stroke), 0.1});
  double lo_x = -reach, hi_x = reach, lo_y = -0.08, hi_y = reach;
  const double R = model_.shape().boundingRadius();
  auto include = [&](double x, double y, double pad) {
    lo_x = std::min(lo_x, x - pad), hi_x = std::max(hi_x, x + pad);
    lo_y = std::min(lo_y, y - pad), hi_y = std::max(hi_y, y + pad);
  };
  for (std::size_t k = 0; k < frames_.size(); ++k) {
    const VecQ& q = frames_[k].q;
    include(q[layout::kX], q[layout::kY], R);
    for (int i = 0; i < m; ++i) {
      const Contact& c = contacts_[k][i];
      if (c.touching) {
        const Vec2 tail = c.tip - frames_[k].f_n[i] * force_scale_ * c.normal;
        include(tail.x(), tail.y(), 0.01);
      }
    }
  }
  if (options_.goal) include(options_.goal->x, options_.goal->y, R);
  min_x_ = lo_x * kMm, max_x_ = hi_x * kMm, min_y_ = lo_y * kMm, max_y_ = hi_y * kMm;
}

double SvgAnimation::duration() const { return frames_.back().t - frames_.front().t; }

std::string SvgAnimation::keyTimes() const {
  const double t0 = frames_.front().t, T = duration();
  std::vector<std::string> k;
  for (std::size_t i = 0; i < frames_.size(); ++i)
    k.push_back(i == 0                    ? "0"
                : i + 1 == frames_.size() ? "1"
                                          : fixedNumber((frames_[i].t - t0) / T, 6));
  return join(k);
}

std::string SvgAnimation::animation(const std::string& attribute,
                                    const std::vector<std::string>& values,
                                    const std::string& id) const {
  if (duration() <= 0.0) return "";
  const bool discrete = attribute == "visibility";
  return "<animate id=\"" + options_.id_prefix + "-" + id + "\" attributeName=\"" + attribute +
         "\" dur=\"" + fixedNumber(duration(), 6) + "s\" repeatCount=\"indefinite\"" +
         (discrete ? " calcMode=\"discrete\"" : "") + " keyTimes=\"" + keyTimes() + "\" values=\"" +
         join(values) + "\"/>";
}

std::string SvgAnimation::transformAnimation(const std::string& type,
                                             const std::vector<std::string>& values,
                                             const std::string& id) const {
  if (duration() <= 0.0) return "";
  return "<animateTransform id=\"" + options_.id_prefix + "-" + id +
         "\" attributeName=\"transform\" type=\"" + type + "\" dur=\"" +
         fixedNumber(duration(), 6) + "s\" repeatCount=\"indefinite\" keyTimes=\"" + keyTimes() +
         "\" values=\"" + join(values) + "\"/>";
}

std::string SvgAnimation::visibilityWindow(std::size_t first, std::size_t last) const {
  const bool shown = still_ >= first && still_ <= last;
  std::string s = " visibility=\"" + std::string(shown ? "visible" : "hidden") + "\">";
  if (duration() <= 0.0 || (first == 0 && last + 1 == frames_.size())) return s;
  const double t0 = frames_.front().t, T = duration();
  std::string values, times = "0";
  if (first > 0) values = "hidden;", times += ";" + fixedNumber((frames_[first].t - t0) / T, 6);
  values += "visible";
  if (last + 1 < frames_.size()) {
    values += ";hidden";
    times += ";" + fixedNumber((frames_[last + 1].t - t0) / T, 6);
  }
  return s + "<animate attributeName=\"visibility\" calcMode=\"discrete\" dur=\"" +
         fixedNumber(T, 6) + "s\" repeatCount=\"indefinite\" keyTimes=\"" + times + "\" values=\"" +
         values + "\"/>";
}

std::string SvgAnimation::drawBase() const {
  const Cell& cell = model_.cell();
  const int m = model_.numFingers();
  std::vector<std::string> theta;
  for (const TrajectorySample& f : frames_) theta.push_back(deg(f.q[layout::kTheta]));
  double r_min = 0.0, r_max = 0.0;
  for (const FingerParams& f : cell.fingers)
    r_min = std::min(r_min, f.r), r_max = std::max(r_max, f.r);
  std::string s = "<g class=\"base\" transform=\"rotate(" + theta[still_] + ")\">" +
                  transformAnimation("rotate", theta, "base-rotate") + "<line x1=\"" +
                  mm(r_min - 0.06) + "\" y1=\"0\" x2=\"" + mm(r_max + 0.06) +
                  "\" y2=\"0\" stroke=\"#566573\" stroke-width=\"16\" stroke-linecap=\"round\"/>";
  for (int i = 0; i < m; ++i) {
    const FingerParams& f = cell.fingers[i];
    const std::string r = mm(f.r), id = "finger" + std::to_string(i + 1);
    std::vector<std::string> l;
    for (const TrajectorySample& fr : frames_) l.push_back(mm(fr.q[layout::stroke(i)]));
    s += "<line x1=\"" + r + "\" y1=\"0\" x2=\"" + r + "\" y2=\"" + mm(f.stroke_max) +
         "\" stroke=\"#d5d8dc\" stroke-width=\"5\"/>";
    s += "<line x1=\"" + r + "\" y1=\"0\" x2=\"" + r + "\" y2=\"" + l[still_] +
         "\" stroke=\"#2c3e50\" stroke-width=\"11\">" + animation("y2", l, id + "-stroke") +
         "</line>";
    s += "<circle cx=\"" + r + "\" cy=\"" + l[still_] + "\" r=\"9\" fill=\"#17202a\">" +
         animation("cy", l, id + "-tip") + "</circle>";
  }
  s += "</g><circle cx=\"0\" cy=\"0\" r=\"14\" fill=\"#fdfefe\" stroke=\"#566573\" "
       "stroke-width=\"5\"/><path d=\"M0,-14 L-40,-70 L40,-70 Z\" fill=\"#abb2b9\"/>";
  return s;
}

std::string SvgAnimation::drawPart() const {
  const std::string outline = outlinePath(model_.shape(), options_.outline_points);
  std::string s;
  if (options_.goal) {
    s += "<g class=\"goal\" transform=\"translate(" + mm(options_.goal->x) + " " +
         mm(options_.goal->y) + ") rotate(" + deg(options_.goal->phi) + ")\"><path d=\"" + outline +
         "\" fill=\"none\" stroke=\"#1e8449\" stroke-width=\"4\" " +
         "stroke-dasharray=\"14 10\"/><circle r=\"7\" fill=\"#1e8449\"/></g>";
  }
  const VecQ& q0 = frames_.front().q;
  s += "<g class=\"start\" transform=\"translate(" + mm(q0[layout::kX]) + " " + mm(q0[layout::kY]) +
       ") rotate(" + deg(q0[layout::kPhi]) + ")\"><path d=\"" + outline +
       "\" fill=\"none\" stroke=\"#808b96\" stroke-width=\"3\" stroke-dasharray=\"6 8\"/></g>";
  std::vector<std::string> at, phi;
  for (const TrajectorySample& f : frames_) {
    at.push_back(mm(f.q[layout::kX]) + " " + mm(f.q[layout::kY]));
    phi.push_back(deg(f.q[layout::kPhi]));
  }
  s += "<g class=\"part\" transform=\"translate(" + at[still_] + ")\">" +
       transformAnimation("translate", at, "part-translate") + "<g transform=\"rotate(" +
       phi[still_] + ")\">" + transformAnimation("rotate", phi, "part-rotate") + "<path d=\"" +
       outline +
       "\" fill=\"#f7dc6f\" fill-opacity=\"0.75\" stroke=\"#9a7d0a\" stroke-width=\"5\"/>" +
       "<line x1=\"0\" y1=\"0\" x2=\"" + mm(0.6 * model_.shape().boundingRadius()) +
       "\" y2=\"0\" stroke=\"#9a7d0a\" stroke-width=\"4\"/><circle r=\"9\" fill=\"#7d6608\"/>" +
       "</g></g>";
  return s;
}

std::string SvgAnimation::drawContacts() const {
  const int m = model_.numFingers();
  std::string s;
  for (int i = 0; i < m; ++i) {
    const std::string id = "contact" + std::to_string(i + 1);
    std::vector<std::string> nx1, ny1, nx2, ny2, fx1, fy1, shown;
    for (std::size_t k = 0; k < frames_.size(); ++k) {
      const Contact& c = contacts_[k][i];
      const double len = c.touching ? kNormalLength : 0.0;
      const double force = c.touching ? frames_[k].f_n[i] * force_scale_ : 0.0;
      nx1.push_back(mm(c.tip.x())), ny1.push_back(mm(c.tip.y()));
      nx2.push_back(mm(c.tip.x() + len * c.normal.x()));
      ny2.push_back(mm(c.tip.y() + len * c.normal.y()));
      fx1.push_back(mm(c.tip.x() - force * c.normal.x()));
      fy1.push_back(mm(c.tip.y() - force * c.normal.y()));
      shown.push_back(force > 1e-4 ? "visible" : "hidden");
    }
    const std::size_t k = still_;
    s += "<line x1=\"" + nx1[k] + "\" y1=\"" + ny1[k] + "\" x2=\"" + nx2[k] + "\" y2=\"" + ny2[k] +
         "\" stroke=\"#2874a6\" stroke-width=\"4\">" + animation("x1", nx1, id + "-normal-x1") +
         animation("y1", ny1, id + "-normal-y1") + animation("x2", nx2, id + "-normal-x2") +
         animation("y2", ny2, id + "-normal-y2") + "</line>";
    s += "<line x1=\"" + fx1[k] + "\" y1=\"" + fy1[k] + "\" x2=\"" + nx1[k] + "\" y2=\"" + ny1[k] +
         "\" stroke=\"#c0392b\" stroke-width=\"7\" marker-end=\"url(#" + options_.id_prefix +
         "-arrow)\" visibility=\"" + shown[k] + "\">" + animation("x1", fx1, id + "-force-x1") +
         animation("y1", fy1, id + "-force-y1") + animation("x2", nx1, id + "-force-x2") +
         animation("y2", ny1, id + "-force-y2") +
         animation("visibility", shown, id + "-force-shown") + "</line>";
  }
  return s;
}

std::string SvgAnimation::drawLabels() const {
  const double w = max_x_ - min_x_, font = w / 34.0;
  const double left = min_x_ + 0.6 * font, right = max_x_ - 0.6 * font;
  const double head = -max_y_ - 4.2 * font;  // top of the view box (render())
  std::string s =
      "<g font-family=\"sans-serif\" font-size=\"" + fixedNumber(font, 1) + "\" fill=\"#17202a\">";
  s += "<text x=\"" + fixedNumber(left, 1) + "\" y=\"" + fixedNumber(head + 1.2 * font, 1) +
       "\" font-weight=\"bold\">" + escapeXml(options_.title) + "</text>";
  s += "<text x=\"" + fixedNumber(left, 1) + "\" y=\"" + fixedNumber(head + 2.1 * font, 1) +
       "\" font-size=\"" + fixedNumber(0.6 * font, 1) + "\">" + escapeXml(options_.subtitle) +
       "</text>";
  // Phase and time: one label per run of equal text, shown over its run's time window.
  auto runs = [&](auto label, double x, const std::string& extra) {
    for (std::size_t a = 0; a < frames_.size();) {
      std::size_t b = a;
      while (b + 1 < frames_.size() && label(b + 1) == label(a)) ++b;
      s += "<text x=\"" + fixedNumber(x, 1) + "\" y=\"" + fixedNumber(head + 3.4 * font, 1) + "\"" +
           extra + visibilityWindow(a, b) + escapeXml(label(a)) + "</text>";
      a = b + 1;
    }
  };
  runs([&](std::size_t k) { return "phase " + std::string(phaseDescription(frames_[k].phase)); },
       left, " font-weight=\"bold\" fill=\"#1a5276\"");
  runs([&](std::size_t k) { return "t = " + fixedNumber(frames_[k].t, 2) + " s"; }, right,
       " text-anchor=\"end\"");
  // A bar along the bottom that fills over one play.
  const double bar_y = -min_y_ + 0.6 * font, bar_h = 0.3 * font;
  s += "<rect x=\"" + fixedNumber(min_x_, 1) + "\" y=\"" + fixedNumber(bar_y, 1) + "\" width=\"" +
       fixedNumber(w, 1) + "\" height=\"" + fixedNumber(bar_h, 1) + "\" fill=\"#eaecee\"/>";
  const std::string full = fixedNumber(w, 1);
  s += "<rect x=\"" + fixedNumber(min_x_, 1) + "\" y=\"" + fixedNumber(bar_y, 1) + "\" width=\"" +
       fixedNumber(duration() > 0 ? w * (frames_[still_].t - frames_.front().t) / duration() : w,
                   1) +
       "\" height=\"" + fixedNumber(bar_h, 1) + "\" fill=\"#5d6d7e\">";
  if (duration() > 0)
    s += "<animate attributeName=\"width\" dur=\"" + fixedNumber(duration(), 6) +
         "s\" repeatCount=\"indefinite\" keyTimes=\"0;1\" values=\"0;" + full + "\"/>";
  return s + "</rect></g>";
}

std::string SvgAnimation::drawLegend(double font) const {
  const double small = 0.62 * font;
  double y = -min_y_ + 2.3 * font, mid = y - 0.3 * font;
  double x = min_x_ + 0.6 * font;
  // A second row when an item (its drawing `len` and text) would pass the right edge.
  auto fit = [&](double len, const std::string& t) {
    if (x + len + small * 0.55 * static_cast<double>(t.size()) <= max_x_) return;
    x = min_x_ + 0.6 * font, y += 1.1 * font, mid += 1.1 * font;
  };
  const std::string p = options_.id_prefix;
  auto text = [&](double at, const std::string& t) {
    return "<text x=\"" + fixedNumber(at, 1) + "\" y=\"" + fixedNumber(y, 1) + "\">" +
           escapeXml(t) + "</text>";
  };
  auto advance = [&](const std::string& t) { x += small * (0.55 * t.size() + 1.2); };
  std::string s = "<g class=\"legend\" font-family=\"sans-serif\" font-size=\"" +
                  fixedNumber(small, 1) + "\" fill=\"#17202a\">";
  // Scale bar: 100 mm of the drawing.
  s += "<g class=\"scale-bar\" stroke=\"#17202a\" stroke-width=\"3\"><line x1=\"" +
       fixedNumber(x, 1) + "\" y1=\"" + fixedNumber(mid, 1) + "\" x2=\"" + fixedNumber(x + 100, 1) +
       "\" y2=\"" + fixedNumber(mid, 1) + "\"/>";
  for (const double e : {x, x + 100})
    s += "<line x1=\"" + fixedNumber(e, 1) + "\" y1=\"" + fixedNumber(mid - 0.25 * font, 1) +
         "\" x2=\"" + fixedNumber(e, 1) + "\" y2=\"" + fixedNumber(mid + 0.25 * font, 1) + "\"/>";
  s += "</g>" + text(x + 100 + 0.3 * font, "0.1 m");
  x += 100 + 0.3 * font;
  advance("0.1 m");
  // Force arrow: a round number of newtons at the drawing's scale, and each peak.
  s += "<g class=\"force-legend\">";
  if (force_scale_ > 0.0) {
    const double peak = *std::max_element(peak_fn_.begin(), peak_fn_.end());
    const std::vector<double> ticks = niceTicks(0.0, 0.25 * peak, 1);
    const double newtons = ticks.size() > 1 ? ticks[1] : peak;
    const double len = newtons * force_scale_ * kMm;
    std::string label = "f_n " + fixedNumber(newtons, newtons < 10 ? 1 : 0) + " N; peaks";
    for (std::size_t i = 0; i < peak_fn_.size(); ++i)
      label += (i ? ", " : " ") + std::to_string(i + 1) + ": " + fixedNumber(peak_fn_[i], 0) + " N";
    fit(len, label);
    s += "<line x1=\"" + fixedNumber(x, 1) + "\" y1=\"" + fixedNumber(mid, 1) + "\" x2=\"" +
         fixedNumber(x + len, 1) + "\" y2=\"" + fixedNumber(mid, 1) +
         "\" stroke=\"#c0392b\" stroke-width=\"7\" marker-end=\"url(#" + p + "-arrow)\"/>";
    x += len + 0.3 * font;
    s += text(x, label);
    advance(label);
  } else {
    s += text(x, "no contact force");
    advance("no contact force");
  }
  s += "</g>";
  // Normal, goal and start.
  fit(40, "normal");
  s += "<line x1=\"" + fixedNumber(x, 1) + "\" y1=\"" + fixedNumber(mid, 1) + "\" x2=\"" +
       fixedNumber(x + 40, 1) + "\" y2=\"" + fixedNumber(mid, 1) +
       "\" stroke=\"#2874a6\" stroke-width=\"4\"/>" + text(x + 40 + 0.3 * font, "normal");
  x += 40 + 0.3 * font;
  advance("normal");
  if (options_.goal) {
    fit(40, "goal");
    s += "<line x1=\"" + fixedNumber(x, 1) + "\" y1=\"" + fixedNumber(mid, 1) + "\" x2=\"" +
         fixedNumber(x + 40, 1) + "\" y2=\"" + fixedNumber(mid, 1) +
         "\" stroke=\"#1e8449\" stroke-width=\"4\" stroke-dasharray=\"14 10\"/>" +
         text(x + 40 + 0.3 * font, "goal");
    x += 40 + 0.3 * font;
    advance("goal");
  }
  fit(40, "start");
  s += "<line x1=\"" + fixedNumber(x, 1) + "\" y1=\"" + fixedNumber(mid, 1) + "\" x2=\"" +
       fixedNumber(x + 40, 1) + "\" y2=\"" + fixedNumber(mid, 1) +
       "\" stroke=\"#808b96\" stroke-width=\"3\" stroke-dasharray=\"6 8\"/>" +
       text(x + 40 + 0.3 * font, "start");
  return s + "</g>";
}

std::string SvgAnimation::render() const {
  const double w = max_x_ - min_x_, font = w / 34.0;
  const double vx = min_x_, vy = -max_y_ - 4.2 * font, vw = w,
               vh = (max_y_ - min_y_) + 4.2 * font + 4.0 * font;  // legend: two rows
  const std::string p = options_.id_prefix;
  std::string s =
      "<svg xmlns=\"http://www.w3.org/2000/svg\" id=\"" + p + "\" viewBox=\"" + fixedNumber(vx, 1) +
      " " + fixedNumber(vy, 1) + " " + fixedNumber(vw, 1) + " " + fixedNumber(vh, 1) +
      "\" width=\"" + std::to_string(options_.width_px) + "\" height=\"" +
      std::to_string(static_cast<int>(std::lround(options_.width_px * vh / vw))) + "\">";
  s += "<defs><marker id=\"" + p +
       "-arrow\" viewBox=\"0 0 10 10\" refX=\"8\" refY=\"5\" markerWidth=\"4\" "
       "markerHeight=\"4\" orient=\"auto\"><path d=\"M0,0 L10,5 L0,10 Z\" fill=\"#c0392b\"/>"
       "</marker><marker id=\"" +
       p +
       "-axis\" viewBox=\"0 0 10 10\" refX=\"8\" refY=\"5\" markerWidth=\"5\" "
       "markerHeight=\"5\" orient=\"auto\"><path d=\"M0,0 L10,5 L0,10 Z\" fill=\"#17202a\"/>"
       "</marker></defs>";
  s += "<rect x=\"" + fixedNumber(vx, 1) + "\" y=\"" + fixedNumber(vy, 1) + "\" width=\"" +
       fixedNumber(vw, 1) + "\" height=\"" + fixedNumber(vh, 1) + "\" fill=\"#ffffff\"/>";
  // World frame: x right, y up (docs/model.md); SVG's y points down, hence the flip.
  // The world axes at the base axis, 100 mm each, drawn last so that nothing hides them.
  const std::string axes =
      "<g class=\"world-axes\" stroke=\"#17202a\" stroke-width=\"3\" marker-end=\"url(#" + p +
      "-axis)\"><line x1=\"0\" y1=\"0\" x2=\"100\" y2=\"0\"/><line x1=\"0\" y1=\"0\" x2=\"0\" "
      "y2=\"100\"/></g>";
  s += "<g transform=\"scale(1,-1)\">" + drawBase() + drawPart() + drawContacts() + axes + "</g>";
  s += "<g class=\"world-axes-labels\" font-family=\"sans-serif\" font-size=\"" +
       fixedNumber(0.7 * font, 1) + "\" fill=\"#17202a\"><text x=\"112\" y=\"" +
       fixedNumber(0.25 * font, 1) + "\">x</text><text x=\"" + fixedNumber(-0.25 * font, 1) +
       "\" y=\"-112\" text-anchor=\"middle\">y</text></g>";
  s += drawLabels();
  s += drawLegend(font);
  return s + "</svg>";
}

std::string SvgAnimation::document() const {
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n" + render() + "\n";
}

}  // namespace rbsf::tools
