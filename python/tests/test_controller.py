"""The controller facade driving a plant written in Python."""

import numpy as np
import pytest

import rbsf
from conftest import SOURCE


def run_closed_loop(controller, model, plan, push_at=None):
    """Step rbsf.Simulator as a Python plant with controller.track() every period; returns the
    last state and the statuses' verdicts."""
    sim = rbsf.Simulator(model)
    state = rbsf.SimState(plan.q0)
    status = rbsf.ExecutionStatus()
    tau = np.zeros(model.control_dim)
    verdicts = []
    h = controller.time_step
    for k in range(int(round((plan.duration + 1.0) / h))):
        t = k * h
        joints = state.q[3:]
        controller.track(t, joints, out=tau, status=status)
        verdicts.append(status.verdict)
        sim.step(state, tau)
    return state, verdicts


def test_a_python_plant_runs_the_plan_to_its_goal(model, plan_file):
    controller = rbsf.Controller(str(SOURCE / "cells" / "default.yaml"))
    controller.load_file(str(plan_file))
    plan = rbsf.PlanRecord.read(str(plan_file)).plan
    assert controller.duration == pytest.approx(plan.duration)
    state, verdicts = run_closed_loop(controller, model, plan)
    assert np.hypot(*(state.q[:2] - [0.1, 0.40])) < 0.01
    assert abs(state.q[2] - rbsf.deg(-15)) < rbsf.deg(2)
    assert verdicts[-1] == "done" and "leaving" not in verdicts and "holding" not in verdicts
    reference = controller.sample(plan.duration)
    assert reference["q"][2] == pytest.approx(plan.samples.q[-1, 2], abs=1e-9)


def test_a_commanded_hold_rests_the_part(model, plan_file):
    controller = rbsf.Controller(rbsf.Cell.from_file(str(SOURCE / "cells" / "default.yaml")))
    controller.load_file(str(plan_file))
    plan = rbsf.PlanRecord.read(str(plan_file)).plan
    sim, state = rbsf.Simulator(model), rbsf.SimState(plan.q0)
    status, tau = rbsf.ExecutionStatus(), np.zeros(4)
    h = controller.time_step
    for k in range(int(round((plan.duration / 2 + 1.0) / h))):
        if k == int(round(plan.duration / 2 / h)):
            controller.hold()
        controller.track(k * h, state.q[3:], out=tau, status=status)
        sim.step(state, tau)
    assert status.verdict == "holding" and status.hold_reason == "commanded"
    pose, theta = controller.held_state()
    assert np.hypot(pose.x - state.q[0], pose.y - state.q[1]) < 0.01
    assert np.abs(state.v[:3]).max() < 0.01  # at rest


def test_bad_controller_inputs_raise_and_nan_readings_are_bridged(model, plan_file, tmp_path):
    controller = rbsf.Controller(str(SOURCE / "cells" / "default.yaml"))
    with pytest.raises(RuntimeError, match="no plan"):
        controller.track(0.0, np.zeros(4))
    data = rbsf.load_cell_dict(str(SOURCE / "cells" / "default.yaml"))
    data["friction"]["static"] = 0.3
    other = rbsf.Controller(rbsf.cell_from_dict(data))
    with pytest.raises(ValueError, match="static friction mu_s is 0.5 in the plan, 0.3"):
        other.load_file(str(plan_file))
    controller.load_file(str(plan_file))
    q0 = rbsf.PlanRecord.read(str(plan_file)).plan.q0
    with pytest.raises(ValueError, match="joints: expected an array of 4"):
        controller.track(0.0, np.zeros(3))
    status = rbsf.ExecutionStatus()
    tau = controller.track(0.0, q0[3:], status=status)
    reading = q0[3:].copy()
    reading[1] = np.nan
    tau = controller.track(0.001, reading, status=status)  # bridged by the last good reading
    assert np.all(np.isfinite(tau)) and "joint" in status.flags_text
    for out in (np.zeros(2), np.zeros(4, dtype=np.float32), np.zeros(8)[::2], [0.0] * 4):
        with pytest.raises(ValueError, match="out: expected a writeable, contiguous float64"):
            controller.track(0.002, q0[3:], out=out)
    with pytest.raises(ValueError, match="status: expected an rbsf.ExecutionStatus"):
        controller.track(0.002, q0[3:], status={})


def test_a_log_replayed_in_cpp_gives_the_inputs_of_the_python_loop(model, plan_file):
    # Two loops over the same readings: track() per tick from Python, and track_log().
    plan = rbsf.PlanRecord.read(str(plan_file)).plan
    _, trace = rbsf.replay_trial(model, plan, -1)
    joints = np.vstack([plan.q0[3:], trace.q[:1999, 3:]])
    times = 1e-3 * np.arange(len(joints))
    controller = rbsf.Controller(str(SOURCE / "cells" / "default.yaml"))
    controller.load_file(str(plan_file))
    each = np.array([controller.track(t, j) for t, j in zip(times, joints)])
    controller.start()
    logged, verdicts = controller.track_log(times, joints)
    assert np.array_equal(each, logged)
    assert set(verdicts) <= {0, 1}  # on plan or degraded along the nominal run
    with pytest.raises(ValueError, match="track_log"):
        controller.track_log(times, joints[:, :3])
