#!/usr/bin/env python3
"""The Python module's costs against the C++ library's (BENCHMARKS.md "Python"):

  track():  the facade's track() with its status called from a Python loop, on the -15
            degree support plan and the ticks of BM_ControllerTrackLoadedPlanWithStatus (the
            plan's nominal trial, 1 ms apart, restarting each pass), against the same ticks
            through Controller.track_log (the loop in C++); the overhead is the difference of
            the medians per tick, the Python loop's own cost included.
  rollout:  a 10 s rollout at 1 kHz returned as numpy arrays, against BM_Rollout10s (the
            same rollout in C++, every sample kept).

Usage: PYTHONPATH=build/python /usr/bin/python3 bench/python_bench.py [--build build]
       [--repeats 7]. Medians over the repeats; the C++ rollout is build/bench/rbsf_micro_bench
run in turns with the Python one, so that both see the same machine and load.
"""

import argparse
import json
import pathlib
import statistics
import subprocess
import time

import numpy as np

import rbsf

ROOT = pathlib.Path(__file__).resolve().parents[1]


def cpp_rollout(build):
    """Real time [ns] of BM_Rollout10s, one run of at least 0.3 s."""
    out = subprocess.run(
        [str(build / "bench" / "rbsf_micro_bench"), "--benchmark_filter=BM_Rollout10s$",
         "--benchmark_min_time=0.3", "--benchmark_format=json"],
        check=True, capture_output=True, text=True).stdout
    b = json.loads(out)["benchmarks"][0]
    return b["real_time"] * {"ns": 1.0, "us": 1e3, "ms": 1e6}[b["time_unit"]]


def track_medians(repeats, calls=20000):
    """Median time per tick [ns] of track() from a Python loop and of track_log()."""
    model = rbsf.Model(str(ROOT / "cells" / "default.yaml"))
    settings = rbsf.PlanSettings()
    settings.method, settings.optimize = "support", False
    problem = rbsf.Problem((0.1, 0.40, 0.0), (0.1, 0.40, rbsf.deg(-15)))
    record = rbsf.plan(model, problem, settings).record
    controller = rbsf.Controller(str(ROOT / "cells" / "default.yaml"))
    controller.load(record)
    _, trace = rbsf.replay_trial(model, record.plan, -1)
    ticks = [record.plan.q0[3:].copy()] + [np.ascontiguousarray(q[3:]) for q in trace.q[:-1]]
    times = [1e-3 * n for n in range(len(ticks))]
    tau, status = np.zeros(model.control_dim), rbsf.ExecutionStatus()
    track = controller.track
    n = len(ticks)
    log_times = np.array([times[k % n] for k in range(calls)])
    log_joints = np.array([ticks[k % n] for k in range(calls)])
    python, cpp = [], []
    for _ in range(repeats):
        controller.start()
        start = time.perf_counter_ns()
        for k in range(calls):
            i = k % n
            track(times[i], ticks[i], tau, status)
        python.append((time.perf_counter_ns() - start) / calls)
        controller.start()
        start = time.perf_counter_ns()
        controller.track_log(log_times, log_joints)
        cpp.append((time.perf_counter_ns() - start) / calls)
    return statistics.median(python), statistics.median(cpp)


def rollout_medians(build, repeats, runs=10):
    """Median time [ns] of the 10 s rollout from Python and in C++ (BM_Rollout10s), taken in
    turns so that both see the same load, and the final x of the Python run (the C++ run's
    end_x)."""
    model = rbsf.Model(str(ROOT / "cells" / "default.yaml"))
    q = model.resting_configuration((0.1, 0.40, 0.0))
    tau = model.analyze(q, np.zeros(7), np.zeros(4)).holding.tau[np.newaxis, :]
    sim = rbsf.Simulator(model)
    python, cpp = [], []
    for _ in range(repeats):
        cpp.append(cpp_rollout(build))
        times = []
        for _ in range(runs):
            start = time.perf_counter_ns()
            run = sim.rollout(q, tau, [10000])
            times.append(time.perf_counter_ns() - start)
        python.append(statistics.median(times))
    assert len(run) == 10000
    return statistics.median(python), statistics.median(cpp), run.q[-1, 0]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default=str(ROOT / "build"))
    parser.add_argument("--repeats", type=int, default=7)
    args = parser.parse_args()
    py_track, c_track = track_medians(args.repeats)
    py_rollout, c_rollout, end_x = rollout_medians(pathlib.Path(args.build), args.repeats)
    print(f"track() with status: Python {py_track / 1e3:.2f} us, C++ loop {c_track / 1e3:.2f} us, "
          f"overhead {(py_track - c_track) / 1e3:.2f} us per call (goal: under 3 us)")
    print(f"10 s rollout at 1 kHz: Python {py_rollout / 1e6:.2f} ms, C++ {c_rollout / 1e6:.2f} ms, "
          f"ratio {py_rollout / c_rollout:.2f} (goal: under 1.2); final x {end_x:.6f} m")


if __name__ == "__main__":
    main()
