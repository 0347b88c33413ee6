#!/usr/bin/python3
"""Success rate against time per planner, one panel per problem, from a Planner Arena
database written by rbsf-bench (benchmark.db: tables experiments, plannerConfigs, runs).

A run counts as a success at time t when it solved the problem exactly (runs.solved) within
t seconds (runs.time). Needs python3-matplotlib (Debian).

    scripts/plot-success.py rbsf-bench-out/benchmark.db docs/success-default.svg
"""
import sqlite3
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.stderr.write("usage: plot-success.py BENCHMARK_DB OUTPUT.(svg|png)\n")
        return 2
    db = sqlite3.connect(sys.argv[1])
    experiments = db.execute("SELECT id, name, timelimit FROM experiments ORDER BY id").fetchall()
    planners = db.execute("SELECT id, name FROM plannerConfigs ORDER BY id").fetchall()
    if not experiments:
        sys.stderr.write("plot-success.py: no experiments in %s\n" % sys.argv[1])
        return 2
    fig, axes = plt.subplots(1, len(experiments), figsize=(4.2 * len(experiments), 3.9),
                             sharey=True, squeeze=False)
    for ax, (eid, ename, limit) in zip(axes[0], experiments):
        for pid, pname in planners:
            rows = db.execute("SELECT time, solved FROM runs WHERE experimentid=? AND plannerid=?",
                              (eid, pid)).fetchall()
            if not rows:
                continue
            n = len(rows)
            times = sorted(t for t, s in rows if s)
            xs, ys = [0.0], [0.0]
            for k, t in enumerate(times, 1):
                xs += [t, t]
                ys += [ys[-1], 100.0 * k / n]
            xs.append(limit)
            ys.append(ys[-1])
            ax.plot(xs, ys, label="%s (%d runs)" % (pname.replace("control_", ""), n))
        ax.set_title(ename)
        ax.set_xlabel("planning time [s]")
        ax.set_xlim(0, limit)
        ax.set_ylim(0, 100)
        ax.grid(alpha=0.3)
    axes[0][0].set_ylabel("success rate [%]")
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=max(1, len(labels)), fontsize=9)
    fig.tight_layout(rect=(0, 0.08, 1, 1), w_pad=2.0)
    fig.savefig(sys.argv[2])
    return 0


if __name__ == "__main__":
    sys.exit(main())
