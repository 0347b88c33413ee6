"""rbsf: planning, simulation and execution for the RBSF intelligent jig.

The C++ library rbsf from Python (docs/python.md): cells, the model's analyses, the
simulator, the planning pipeline, plans and their certificates, and the controller facade.
Arrays are numpy float64; state order q = (x, y, phi, theta, l_1..l_m), tau = (tau_theta,
tau_1..tau_m); SI units, angles in radians. Bad input raises ValueError (rbsf.InputError)
with the library's message naming the key, argument or value.
"""

import json as _json
import math as _math

from ._rbsf import __version__  # noqa: F401
from ._rbsf import (  # noqa: F401
    Attempt,
    BenchProblem,
    Cell,
    Certificate,
    CertificateSettings,
    ContactReport,
    ContactStep,
    Controller,
    ExecutionStatus,
    Finger,
    Holding,
    InputError,
    Model,
    OmegaDotRange,
    OptimizationSummary,
    Plan,
    PlanEvent,
    PlanRecord,
    PlanResult,
    PlanSegment,
    PlanSettings,
    Pose,
    Problem,
    Samples,
    SimState,
    Simulator,
    SimulatorSettings,
    StateAnalysis,
    Trajectory,
    TrialOutcome,
    certify,
    draw_trial,
    load_problem_suite,
    plan,
    replay_trial,
)

#: Phase codes of Trajectory.phase and Samples.phase.
PHASES = ("C", "P", "U", "unsupported")
#: Contact mode codes of Trajectory.mode.
MODES = ("stick", "slide", "separated")


def deg(angle_degrees):
    """An angle in degrees as radians."""
    return angle_degrees * _math.pi / 180.0


def cell_from_dict(cell, label="<dict>"):
    """A Cell from a dict with the keys of a cell file (docs/model.md "Files").

    Raises ValueError naming the offending key, as for a file.
    """
    if not isinstance(cell, dict):
        raise ValueError(f"{label}: expected a dict of cell keys, got {type(cell).__name__}")
    try:
        text = _json.dumps(cell, allow_nan=False)
    except ValueError as error:  # NaN or infinity somewhere in the dict
        raise ValueError(f"{label}: every number must be finite ({error})") from None
    except TypeError as error:
        raise ValueError(f"{label}: {error}") from None
    return Cell.from_yaml(text, label)


def load_cell_dict(path):
    """A cell file as a dict (to change a key and build it with cell_from_dict)."""
    import yaml  # Debian's python3-yaml

    with open(path, encoding="utf-8") as f:
        data = yaml.safe_load(f)
    if not isinstance(data, dict):
        raise ValueError(f"{path}: not a cell file (expected a mapping of keys)")
    return data


__all__ = [name for name in dir() if not name.startswith("_")]
