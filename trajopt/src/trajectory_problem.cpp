#include "rbsf/trajopt/trajectory_problem.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "rbsf/trajopt/collocation_constraint.h"
#include "rbsf/trajopt/contact_constraint.h"
#include "rbsf/trajopt/effort_cost.h"
#include "rbsf/trajopt/friction_cone_constraint.h"
#include "rbsf/trajopt/internal_force_constraint.h"
#include "rbsf/trajopt/smoothness_cost.h"
#include "rbsf/trajopt/sticking_constraint.h"

namespace rbsf::trajopt {

TrajectoryProblem::TrajectoryProblem(const RbsfModel& model, const plan::Plan& plan,
                                     const OptimizerSettings& settings)
    : model_(model) {
  const RunCut cut = settings.stated_roles                  ? RunCut::kStatedRoles
                     : settings.split_runs_by_contact_modes ? RunCut::kContactModes
                                                            : RunCut::kPhaseLetters;
  ScheduleResult built = buildSchedule(model, plan, settings.knots, cut);
  ok_ = built.ok();
  why_ = std::move(built.error);
  schedule_ = std::move(built.schedule);
  if (!ok_) return;
  layout_ = std::make_unique<DecisionLayout>(model.numFingers(), schedule_.intervals(),
                                             static_cast<int>(schedule_.runs.size()));
  variables_ = std::make_unique<DecisionVariables>(model, *layout_, schedule_, plan, settings);
  sets_.push_back(std::make_unique<CollocationConstraint>(model, *layout_, schedule_));
  sets_.push_back(std::make_unique<ContactConstraint>(model, *layout_, schedule_));
  sets_.push_back(std::make_unique<StickingConstraint>(
      *layout_, schedule_, settings.keep_slide_direction, settings.min_slip_rate));
  sets_.push_back(std::make_unique<FrictionConeConstraint>(
      *layout_, schedule_, model.cell().friction.mu_static, settings.cone_margin));
  if (settings.least_norm)
    sets_.push_back(std::make_unique<InternalForceConstraint>(model, *layout_, schedule_));
  costs_.push_back(std::make_unique<EffortCost>(model, *layout_, schedule_));
  if (settings.force_weight > 0.0)
    costs_.push_back(
        std::make_unique<ContactForceCost>(model, *layout_, schedule_, settings.force_weight));
  if (settings.smoothness_weight > 0.0)
    costs_.push_back(
        std::make_unique<SmoothnessCost>(model, *layout_, schedule_, settings.smoothness_weight));
  for (const auto& set : sets_) {
    offsets_.push_back(rows_);
    for (const auto& [r, c] : set->structure()) {
      jac_rows_.push_back(rows_ + r);
      jac_cols_.push_back(c);
    }
    rows_ += set->rows();
  }
  for (const auto& c : costs_) c->hessianStructure(hessian_);
  for (const auto& set : sets_) set->hessianStructure(hessian_);
}

void TrajectoryProblem::hessianValues(const ConstVectorRef& z, double sigma, const double* lambda,
                                      double* values) const {
  std::fill(values, values + hessian_.size(), 0.0);
  for (const auto& c : costs_) c->addHessian(z, sigma, values);
  for (std::size_t s = 0; s < sets_.size(); ++s)
    sets_[s]->addHessian(z, lambda + offsets_[s], values);
}

void TrajectoryProblem::constraintBounds(Eigen::VectorXd& lower, Eigen::VectorXd& upper) const {
  lower.resize(rows_);
  upper.resize(rows_);
  for (std::size_t s = 0; s < sets_.size(); ++s)
    sets_[s]->bounds(lower.segment(offsets_[s], sets_[s]->rows()),
                     upper.segment(offsets_[s], sets_[s]->rows()));
}

double TrajectoryProblem::objective(const ConstVectorRef& z) const {
  double J = 0.0;
  for (const auto& c : costs_) J += c->value(z);
  return J;
}

void TrajectoryProblem::gradient(const ConstVectorRef& z, VectorRef grad) const {
  grad.setZero();
  for (const auto& c : costs_) c->addGradient(z, grad);
}

void TrajectoryProblem::constraintValues(const ConstVectorRef& z, VectorRef g) const {
  for (std::size_t s = 0; s < sets_.size(); ++s)
    sets_[s]->values(z, g.segment(offsets_[s], sets_[s]->rows()));
}

void TrajectoryProblem::jacobianValues(const ConstVectorRef& z, double* values) const {
  for (const auto& set : sets_) {
    set->jacobian(z, values);
    values += set->structure().size();
  }
}

double TrajectoryProblem::effort(const ConstVectorRef& z) const { return costs_[0]->value(z); }

plan::Plan TrajectoryProblem::toPlan(const ConstVectorRef& z, const plan::Plan& input) const {
  const int n = model_.configDim(), nu = model_.controlDim(), m = model_.numFingers();
  plan::Plan out = input;
  out.segments.clear();
  out.samples.clear();
  for (int k = 0; k < layout_->intervals(); ++k) {
    const int j = schedule_.run_of_interval[k];
    plan::PlanSegment seg;
    seg.phase = schedule_.runs[j].phase;
    seg.duration = z[layout_->duration(j)] / schedule_.runs[j].intervals;
    seg.steps = static_cast<int>(std::lround(seg.duration / input.simulator.time_step));
    seg.tau = z.segment(layout_->tau(k), nu);
    seg.tau_end = z.segment(layout_->tau(k + 1), nu);
    seg.contacts = schedule_.runs[j].planned;  // the roles the plan stated, if it did
    out.segments.push_back(seg);
  }
  for (int k = 0; k < layout_->knots(); ++k) {
    plan::PlanSample s;
    s.t = variables_->knotTime(z, k);
    s.q = z.segment(layout_->q(k), n);
    s.v = z.segment(layout_->v(k), n);
    s.tau = z.segment(layout_->tau(k), nu);
    s.f_n = z.segment(layout_->fn(k), m);
    // Like the planner's samples: the phase of the interval that ends at the knot.
    s.phase = schedule_.runOf(k > 0 ? k - 1 : 0).phase;
    out.samples.push_back(s);
  }
  return out;
}

double planEffort(const RbsfModel& model, const plan::Plan& plan) {
  const VecU w = effortWeights(model);
  double J = 0.0;
  for (const plan::PlanSegment& seg : plan.segments) J += seg.duration * seg.tau.cwiseAbs2().dot(w);
  return J;
}

}  // namespace rbsf::trajopt
