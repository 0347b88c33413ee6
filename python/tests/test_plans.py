"""Planning, plan files and certificates from Python, against the command-line tool."""

import numpy as np
import pytest

import rbsf
from conftest import DEFAULT_CELL


def turn15_settings():
    """plan-reorientation's settings for conftest.TURN_15."""
    settings = rbsf.PlanSettings()
    settings.method = "support"
    settings.optimize = False
    settings.certificate.trials = 64
    return settings


def test_a_plan_made_in_python_is_the_tools_plan_byte_for_byte(model, plan_file):
    events = []
    problem = rbsf.Problem((0.1, 0.40, 0.0), (0.1, 0.40, rbsf.deg(-15)))
    result = rbsf.plan(model, problem, turn15_settings(), progress=events.append)
    assert result.status == "certified" and result.certified
    assert result.record.to_json(reproducible=True) == plan_file.read_text()
    kinds = [e.kind for e in events]
    assert kinds[0] == "stage" and "plan found" in kinds and kinds[-1] == "judged"


def test_a_plan_file_reads_into_arrays_and_writes_back_unchanged(plan_file, tmp_path):
    record = rbsf.PlanRecord.read(str(plan_file))
    plan = record.plan
    samples = plan.samples
    n = len(samples)
    assert samples.q.shape == (n, 7) and samples.tau.shape == (n, 4) and samples.f_n.shape == (n, 3)
    assert np.all(np.diff(samples.t) > 0) and samples.t[-1] == pytest.approx(plan.duration)
    assert plan.pivots >= 1 and plan.planned_phases.count("P") == plan.pivots
    assert len(plan.segment_starts) == len(plan.segments)
    assert all(len(s.roles) == 3 for s in plan.segments)
    roles = plan.sample_roles
    assert len(roles) == n and roles[0] == plan.segments[0].roles
    assert roles[-1] == plan.segments[-1].roles
    assert set(roles) == {s.roles for s in plan.segments if s.steps > 0}
    # The plan ends at its goal: the last sample's pose within the tolerances.
    assert np.hypot(*(samples.q[-1, :2] - [0.1, 0.40])) < 0.01
    assert abs(samples.q[-1, 2] - rbsf.deg(-15)) < rbsf.deg(2)
    out = tmp_path / "copy.json"
    record.write(str(out), reproducible=True)
    assert out.read_text() == plan_file.read_text()


def test_certify_from_python_repeats_the_files_certificate(model, plan_file):
    record = rbsf.PlanRecord.read(str(plan_file))
    settings = rbsf.CertificateSettings()
    settings.trials = 64
    again = rbsf.certify(model, record.plan, settings)
    theirs = record.certificate
    assert again.certified == theirs.certified
    assert (again.trials, again.successes) == (theirs.trials, theirs.successes)
    assert again.lower_bound == pytest.approx(theirs.lower_bound, abs=1e-6)
    assert again.worst.index == theirs.worst.index
    assert "certificate" in again.report


def test_a_replayed_trial_is_its_draw_run_closed_loop(default_cell, model, plan_file):
    plan = rbsf.PlanRecord.read(str(plan_file)).plan
    nominal, trace = rbsf.replay_trial(model, plan, -1)
    assert nominal.success and nominal.end == "done"
    assert trace.q.shape[1] == 7 and np.all(np.isfinite(trace.q))
    draw = rbsf.draw_trial(model, plan, 1, 3)
    assert draw["part_mass"] != default_cell.part_mass  # drawn within the uncertainty
    assert abs(draw["part_mass"] / 24.0 - 1.0) <= 0.05
    outcome, trace = rbsf.replay_trial(model, plan, 3)
    assert np.allclose(trace.q[0, :3], draw["q0"][:3], atol=2e-3)  # the drawn start
    assert outcome.index == 3


def test_bad_plan_inputs_raise_value_errors(model, tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"status": "exact"}')
    with pytest.raises(ValueError, match="bad.json"):
        rbsf.PlanRecord.read(str(bad))
    settings = rbsf.PlanSettings()
    with pytest.raises(ValueError, match="method: unknown planner 'RRTX'"):
        settings.method = "RRTX"
    with pytest.raises(ValueError, match="tolerance"):
        rbsf.Problem((0.1, 0.4, 0.0), (0.1, 0.4, 0.1), position_tolerance=-1.0)
    for key, value in (("max_expansions", -5), ("attempts", -1), ("friction_uses", [0.5, 1.5]),
                       ("simple_turns", [0.0])):
        with pytest.raises(ValueError, match=key):
            setattr(settings, key, value)
    problem = rbsf.Problem((0.1, 0.4, 0.0), (0.1, 0.4, 0.1))
    with pytest.raises(ValueError, match="pose: x must be finite"):
        problem.goal.x = float("nan")
    with pytest.raises(ValueError, match="start_theta"):
        problem.start_theta = float("inf")
    settings.time_limit = -1.0
    with pytest.raises(ValueError, match="time"):
        rbsf.plan(model, rbsf.Problem((0.1, 0.4, 0.0), (0.1, 0.4, 0.1)), settings)
    with pytest.raises(ValueError, match="goal"):  # a goal no finger reaches
        rbsf.plan(model, rbsf.Problem((0.1, 0.4, 0.0), (3.0, 0.4, 0.0)), rbsf.PlanSettings())


def test_the_benchmark_suites_load(default_cell):
    from conftest import SOURCE

    suite = rbsf.load_problem_suite(str(SOURCE / "cells" / "problems" / "quarter.yaml"))
    assert len(suite) >= 2 and all(p.name for p in suite)
    assert all(p.cell_path.endswith(".yaml") for p in suite)
    with pytest.raises(ValueError, match="nothing"):
        rbsf.load_problem_suite("nothing.yaml")
