// rbsf-simulate: forward simulation of a cell under a piecewise-constant input schedule,
// through stick, slip, separation and renewed contact (rbsf/dynamics/core/simulator.h). The part
// starts at rest on the fingers placed by the placement rule.
//
// Exit status: 0 success; 2 bad input (cell, start pose, controls file, option value,
// output name, a run beyond the bounds), with one message naming the culprit and no output
// file; 130 stopped by SIGINT, 143 by SIGTERM (no output file); 1 internal error.
#include <CLI/CLI.hpp>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "rbsf/dynamics/core/errors.h"
#include "rbsf/dynamics/core/placement.h"
#include "rbsf/dynamics/core/rollout.h"
#include "rbsf/dynamics/core/simulator.h"
#include "rbsf/dynamics/io/atomic_file.h"
#include "rbsf/dynamics/io/cell_file.h"
#include "rbsf/tools/cli_values.h"
#include "rbsf/tools/controls_file.h"
#include "rbsf/tools/interrupt.h"
#include "rbsf/tools/run_files.h"
#include "rbsf/tools/svg_animation.h"
#include "rbsf/tools/tool_main.h"
#include "rbsf/tools/trajectory_writer.h"

namespace rbsf::tools {
namespace {

constexpr double kMaxTimeStep = 0.1;    // [s]: beyond this the contact model is meaningless
constexpr int kMaxPhasesPrinted = 40;   // longer phase sequences are summarised
constexpr double kSvgFrameTime = 0.01;  // [s] between frames of --svg
constexpr long kMaxSteps = 10000000;    // simulator steps of one run (10^4 s at 1 ms)
constexpr long kMaxSvgFrames = 60000;   // --svg frames (10 minutes at 10 ms)

struct Options {
  std::string cell, start, theta = "0", controls, dt = "0.001", out, svg;
};

/// Limits of the cell on tau, checked per segment (inputs beyond them are not a plan).
void checkLimits(const RbsfModel& model, const ControlSchedule& schedule) {
  for (const ControlSegment& seg : schedule.segments())
    checkInputLimits(model.cell(), seg.tau,
                     schedule.label() + ":" + std::to_string(seg.line) + ": column ");
}

/// Steps of each segment: the segment boundaries rounded to the step grid, so rounding
/// never accumulates over many segments.
std::vector<long> stepsPerSegment(const ControlSchedule& schedule, double h) {
  std::vector<long> steps;
  double end = 0.0;
  long done = 0;
  for (const ControlSegment& seg : schedule.segments()) {
    end += seg.duration;
    if (!(end / h <= static_cast<double>(kMaxSteps)))
      throw InputError(schedule.label() + ":" + std::to_string(seg.line) +
                       ": column 'duration': the run would take more than " +
                       std::to_string(kMaxSteps) + " steps of " + numberText(h) +
                       " s (the limit of one run); shorten it or take a larger --dt");
    const long upto = std::lround(end / h);
    if (upto <= done)
      throw InputError(schedule.label() + ":" + std::to_string(seg.line) +
                       ": column 'duration': " + numberText(seg.duration) +
                       " s is shorter than the time step " + numberText(h) + " s");
    steps.push_back(upto - done);
    done = upto;
  }
  return steps;
}

struct Summary {
  std::vector<std::pair<Phase, long>> phases;  // runs of equal phase, in steps
  double min_fn = INFINITY, min_fn_t = 0.0;
  int min_fn_contact = -1;
  double max_gap = 0.0;
  bool touched = false;
  std::array<bool, kMaxFingers> was_touching{};

