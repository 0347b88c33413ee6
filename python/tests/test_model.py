"""Cells, the model and its analyses from Python."""

import math

import numpy as np
import pytest

import rbsf
from conftest import DEFAULT_CELL


def test_a_cell_from_a_dict_is_the_cell_of_its_file(default_cell):
    cell = rbsf.cell_from_dict(rbsf.load_cell_dict(str(DEFAULT_CELL)))
    assert cell.num_fingers == default_cell.num_fingers == 3
    assert [f.r for f in cell.fingers] == [f.r for f in default_cell.fingers]
    assert (cell.part_mass, cell.part_inertia, cell.mu_static) == (24.0, 0.675, 0.5)
    assert cell.shape == "ellipse"


def test_a_bad_cell_dict_raises_value_error_naming_the_key():
    data = rbsf.load_cell_dict(str(DEFAULT_CELL))
    data["fingers"][1]["mass"] = -2.0
    with pytest.raises(ValueError, match=r"fingers\[1\]\.mass"):
        rbsf.cell_from_dict(data)
    del data["object"]
    with pytest.raises(ValueError, match="object"):
        rbsf.cell_from_dict(data)
    data = rbsf.load_cell_dict(str(DEFAULT_CELL))
    data["gravity"] = float("nan")
    with pytest.raises(ValueError, match="finite"):
        rbsf.cell_from_dict(data)
    with pytest.raises(ValueError, match="dict"):
        rbsf.cell_from_dict([1, 2])
    with pytest.raises(ValueError, match="nothing.yaml"):
        rbsf.Cell.from_file("nothing.yaml")


def test_a_nan_or_a_wrong_shape_in_an_input_array_raises(model):
    q = model.resting_configuration((0.1, 0.40, 0.0))
    v, tau = np.zeros(7), np.zeros(4)
    bad = q.copy()
    bad[2] = np.nan
    with pytest.raises(ValueError, match="q: entry 2 is not finite"):
        model.analyze(bad, v, tau)
    with pytest.raises(ValueError, match="tau: expected an array of 4 numbers"):
        model.analyze(q, v, np.zeros((2, 4)))
    with pytest.raises(ValueError, match="finger"):
        model.fingertip(q, 3)
    with pytest.raises(ValueError, match="pose: expected 3 numbers"):
        rbsf.Pose((0.1, 0.4))
    with pytest.raises(TypeError):  # not a pose: pybind11's own refusal
        model.resting_configuration((0.1, 0.4))


def test_energy_agrees_with_the_mass_matrix(model):
    # Two computations: the model's kinetic energy and 1/2 v^T M v from its mass matrix.
    rng = np.random.default_rng(3)
    q = model.resting_configuration((0.1, 0.40, 0.2), 0.1)
    for _ in range(5):
        v = rng.normal(size=7)
        kinetic = model.energy(q, v) - model.energy(q, np.zeros(7))
        mass = model.mass_matrix(q)
        assert np.allclose(mass, mass.T)
        assert kinetic == pytest.approx(0.5 * v @ mass @ v, rel=1e-12)


def test_the_holding_inputs_hold_the_part_in_the_simulator(model):
    q = model.resting_configuration((0.1, 0.40, 0.0), 0.0)
    analysis = model.analyze(q, np.zeros(7), np.zeros(4))
    assert analysis.phase == "C" and analysis.determinate and analysis.holding.feasible
    assert analysis.omega_dot.positive and analysis.omega_dot.negative
    # Static balance: the part carries its weight on the normal and tangential forces.
    assert analysis.holding.f_n.sum() > 0.9 * 24.0 * 9.81
    run = rbsf.Simulator(model).rollout(q, analysis.holding.tau[np.newaxis, :], [1000])
    assert len(run) == 1000 and run.fell_at == -1.0
    assert np.abs(run.q[-1, :3] - q[:3]).max() < 1e-9
    assert set(run.phase) == {0}  # C throughout


def test_a_pose_is_a_tuple_or_a_pose():
    p = rbsf.Pose(0.1, 0.4, rbsf.deg(90))
    assert tuple(p) == pytest.approx((0.1, 0.4, math.pi / 2))
    assert tuple(rbsf.Pose([1, 2, 3])) == (1.0, 2.0, 3.0)
    with pytest.raises(ValueError, match="finite"):
        rbsf.Pose(0.0, float("inf"), 0.0)


def test_the_version_is_the_projects():
    from conftest import SOURCE
    import re

    version = re.search(r"project\(rbsf VERSION ([0-9.]+)", (SOURCE / "CMakeLists.txt").read_text())
    assert rbsf.__version__ == version.group(1)
