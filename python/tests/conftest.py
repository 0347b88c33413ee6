"""Shared fixtures: where the sources and the build are, the default cell, and a certified
plan file written by the command-line tool (the reference the bindings are checked against)."""

import os
import pathlib
import subprocess

import pytest

SOURCE = pathlib.Path(os.environ.get("RBSF_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
BUILD = pathlib.Path(os.environ.get("RBSF_BUILD_DIR", SOURCE / "build"))
DEFAULT_CELL = SOURCE / "cells" / "default.yaml"

#: The -15 degree support plan of tests/consumer_plan: certified in about two seconds.
TURN_15 = ["--start", "0.1,0.40,0", "--goal", "0.1,0.40,-15deg", "--planner", "support",
           "--no-optimize", "--trials", "64"]


def tool(name):
    """The path of a command-line tool in the build."""
    return str(BUILD / "tools" / name)


@pytest.fixture(scope="session")
def default_cell():
    import rbsf

    return rbsf.Cell.from_file(str(DEFAULT_CELL))


@pytest.fixture(scope="session")
def model(default_cell):
    import rbsf

    return rbsf.Model(default_cell)


@pytest.fixture(scope="session")
def plan_file(tmp_path_factory):
    """The -15 degree plan as plan-reorientation writes it with --reproducible."""
    path = tmp_path_factory.mktemp("plans") / "turn15.json"
    subprocess.run([tool("plan-reorientation"), "--cell", str(DEFAULT_CELL), *TURN_15,
                    "--quiet", "--reproducible", "--out", str(path)], check=True,
                   stdout=subprocess.DEVNULL)
    return path
