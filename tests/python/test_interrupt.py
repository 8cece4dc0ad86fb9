"""Ctrl-C during a long wear run raises KeyboardInterrupt at the next step boundary, and during a long stress stage
before its next column of the map; either writes nothing and leaves the module ready for the next run; meanwhile the
solve holds no GIL, so Python's other threads run."""
import json
import os
import signal
import subprocess
import sys
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
# Ticks of the other thread the middle of a solve must see: a third of what an idle machine gives.
TICKS_WITHOUT_GIL = 8


def stops_cleanly(scene, folder):
    """SIGINT DELAY_S into the run raises KeyboardInterrupt within STOP_WITHIN_S; nothing written; the next run runs."""
    timer = threading.Timer(DELAY_S, os.kill, (os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            fretwear.run(scene, output=folder / "out")
    finally:
        timer.cancel()
    assert time.monotonic() - start < DELAY_S + STOP_WITHIN_S
    assert list(folder.iterdir()) == []
    assert fretwear.run(example("hertz_normal")).summary["status"] == "completed"


def test_ctrl_c_stops_a_long_wear_run_cleanly(in_empty_folder):
    stops_cleanly(LONG, in_empty_folder)


# The coupled cycle of dissimilar bodies at 20 000 increments a cycle (45 000 in all, some ten seconds): marched by
# the cycle stage, or, for a wear scene, by the checks before the run. Either stops at its next increment.
MARCHED = example("dissimilar_cycle", **{"effects.tangential.increments": 20000})
MARCHED_FOR_WEAR = example("dissimilar_cycle", **{"effects.tangential.increments": 20000,
                                                  "effects.wear": {"law": "archard", "k": 1e-12, "cycles": 1e5}})


@pytest.mark.parametrize("scene", [MARCHED, MARCHED_FOR_WEAR], ids=["cycle", "cycle checked for wear"])
def test_ctrl_c_stops_a_long_marched_cycle_cleanly(scene, in_empty_folder):
    stops_cleanly(scene, in_empty_folder)


# hertz_cycle with a stress map of 401 x 401 points on 2048 cells: some ten seconds in the stress stage alone.
LONG_STRESS = example("hertz_cycle", **{"effects.stress": {"nx": 401, "ny": 400}})


def test_ctrl_c_stops_a_long_stress_stage_cleanly(in_empty_folder):
    stops_cleanly(LONG_STRESS, in_empty_folder)


def test_other_threads_run_while_it_solves():
    ticks = []
    running = threading.Event()

    def tick():
        while not running.is_set():
            time.sleep(0.001)
        while running.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.005)

    thread = threading.Thread(target=tick)
    thread.start()
    running.set()
    start = time.monotonic()
    result = fretwear.run(example("hertz_wear"))
    end = time.monotonic()
    running.clear()
    thread.join()
    # The solve (timings.total, some 0.25 s) ends just before the run returns, after the checks before solving, and
    # the middle half of it lies well inside it: some 25 ticks of 5 ms when the solve lets the thread run,
    # a few at most when it holds the GIL (measured: 3).
    solve = result.summary["timings"]["total"]
    assert solve > 0.1 and end - start > solve
    during = [t for t in ticks if end - 0.8 * solve < t < end - 0.3 * solve]
    assert len(during) >= TICKS_WITHOUT_GIL, (solve, len(during))


# A run left solving in another thread when the interpreter exits: one whose join() a Ctrl-C interrupted (Python
# then no longer waits for the thread), or a daemon thread. Each is stopped at its next step and awaited; its thread
# sees SystemExit. Before, the interpreter took the thread off mid-run and the process aborted (exit 134).
LEFT_RUNNING = """
import json, os, signal, sys, threading, time
import fretwear

scene = json.loads(sys.stdin.read())
def work():
    try:
        fretwear.run(scene)
    except BaseException as e:
        print(type(e).__name__, e, flush=True)
worker = threading.Thread(target=work, daemon=sys.argv[1] == "daemon")
worker.start()
time.sleep(1)
if sys.argv[1] == "join":
    threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT)).start()
    try:
        worker.join()
    except KeyboardInterrupt:
        print("interrupted", flush=True)
"""


@pytest.mark.parametrize("how", ["join", "daemon"])
def test_a_run_left_solving_in_a_thread_stops_as_the_interpreter_exits(how, in_empty_folder):
    start = time.monotonic()
    done = subprocess.run([sys.executable, "-W", "ignore", "-c", LEFT_RUNNING, how], input=json.dumps(LONG),
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    said = ("interrupted\n" if how == "join" else "") + (
        "SystemExit fretwear.run stopped: the Python interpreter is exiting\n")
    assert done.stdout == said, done.stdout + done.stderr
    assert time.monotonic() - start < 1.5 + STOP_WITHIN_S + 5  # the interpreter's start, and numpy's import
    assert list(in_empty_folder.iterdir()) == []
