// Planning from Python: the pipeline (plan, refine, certify) on a worker thread while the
// caller's thread, GIL released between looks, delivers progress events, watches Ctrl-C
// and a cancel event; and what a run returns.
#include <pybind11/stl.h>

#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "arrays.h"
#include "bindings.h"
#include "rbsf/planner/pipeline/reorientation_pipeline.h"

namespace rbsf::python {

namespace {

/// One pipeline event as plain values (the event's references die with it).
struct PlanEvent {
  std::string kind;  ///< "stage", "search", "plan found", "refined", "judged"
  std::string text;  ///< what a progress line says
  double elapsed = 0.0;
  std::uint64_t propagations = 0;
  double best_distance = 0.0;
};

PlanEvent eventOf(const planner::PipelineEvent& e) {
  PlanEvent out;
  if (const auto* s = std::get_if<planner::StageStarted>(&e)) {
    out.kind = "stage";
    out.text = planner::stageText(s->stage, s->attempt.method(), s->attempt.seed);
  } else if (const auto* p = std::get_if<planner::SearchProgress>(&e)) {
    out.kind = "search";
    out.elapsed = p->progress.elapsed, out.propagations = p->progress.propagations;
    out.best_distance = p->progress.best_distance;
    out.text = "closest " + std::to_string(out.best_distance) + " (1 = 1 cm or 2 deg)";
  } else if (const auto* f = std::get_if<planner::PlanFound>(&e)) {
    out.kind = "plan found";
    out.text = std::string(plan::toString(f->plan.status)) + " plan, planned phases " +
               f->plan.plannedPhases() + ", " + std::to_string(f->plan.pivots()) + " pivots";
  } else if (const auto* r = std::get_if<planner::PlanRefined>(&e)) {
    out.kind = "refined";
    out.text = r->refinement.refined ? "the refined plan kept" : "the planner's plan kept";
  } else if (const auto* j = std::get_if<planner::AttemptJudged>(&e)) {
    out.kind = "judged";
    out.text =
        j->attempt.certificate.ran ? plan::verdictText(j->attempt.certificate) : j->attempt.note;
  }
  return out;
}

/// The pipeline's run on a worker thread (file comment). Ctrl-C or an exception in the
/// progress callback cancel the run, wait for it and are raised; a set `cancel` event
/// cancels it and returns its outcome (status "cancelled").
planner::PipelineOutcome runPipeline(const RbsfModel& model,
                                     const planner::PipelineSettings& settings,
                                     const planner::Problem& problem, const py::object& progress,
                                     const py::object& cancel_event) {
  planner::ReorientationPipeline pipeline(model, settings);  // bad settings: ValueError here
  if (!cancel_event.is_none() && !py::hasattr(cancel_event, "is_set"))
    throw InputError("cancel: expected an object with is_set(), such as threading.Event");
  if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
    throw InputError("progress: expected a callable taking a PlanEvent");
  std::atomic<bool> cancel{false}, done{false};
  std::mutex mutex;
  std::condition_variable wake;
  std::vector<PlanEvent> queue;
  planner::PipelineOutcome outcome;
  std::exception_ptr failure;
  planner::RunContext context;
  context.cancel = &cancel;
  if (!progress.is_none())
    context.on_event = [&](const planner::PipelineEvent& e) {
      PlanEvent event = eventOf(e);
      std::lock_guard<std::mutex> lock(mutex);
      queue.push_back(std::move(event));
      wake.notify_one();
    };
  std::thread worker([&] {
    try {
      outcome = pipeline.run(problem, context);
    } catch (...) {
      failure = std::current_exception();
    }
    std::lock_guard<std::mutex> lock(mutex);
    done = true;
    wake.notify_one();
  });
  // Ctrl-C, or an exception of the callback or the cancel event: the run is cancelled and,
  // once the worker has stopped, it is raised.
  std::exception_ptr raised;
  const auto stop = [&](std::exception_ptr error) {
    if (!raised) raised = error;
    cancel = true;
  };
  const auto deliver = [&] {
    std::vector<PlanEvent> events;
    {
      std::lock_guard<std::mutex> lock(mutex);
      events.swap(queue);
    }
    for (const PlanEvent& e : events) {
      if (raised) return;
      try {
        progress(e);
      } catch (...) {
        stop(std::current_exception());
      }
    }
  };
  try {
    while (true) {
      {
        py::gil_scoped_release release;
        std::unique_lock<std::mutex> lock(mutex);
        wake.wait_for(lock, std::chrono::milliseconds(50),
                      [&] { return done.load() || !queue.empty(); });
      }
      deliver();
      if (done) break;
      if (raised) continue;
      if (PyErr_CheckSignals() != 0)  // the KeyboardInterrupt the signal handler set
        stop(std::make_exception_ptr(py::error_already_set()));
      else if (!cancel_event.is_none() && py::bool_(cancel_event.attr("is_set")()))
        cancel = true;
    }
  } catch (...) {
    stop(std::current_exception());
  }
  {
    py::gil_scoped_release release;
    worker.join();
  }
  deliver();
  if (raised) std::rethrow_exception(raised);
  if (failure) std::rethrow_exception(failure);
  return outcome;
}

}  // namespace

void bindPipeline(py::module_& m) {
  py::class_<PlanEvent>(m, "PlanEvent", "One event of a planning run, for progress callbacks.")
      .def_readonly("kind", &PlanEvent::kind, "stage, search, plan found, refined or judged")
      .def_readonly("text", &PlanEvent::text)
      .def_readonly("elapsed", &PlanEvent::elapsed, "search: seconds so far")
      .def_readonly("propagations", &PlanEvent::propagations)
      .def_readonly("best_distance", &PlanEvent::best_distance, "search: tolerance units")
      .def("__repr__",
           [](const PlanEvent& e) { return "PlanEvent(" + e.kind + ": " + e.text + ")"; });

  py::class_<planner::PipelineAttempt>(m, "Attempt", "One search and its plan's certificate.")
      .def_property_readonly("search",
                             [](const planner::PipelineAttempt& a) {
                               return a.search == planner::SearchKind::kSupport ? "support"
                                                                                : "kinodynamic";
                             })
      .def_readonly("planner", &planner::PipelineAttempt::planner)
      .def_readonly("seed", &planner::PipelineAttempt::seed)
      .def_readonly("found", &planner::PipelineAttempt::found)
      .def_readonly("exact", &planner::PipelineAttempt::exact)
      .def_readonly("refined", &planner::PipelineAttempt::refined)
      .def_readonly("cancelled", &planner::PipelineAttempt::cancelled)
      .def_readonly("search_time", &planner::PipelineAttempt::search_time, "[s]")
      .def_readonly("wall_time", &planner::PipelineAttempt::wall_time, "[s]")
      .def_readonly("expansions", &planner::PipelineAttempt::expansions)
      .def_readonly("phases", &planner::PipelineAttempt::phases)
      .def_readonly("certificate", &planner::PipelineAttempt::certificate)
      .def_readonly("note", &planner::PipelineAttempt::note)
      .def_property_readonly(
          "reach",
          [](const planner::PipelineAttempt& a) -> py::object {
            if (!a.reach.measured) return py::none();
            return py::str(a.reach.text());
          },
          "what the support searches reached and the rule that refused most moves beyond the "
          "closest pose (the reach answer when they found no path); None when none ran");

  py::class_<planner::PipelineOutcome>(m, "PlanResult", "How a planning run ended.")
      .def_property_readonly(
          "status",
          [](const planner::PipelineOutcome& o) {
            return std::string(planner::statusText(o.status));
          },
          "certified, not certified, approximate, no plan or cancelled")
      .def_property_readonly("certified",
                             [](const planner::PipelineOutcome& o) {
                               return o.status == planner::PipelineStatus::kCertified;
                             })
      .def_property_readonly(
          "record",
          [](const planner::PipelineOutcome& o) -> py::object {
            if (o.status == planner::PipelineStatus::kNoPlan || o.record.plan.samples.empty())
              return py::none();
            return py::cast(o.record);
          },
          "the plan kept with its certificate (None: no plan)")
      .def_readonly("attempts", &planner::PipelineOutcome::attempts)
      .def_readonly("chosen", &planner::PipelineOutcome::chosen,
                    "index of the attempt kept (-1: none)")
      .def_readonly("best_distance", &planner::PipelineOutcome::best_distance)
      .def_readonly("wall_time", &planner::PipelineOutcome::wall_time, "[s]")
      .def("__repr__", [](const planner::PipelineOutcome& o) {
        return "PlanResult(" + std::string(planner::statusText(o.status)) + ")";
      });

  m.def(
      "plan",
      [](const RbsfModel& model, const planner::Problem& problem,
         const planner::PipelineSettings& settings, const py::object& progress,
         const py::object& cancel) {
        return runPipeline(model, settings, problem, progress, cancel);
      },
      py::arg("model"), py::arg("problem"), py::arg("settings") = defaultPlanSettings(),
      py::arg("progress") = py::none(), py::arg("cancel") = py::none(),
      "Plan, refine and certify (the pipeline of plan-reorientation) on a worker thread. "
      "`progress(event)` is called on this thread with each PlanEvent; `cancel` is any object "
      "with is_set() (threading.Event): once set, the run stops and returns status "
      "'cancelled'. Ctrl-C stops the run and raises KeyboardInterrupt within a second.");
}

}  // namespace rbsf::python