  void add(const StepReport& r, double t, int m) {
    if (phases.empty() || phases.back().first != r.phase) phases.emplace_back(r.phase, 0);
    ++phases.back().second;
    for (int i = 0; i < m; ++i) {
      const ContactStepReport& c = r.contacts[i];
      const bool touching = c.mode != ContactMode::kSeparated;
      if (touching) {
        touched = true;
        if (c.f_n < min_fn) min_fn = c.f_n, min_fn_t = t, min_fn_contact = i;
        // The gap is taken at the start of the step: a contact touching down within the
        // step started it open, so only contacts touching on both sides count.
        if (was_touching[i]) max_gap = std::max(max_gap, std::abs(c.gap));
      }
      was_touching[i] = touching;
    }
  }
};

void printSummary(const Summary& s, const SimState& state, const RbsfModel& model, double h,
                  const Options& o, long steps, std::size_t samples) {
  const int m = model.numFingers();
  const double deg = 180.0 / M_PI;
  std::printf("rbsf-simulate: %s, %d fingers, %.6g s in %ld steps of %.6g s\n", o.cell.c_str(), m,
              state.t, steps, h);
  std::printf("final pose           x %.6f m, y %.6f m, phi %.6f rad (%.3f deg)\n",
              state.q[layout::kX], state.q[layout::kY], state.q[layout::kPhi],
              state.q[layout::kPhi] * deg);
  std::printf("final mechanism      theta %.6f rad (%.3f deg), strokes", state.q[layout::kTheta],
              state.q[layout::kTheta] * deg);
  for (int i = 0; i < m; ++i) std::printf(" %.6f", state.q[layout::stroke(i)]);
  std::printf(" m\nphases              ");
  const int shown = std::min<int>(static_cast<int>(s.phases.size()), kMaxPhasesPrinted);
  for (int k = 0; k < shown; ++k)
    std::printf("%s %s %.3f s", k ? "," : "", std::string(toString(s.phases[k].first)).c_str(),
                s.phases[k].second * h);
  if (shown < static_cast<int>(s.phases.size()))
    std::printf(", ... (%zu more phase changes)", s.phases.size() - shown);
  std::printf("\n");
  if (s.touched) {
    std::printf("min f_n              %.6g N (contact %d at t = %.3f s)\n", s.min_fn,
                s.min_fn_contact + 1, s.min_fn_t);
    std::printf("max |gap|            %.3g m (touching contacts)\n", s.max_gap);
  } else {
    std::printf("min f_n              none: no contact touched\n");
    std::printf("max |gap|            none: no contact touched\n");
  }
  if (!o.out.empty())
    std::printf("output               %s (%zu samples)\n", o.out.c_str(), samples);
  if (!o.svg.empty()) std::printf("animation            %s\n", o.svg.c_str());
}

Options parseOptions(int argc, char** argv) {
  CLI::App app{
      "Simulate a cell under piecewise-constant inputs through stick, slip, separation and "
      "renewed contact, the part starting at rest on the fingers placed by the placement "
      "rule. Prints a summary; --out writes the sampled trajectory. SI units; angles in "
      "radians or with a deg suffix.",
      "rbsf-simulate"};
  Options o;
  app.add_option("--cell", o.cell, "cell YAML file")->required();
  app.add_option("--start", o.start, "start pose of the part x,y,phi; fingers placed")->required();
  app.add_option("--theta", o.theta, "start base angle (default 0)");
  app.add_option("--controls", o.controls,
                 "CSV: header duration,tau_theta,tau_1..tau_m, one segment per line")
      ->required();
  app.add_option("--dt", o.dt, "time step [s] (default 0.001)");
  app.add_option("--out", o.out, "write the sampled trajectory (.csv or .json)");
  app.add_option("--svg", o.svg, "write an animated SVG of the motion (a frame every 10 ms)");
  app.footer(
      "Exit status: 0 success; 2 bad input (option, value, file, a run beyond the bounds), "
      "with one message on stderr and no file written; 130 stopped by SIGINT, 143 by SIGTERM "
      "(no file written); 1 internal error.");
  parseCommandLine(app, argc, argv);
  return o;
}

/// --theta, within the cell's base range [rad].
double startTheta(const RbsfModel& model, const Options& o) {
  const double theta = parseAngle(o.theta, "--theta");
  const BaseParams& base = model.cell().base;
  if (theta < base.theta_min || theta > base.theta_max)
    throw InputError("--theta: " + numberText(theta) + " rad is outside the base range [" +
                     numberText(base.theta_min) + ", " + numberText(base.theta_max) + "] rad");
  return theta;
}

/// --dt, in (0, kMaxTimeStep] [s].
double timeStep(const Options& o) {
  const double h = parseNumber(o.dt, "--dt");
  if (!(h > 0.0 && h <= kMaxTimeStep))
    throw InputError("--dt: must be in (0, " + numberText(kMaxTimeStep) + "] s, got " + o.dt);
  return h;
}

/// The run's steps, checked against what --out and --svg can hold.
void checkRunLength(const std::vector<long>& steps, const TrajectoryWriter* writer,
                    const Options& o, double h, long frame_stride) {
  long total_steps = 0;
  for (long n : steps) total_steps += n;
  if (writer && static_cast<std::size_t>(total_steps) > writer->maxSamples())
    throw InputError("--out: the run takes " + std::to_string(total_steps) +
                     " steps, a sample each; at most " + std::to_string(writer->maxSamples()) +
                     " are written (shorten the run or take a larger --dt)");
  if (!o.svg.empty() && total_steps / frame_stride > kMaxSvgFrames)
    throw InputError("--svg: the run is " + numberText(total_steps * h) +
                     " s long; an animation shows at most " +
                     numberText(kMaxSvgFrames * kSvgFrameTime) + " s");
}

/// What one run did: its summary, the end state, the animation's frames, its steps and
/// when the part fell off the fingers (-1: it did not).
struct Outcome {
  Summary summary;
  SimState state;
  std::vector<TrajectorySample> frames;  // for --svg
  long total = 0;
  double fell_at = -1.0;
};

/// The run from q0 at rest under the schedule's held inputs; stops early when the part
/// falls off or on SIGINT/SIGTERM. Samples go to `writer` (when given), frames every
/// `frame_stride` steps (when `frames`).
Outcome simulate(const RbsfModel& model, const VecQ& q0, double h, const ControlSchedule& schedule,
                 const std::vector<long>& steps, long frame_stride, bool frames,
                 TrajectoryWriter* writer) {
  const int m = model.numFingers();
  SimulatorSettings settings;
  settings.time_step = h;
  const Simulator sim(model, settings);
  SimulatorWorkspace ws(m);
  Outcome out{Summary{}, SimState(q0, VecQ::Zero(m + 4)), {}, 0, -1.0};
  InterruptFlag::install();  // SIGINT or SIGTERM: stop at the next step, write nothing
  std::vector<VecU> taus;
  for (const auto& seg : schedule.segments()) taus.push_back(seg.tau);
  HeldInputs inputs(steps, taus);
  const long last = inputs.totalSteps() - 1;
  out.total = rollout(
      sim, out.state, inputs.totalSteps(), ws, inputs,
      [&](const SimState& now, const StepReport& report, const VecU& tau, long n) {
        if (!now.q.allFinite() || !now.v.allFinite())
          throw std::runtime_error("the simulation diverged at t = " + numberText(now.t) + " s");
        out.summary.add(report, now.t, m);
        const TrajectorySample sample = trajectorySample(now, report, tau);
        if (writer) writer->add(sample);
        if (frames) {
          if (out.frames.empty()) {  // t = 0: the start at rest, with the first step's forces
            out.frames.push_back(sample);
            out.frames.back().t = 0.0, out.frames.back().q = q0, out.frames.back().v.setZero();
          }
          if ((n + 1) % frame_stride == 0 || n == last) out.frames.push_back(sample);
        }
        if (InterruptFlag::raised()) return false;
        if (fellOff(now.q, q0)) {
          out.fell_at = now.t;  // off the fingers: what follows is a free fall
          return false;
        }
        return true;
      });
  return out;
}

int run(int argc, char** argv) {
  const Options o = parseOptions(argc, argv);
  const RbsfModel model(loadCell(o.cell));
  const int m = model.numFingers();
  const Pose pose = parsePose(o.start, "--start");
  const double theta = startTheta(model, o);
  const double h = timeStep(o);
  std::unique_ptr<TrajectoryWriter> writer;
  if (!o.out.empty()) writer = std::make_unique<TrajectoryWriter>(o.out, m);
  RunFiles files;  // no output replaces an input, another output or a special file
  files.addInput(o.cell, "--cell");
  files.addInput(o.controls, "--controls");
  files.addOutput(o.out, "--out");
  files.addOutput(o.svg, "--svg");
  const ControlSchedule schedule = ControlSchedule::load(o.controls, m);
  checkLimits(model, schedule);
  const std::vector<long> steps = stepsPerSegment(schedule, h);
  const long frame_stride = std::max(1L, std::lround(kSvgFrameTime / h));
  checkRunLength(steps, writer.get(), o, h, frame_stride);
  VecQ q0;
  try {
    q0 = restingConfiguration(model, pose, theta);
  } catch (const InputError& e) {
    throw InputError(std::string("--start: ") + e.what());
  }

  Outcome out = simulate(model, q0, h, schedule, steps, frame_stride, !o.svg.empty(), writer.get());
  if (InterruptFlag::raised()) {  // the streamed temporary file goes with the writer
    std::fprintf(stderr, "rbsf-simulate: stopped at t = %.6g s; nothing written\n", out.state.t);
    return InterruptFlag::exitStatus();
  }
  // Everything is formatted before any file is written; each file is written atomically.
  std::string svg;
  if (!o.svg.empty()) {
    SvgAnimationOptions a;
    a.title = "rbsf-simulate: " + o.cell;
    a.subtitle = "controls " + o.controls + ", start " + o.start;
    svg = SvgAnimation(model, std::move(out.frames), a).document();
  }
  if (writer) writer->commit();
  if (!o.svg.empty()) writeFileAtomically(o.svg, svg, "--svg");
  printSummary(out.summary, out.state, model, h, o, out.total, writer ? writer->size() : 0);
  if (out.fell_at >= 0.0)
    std::fprintf(stderr,
                 "rbsf-simulate: warning: the part fell off the fingers (%g m below its start "
                 "at t = %.6g s); the simulation stopped there\n",
                 kFallDepth, out.fell_at);
  return 0;
}

}  // namespace
}  // namespace rbsf::tools

int main(int argc, char** argv) {
  return rbsf::tools::toolMain("rbsf-simulate", argc, argv, rbsf::tools::run);
}
