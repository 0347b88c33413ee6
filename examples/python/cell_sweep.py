#!/usr/bin/env python3
"""Which finger spacings allow the default part's +90 degree turn? For each spacing of the
outer fingers (at -s, 0 and +s), plan the quarter suite's +90 degree goal with the support
planner within a budget of expansions and print the answer: a certified plan, a plan that
failed its certificate, or what the search reached and the rule that stopped it.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/cell_sweep.py \
        [--spacings 0.16,0.20,0.24] [--max-expansions 20000]

A search that finds nothing within its budget shows only that it ran out: the reach line
says where the part got and which rule refused the moves beyond.
"""

import argparse
import math
import pathlib

import rbsf

ROOT = pathlib.Path(__file__).resolve().parents[2]
GOAL = (-0.21, 0.43, rbsf.deg(90))  # cells/problems/quarter.yaml plus90deg


def answer(cell, max_expansions):
    """One line for one cell."""
    model = rbsf.Model(cell)
    settings = rbsf.PlanSettings()
    settings.method = "support"
    settings.optimize = False
    settings.time_limit = 600.0
    settings.max_expansions = max_expansions
    try:
        result = rbsf.plan(model, rbsf.Problem((0.1, 0.40, 0.0), GOAL), settings)
    except ValueError as error:  # a start the fingers cannot hold, a goal none reaches
        return f"refused: {error}"
    if result.certified:
        plan = result.record.plan
        return f"certified: {plan.pivots} pivots, {plan.duration:.1f} s ({result.record.certificate.verdict})"
    if result.status == "not certified":
        return f"a plan, NOT certified: {result.record.certificate.verdict}"
    if result.status == "approximate":  # a path whose closed-loop run missed the goal
        end = result.record.plan.samples.q[-1]
        return (f"approximate: a path whose run ends {math.hypot(end[0] - GOAL[0], end[1] - GOAL[1]):.3f} m "
                f"and {math.degrees(abs(end[2] - GOAL[2])):.1f} deg from the goal")
    reach = [a.reach for a in result.attempts if a.reach]
    return f"{result.status}: the search {reach[0] if reach else 'found no path'}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--spacings", default="0.16,0.20,0.24",
                        help="outer fingers' offsets s [m], comma-separated")
    parser.add_argument("--max-expansions", type=int, default=20000)
    args = parser.parse_args()
    base = rbsf.load_cell_dict(str(ROOT / "cells" / "default.yaml"))
    for s in (float(x) for x in args.spacings.split(",")):
        data = dict(base, fingers=[dict(f) for f in base["fingers"]])
        data["fingers"][0]["r"], data["fingers"][2]["r"] = -s, s
        cell = rbsf.cell_from_dict(data, label=f"spacing {s:g} m")
        print(f"fingers at -{s:g}, 0, +{s:g} m: {answer(cell, args.max_expansions)}", flush=True)


if __name__ == "__main__":
    main()
