#!/usr/bin/env python3
"""Every planning figure README's status states, from one command (scripts/rbsf.sh status).

Runs the release build's plan-reorientation and rbsf-replay on the default cell, as a cell
engineer would, and prints a Markdown table per group: the certified turns of the general
support search with the refinement's verdict and effort, the simple turns, the largest
positive turns, the 256-draw rates of the refined and the planner's plans on the same fresh
draws, and the main job's exit status and wall time. --suites adds the pipeline bench's
default, quarter and hard suites (about 15 minutes more). Plans go to <build>/status/; the
tables also to <build>/status/status.md. Budgets, not the clock, end every search, so the
figures do not depend on the machine's load; the wall times do.

Exit status: 0 when every run ended (whatever its verdict); 1 when a tool crashed or its
output could not be read; 2 for bad options.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import time

START = "0.1,0.40,0"
SUPPORT = ["--planner", "support", "--time-limit", "3600", "--max-expansions", "100000"]
SIMPLE = SUPPORT + ["--simple-turns", "0.6"]
# The largest positive turns one-slider pivots allow (docs/notes, the rest-reach bench).
POSITIVE = [(0.0765, 0.4026, 45), (-0.0303, 0.4087, 60), (-0.1350, 0.3869, 75),
            (-0.1901, 0.4292, 78.75)]


class Failed(Exception):
    """A tool crashed or wrote nothing readable."""


def plan(tools, cell, out_dir, name, goal, extra):
    """Plan and certify one turn; returns the row's figures."""
    out = os.path.join(out_dir, re.sub(r"[^A-Za-z0-9.+-]+", "_", name) + ".json")
    args = [os.path.join(tools, "plan-reorientation"), "--cell", cell, "--start", START,
            "--goal", goal, "--out", out] + extra
    began = time.monotonic()
    r = subprocess.run(args, capture_output=True, text=True)
    wall = time.monotonic() - began
    if r.returncode not in (0, 3, 4):
        raise Failed(f"{name}: plan-reorientation exited {r.returncode}: {r.stderr.strip()}")
    row = {"name": name, "exit": r.returncode, "wall": wall, "pivots": "-", "written": "-",
           "certificate": "no plan", "planner": "-", "effort": "-"}
    m = re.search(r"(\d+) pivots?", r.stdout)
    if m:
        row["pivots"] = m.group(1)
    m = re.search(r"^planner's plan: (?:NOT )?certified: (\d+/\d+)", r.stdout, re.M)
    if m:
        row["planner"] = m.group(1)
    if r.returncode == 3 or not os.path.exists(out):
        return row
    with open(out) as f:
        j = json.load(f)
    c = j.get("certificate", {})
    row["certificate"] = "%d/%d%s" % (c.get("successes", 0), c.get("trials", 0),
                                      " certified" if c.get("certified") else "")
    o = j.get("optimization")
    if o:
        row["written"] = "refined" if o.get("chosen") else "planner's"
        if o.get("cost_before"):  # the refinement's effort over the planner's
            effort = "%.2f" % (o["cost_after"] / o["cost_before"])
            row["effort"] = effort if o.get("chosen") else f"({effort}, not kept)"
    else:
        row["written"] = "planner's (not optimised)"
    row["plan"] = out
    return row


def replay(tools, cell, plan_file, trials=256, seed=2):
    """Successes of a plan on fresh draws (seed 2: not the certificate's)."""
    r = subprocess.run([os.path.join(tools, "rbsf-replay"), "--cell", cell, "--plan", plan_file,
                        "--trials", str(trials), "--seed", str(seed)], capture_output=True,
                       text=True)
    m = re.search(r"(\d+)/(\d+) trials succeeded", r.stdout + r.stderr)
    if r.returncode not in (0, 4) or not m:
        raise Failed(f"rbsf-replay {plan_file}: exit {r.returncode}: {r.stderr.strip()}")
    return f"{m.group(1)}/{m.group(2)}"


def table(title, rows, columns):
    lines = [f"### {title}", "", "| " + " | ".join(h for h, _ in columns) + " |",
             "|" + "---|" * len(columns)]
    for row in rows:
        lines.append("| " + " | ".join(str(fmt(row)) for _, fmt in columns) + " |")
    return "\n".join(lines) + "\n"


