"""The simulator from Python: the same bits as the C++ tool, step by step or in one call."""

import subprocess

import numpy as np
import pytest

import rbsf
from conftest import DEFAULT_CELL, SOURCE, tool

CONTROLS = SOURCE / "cells" / "default_controls.csv"


def controls(h):
    """The controls file's rows and their steps, by rbsf-simulate's rule: segment j ends at
    step round(sum of durations up to j / h)."""
    lines = [l for l in CONTROLS.read_text().splitlines() if l and not l.startswith("#")]
    table = np.array([[float(x) for x in l.split(",")] for l in lines[1:]])
    ends = np.rint(np.cumsum(table[:, 0]) / h).astype(int)
    return table[:, 1:], np.diff(np.concatenate([[0], ends])).tolist()


def test_a_rollout_equals_the_cpp_tool_to_the_last_bit(model, tmp_path):
    out = tmp_path / "run.csv"
    subprocess.run([tool("rbsf-simulate"), "--cell", str(DEFAULT_CELL), "--start", "0.1,0.40,0",
                    "--controls", str(CONTROLS), "--out", str(out)], check=True,
                   stdout=subprocess.DEVNULL)
    reference = np.loadtxt(out, delimiter=",", skiprows=1, usecols=range(0, 1 + 7 + 7 + 4 + 3))
    tau, steps = controls(1e-3)
    run = rbsf.Simulator(model).rollout(model.resting_configuration((0.1, 0.40, 0.0)), tau, steps)
    assert len(run) == len(reference)
    ours = np.column_stack([run.t, run.q, run.v, run.tau, run.f_n])
    assert np.array_equal(ours, reference)  # every bit: the CSV carries 17 digits


def test_steps_from_python_resume_a_rollout_bit_for_bit(model):
    sim = rbsf.Simulator(model)
    q = model.resting_configuration((0.1, 0.40, 0.0))
    tau = np.array([[5.0, 30.0, 60.0, 170.0], [-3.0, 20.0, 90.0, 140.0]])
    whole = sim.rollout(q, tau, [200, 300])
    first = sim.rollout(q, tau[:1], [200])
    state = first.final_state.copy()
    for _ in range(300):
        sim.step(state, tau[1])
    assert np.array_equal(state.q, whole.q[-1]) and np.array_equal(state.v, whole.v[-1])
    assert state.t == whole.t[-1]


def test_a_part_that_falls_ends_the_rollout(model):
    sim = rbsf.Simulator(model)
    q = model.resting_configuration((0.1, 0.40, 0.0))
    run = sim.rollout(q, np.array([[0.0, -800.0, -800.0, -800.0]]), [3000])
    assert 0 < run.fell_at < 3.0 and len(run) < 3000 and run.q.shape == (len(run), 7)
    assert run.phase[-1] == 3  # unsupported


def test_bad_rollout_inputs_raise_value_errors(model):
    sim = rbsf.Simulator(model)
    q = model.resting_configuration((0.1, 0.40, 0.0))
    with pytest.raises(ValueError, match=r"tau: expected an array of shape \(segments, 4\)"):
        sim.rollout(q, np.zeros((2, 3)))
    with pytest.raises(ValueError, match="tau: entry 5 is not finite"):
        sim.rollout(q, np.array([[0, 0, 0, 0], [0, np.nan, 0, 0]], dtype=float))
    with pytest.raises(ValueError, match="steps: expected 1 counts"):
        sim.rollout(q, np.zeros((1, 4)), [1, 2])
    with pytest.raises(ValueError, match="steps: entry 0"):
        sim.rollout(q, np.zeros((1, 4)), [0])
    with pytest.raises(ValueError, match="start"):
        sim.rollout(np.zeros(5), np.zeros((1, 4)))
    with pytest.raises(ValueError, match="q: expected an array of m \\+ 4"):
        rbsf.SimState(np.zeros(40))
