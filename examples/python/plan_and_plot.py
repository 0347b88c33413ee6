#!/usr/bin/env python3
"""Plan the main job (the default part turned by -45 degrees), then plot the part's path
and the contact forces with matplotlib and save a PNG.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/plan_and_plot.py [--out plan.png]

The plan is certified (closed-loop trials under the cell's noise and uncertainty) before it
is plotted; the exit status is 0 for a certified plan, 4 for a plan that failed its
certificate (plotted, marked not certified), 3 when no plan reaches the goal.
"""

import argparse
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")  # files only: no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import rbsf  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cell", default=str(ROOT / "cells" / "default.yaml"))
    parser.add_argument("--turn", type=float, default=-45.0, help="degrees (default -45)")
    parser.add_argument("--max-expansions", type=int, default=100000,
                        help="the support planner's budget (default 100000, as scripts/rbsf.sh run)")
    parser.add_argument("--out", default="plan.png")
    args = parser.parse_args()

    model = rbsf.Model(args.cell)
    problem = rbsf.Problem((0.1, 0.40, 0.0), (0.1, 0.40, rbsf.deg(args.turn)))
    settings = rbsf.PlanSettings()
    settings.time_limit = 300.0
    settings.max_expansions = args.max_expansions
    result = rbsf.plan(model, problem, settings,
                       progress=lambda e: e.kind == "stage" and print("planning:", e.text))
    record = result.record
    if record is None or record.plan.status != "exact":
        print(f"no plan reaches the goal ({result.status})")
        return 3
    plan, certificate = record.plan, record.certificate
    print(certificate.report, end="")

    s = plan.samples
    fig, (path, angle, forces) = plt.subplots(3, 1, figsize=(8, 9), constrained_layout=True)
    path.plot(s.q[:, 0], s.q[:, 1], color="tab:blue")
    path.plot(*s.q[0, :2], "o", color="tab:green", markersize=11, label="start")
    path.plot(*s.q[-1, :2], "s", color="tab:red", label="end")
    path.set(xlabel="x [m]", ylabel="y [m]", title="the part's centre of mass", aspect="equal")
    path.legend()
    angle.plot(s.t, np.degrees(s.q[:, 2]), label="part phi")
    angle.plot(s.t, np.degrees(s.q[:, 3]), label="base theta")
    angle.set(xlabel="t [s]", ylabel="[deg]", title=f"planned phases {plan.planned_phases}")
    angle.legend()
    for i in range(model.num_fingers):
        forces.plot(s.t, s.f_n[:, i], label=f"finger {i + 1}")
    forces.set(xlabel="t [s]", ylabel="f_n [N]", title="normal contact forces")
    forces.legend()
    verdict = "certified" if certificate.certified else "NOT certified"
    fig.suptitle(f"{args.turn:+g} deg turn, {plan.duration:.1f} s, {plan.pivots} pivots: {verdict} "
                 f"({certificate.successes}/{certificate.trials} trials)")
    fig.savefig(args.out, dpi=100)
    print(f"wrote {args.out}")
    return 0 if certificate.certified else 4


if __name__ == "__main__":
    sys.exit(main())