PLAN_COLUMNS = [("turn", lambda r: r["name"]), ("pivots", lambda r: r["pivots"]),
                ("written", lambda r: r["written"]), ("certificate", lambda r: r["certificate"]),
                ("planner's plan", lambda r: r["planner"]), ("effort", lambda r: r["effort"]),
                ("exit", lambda r: r["exit"]), ("wall s", lambda r: "%.1f" % r["wall"])]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default="build", help="the release build folder (default build)")
    ap.add_argument("--cell", default="cells/default.yaml")
    ap.add_argument("--suites", action="store_true", help="also the pipeline bench's suites")
    a = ap.parse_args()
    tools = os.path.join(a.build, "tools")
    if not os.path.exists(os.path.join(tools, "plan-reorientation")) or not os.path.exists(a.cell):
        print(f"status: no {tools}/plan-reorientation or no {a.cell}: build first", file=sys.stderr)
        return 2
    out_dir = os.path.join(a.build, "status")
    os.makedirs(out_dir, exist_ok=True)
    report = []

    def emit(text):
        print(text, flush=True)
        report.append(text)

    main_job = plan(tools, a.cell, out_dir, "main job -45", "0.1,0.40,-45deg",
                    ["--time-limit", "300", "--max-expansions", "100000"])
    emit(table("The main job (scripts/rbsf.sh run)", [main_job], PLAN_COLUMNS))
    general = [plan(tools, a.cell, out_dir, f"{g}deg", f"0.1,0.40,{g}deg", SUPPORT)
               for g in (-5, -10, -15, -20, -25, -30, -35, -40, -45, -60)]
    emit(table("General support search, refined where at least as good", general, PLAN_COLUMNS))
    simple = [plan(tools, a.cell, out_dir, f"simple {g}deg", f"0.1,0.40,{g}deg", SIMPLE)
              for g in (5, -10, -15, -20)]
    simple += [plan(tools, a.cell, out_dir, f"simple +{t}deg", f"{x},{y},{t}deg", SIMPLE)
               for x, y, t in POSITIVE]
    emit(table("Simple turns (--simple-turns 0.6)", simple, PLAN_COLUMNS))

    # The same fresh draws for the refined plan and the planner's.
    draws = []
    for g in (-15, -30, -45):
        row = next(r for r in general if r["name"] == f"{g}deg")
        unrefined = plan(tools, a.cell, out_dir, f"{g}deg planner", f"0.1,0.40,{g}deg",
                         SUPPORT + ["--no-optimize"])
        draws.append({"name": f"{g}deg", "written": row["written"],
                      "rate": replay(tools, a.cell, row["plan"]) if "plan" in row else "-",
                      "planner": replay(tools, a.cell, unrefined["plan"])})
    five = next(r for r in simple if r["name"] == "simple 5deg")
    if "plan" in five:
        draws.append({"name": "simple +5deg", "written": five["written"],
                      "rate": replay(tools, a.cell, five["plan"]), "planner": "-"})
    emit(table("256 fresh draws (rbsf-replay --trials 256 --seed 2)", draws,
               [("turn", lambda r: r["name"]), ("written", lambda r: r["written"]),
                ("written plan", lambda r: r["rate"]), ("planner's plan", lambda r: r["planner"])]))

    if a.suites:
        bench = os.path.join(a.build, "bench", "rbsf_pipeline_bench")
        for suite, seeds in (("cells/problems/default.yaml", "2"),
                             ("cells/problems/quarter.yaml", "2"), ("cells/problems/hard.yaml", "1")):
            r = subprocess.run([bench, "--problems", suite, "--seeds", seeds], capture_output=True,
                               text=True)
            if r.returncode != 0:
                raise Failed(f"{bench} {suite}: exit {r.returncode}: {r.stderr.strip()}")
            emit(f"### {suite}\n\n```\n{r.stdout.strip()}\n```\n")
    with open(os.path.join(out_dir, "status.md"), "w") as f:
        f.write("\n".join(report))
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except Failed as e:
        print(f"status: {e}", file=sys.stderr)
        sys.exit(1)
