#pragma once
/// \file
/// \brief The parts of the Python module `rbsf._rbsf`, one per file (module.cpp calls them
///        in order).

#include <pybind11/pybind11.h>

#include "rbsf/planner/pipeline/reorientation_pipeline.h"

namespace rbsf::python {

void bindModel(pybind11::module_& m);         ///< cells, poses, the model, its analyses
void bindSimulator(pybind11::module_& m);     ///< the simulator: step and rollout
void bindPlans(pybind11::module_& m);         ///< plans, plan files, certificates, trials
void bindPlanSettings(pybind11::module_& m);  ///< the problem, PlanSettings, the suites
void bindPipeline(pybind11::module_& m);      ///< planning and what a run returns
void bindController(pybind11::module_& m);    ///< the controller facade and its status

/// \brief The pipeline's settings with plan-reorientation's defaults (the refinement on):
///        PlanSettings() and plan()'s default.
planner::PipelineSettings defaultPlanSettings();

}  // namespace rbsf::python
