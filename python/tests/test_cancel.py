"""Stopping a plan: Ctrl-C, a cancel event and a failing progress callback."""

import os
import signal
import threading
import time

import pytest

import rbsf

# The quarter turn: no plan within the budget, so only a stop ends the run early.
QUARTER = rbsf.Problem((0.1, 0.40, 0.0), (-0.21, 0.43, rbsf.deg(90)))


def long_settings():
    settings = rbsf.PlanSettings()
    settings.time_limit = 120.0
    return settings


def test_ctrl_c_during_planning_returns_within_a_second(model):
    sent = []

    def interrupt():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(1.5, interrupt)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            rbsf.plan(model, QUARTER, long_settings())
    finally:
        timer.cancel()
    assert sent and time.monotonic() - sent[0] < 1.0


def test_a_cancel_event_ends_the_run_as_cancelled(model):
    stop = threading.Event()
    timer = threading.Timer(1.0, stop.set)
    timer.start()
    began = time.monotonic()
    result = rbsf.plan(model, QUARTER, long_settings(), cancel=stop)
    assert result.status == "cancelled" and not result.certified
    assert time.monotonic() - began < 3.0


def test_an_error_in_the_progress_callback_stops_the_run_and_is_raised(model):
    def fail(event):
        raise RuntimeError("callback failed on " + event.kind)

    with pytest.raises(RuntimeError, match="callback failed on stage"):
        rbsf.plan(model, QUARTER, long_settings(), progress=fail)


def test_a_bad_cancel_or_progress_argument_raises_before_the_run(model):
    with pytest.raises(ValueError, match="cancel: expected an object with is_set"):
        rbsf.plan(model, QUARTER, long_settings(), cancel=object())
    with pytest.raises(ValueError, match="progress: expected a callable"):
        rbsf.plan(model, QUARTER, long_settings(), progress=3)

    class Broken:
        def is_set(self):
            raise RuntimeError("the cell's stop button is unplugged")

    with pytest.raises(RuntimeError, match="unplugged"):
        rbsf.plan(model, QUARTER, long_settings(), cancel=Broken())
