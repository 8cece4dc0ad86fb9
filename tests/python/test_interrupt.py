"""Ctrl-C during a long wear run raises KeyboardInterrupt at the next step boundary, writes nothing, and leaves the
module ready for the next run."""
import os
import signal
import threading
import time

import pytest

import fretwear
from conftest import example

# hertz_wear with the explicit stepper: some two minutes of steps of a few ms each (`fretwear validate` estimates it).
LONG = example("hertz_wear", **{"effects.wear.stepper": "explicit"})
# Ctrl-C lands this long after the run starts, and the run must have stopped this long after it: a step boundary is
# some milliseconds away, the rest is the margin of a loaded machine.
DELAY_S = 1.0
STOP_WITHIN_S = 5.0


def test_ctrl_c_stops_a_long_wear_run_cleanly(in_empty_folder):
    timer = threading.Timer(DELAY_S, os.kill, (os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            fretwear.run(LONG, output=in_empty_folder / "out")
    finally:
        timer.cancel()
    assert time.monotonic() - start < DELAY_S + STOP_WITHIN_S
    assert list(in_empty_folder.iterdir()) == []
    assert fretwear.run(example("hertz_normal")).summary["status"] == "completed"
