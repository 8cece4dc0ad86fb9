"""Python threads may call fretwear.run at once, from the first run of a process on: none waits for ever on another,
and each result is the one the same run gives alone."""
import json
import os
import subprocess
import sys

import numpy
import pytest

import fretwear
from conftest import without_timings

RATIOS = [0.2, 0.4, 0.6, 0.8]
# The four runs take well under a second; the rest is the margin of a loaded machine. Runs that wait for ever fail
# here rather than stall the tests.
TIMEOUT_S = 30


def scenes(effect):
    """Four runs of defaults(effect) on 512 cells: Q/fP from 0.2 to 0.8 with a load cycle, else P from 0.2 to 0.8 of
    the default's."""
    out = []
    for r in RATIOS:
        s = fretwear.defaults(effect)
        s["grid"]["cells"] = 512
        if "tangential" in s.get("effects", {}):
            s["load"]["Q"] = {"ratio": r}
        else:
            s["load"]["P"] *= r
        out.append(s)
    return out


# Two threads' first runs, in a fresh process that imports fretwear and nothing before it (numpy neither): whatever
# the module would set up on its first use, both threads reach at once. Reads the scenes as JSON on stdin; prints
# each run's summary and tables as JSON.
THREADS = """
import json, sys
from concurrent.futures import ThreadPoolExecutor
import fretwear

def study(s):
    result = fretwear.run(s)
    tables = {name: {c: table[c].tolist() for c in table.columns} for name, table in result.tables.items()}
    return {"summary": result.summary, "tables": tables}

with ThreadPoolExecutor(2) as ex:
    print(json.dumps(list(ex.map(study, json.load(sys.stdin)))))
"""


@pytest.mark.parametrize("effect", ["normal", "tangential"])
def test_two_threads_run_at_once_in_a_fresh_process(effect):
    try:
        done = subprocess.run([sys.executable, "-c", THREADS], input=json.dumps(scenes(effect)), capture_output=True,
                              text=True, timeout=TIMEOUT_S, env=dict(os.environ, PYTHONWARNINGS="ignore"))
    except subprocess.TimeoutExpired:
        pytest.fail(f"two threads' runs did not end within {TIMEOUT_S} s: one waits for the other for ever")
    assert done.returncode == 0, done.stderr
    threaded = json.loads(done.stdout)
    alone = [fretwear.run(s) for s in scenes(effect)]  # one after another
    assert len(threaded) == len(alone)
    for t, a in zip(threaded, alone):
        assert without_timings(t["summary"]) == without_timings(a.summary)
        assert sorted(t["tables"]) == sorted(a.tables)
        for name, columns in t["tables"].items():
            assert list(columns) == a.tables[name].columns
            for column, values in columns.items():
                numpy.testing.assert_array_equal(numpy.array(values), a.tables[name][column], err_msg=name + column)
    if effect == "tangential":  # partial slip: a stick zone that shrinks as Q grows
        widths = [t["summary"]["cycle"]["stick_zone"][1] - t["summary"]["cycle"]["stick_zone"][0] for t in threaded]
        assert widths == sorted(widths, reverse=True) and widths[-1] > 0


# A process forked while another thread runs fretwear (a multiprocessing pool on Linux forks so): the child runs
# fretwear too. The FFT planner's lock, held by the other thread at the fork, would be held in the child for good;
# before the fork waited for it, a third of such children hung.
FORKS = """
import os, sys, threading, time
import fretwear

small = fretwear.defaults("normal")
small["grid"]["cells"] = 64
stop = False
def keep_running():
    while not stop:
        fretwear.run(small)
threading.Thread(target=keep_running, daemon=True).start()
time.sleep(0.2)
for _ in range(int(sys.argv[1])):
    pid = os.fork()
    if pid == 0:
        fretwear.run(small)
        os._exit(0)
    deadline = time.monotonic() + 20
    while os.waitpid(pid, os.WNOHANG) == (0, 0):
        if time.monotonic() > deadline:
            os.kill(pid, 9)
            print("a child hung", flush=True)
            os._exit(1)
        time.sleep(0.01)
stop = True
print("ok", flush=True)
"""


def test_a_child_forked_while_another_thread_runs_can_run():
    done = subprocess.run([sys.executable, "-W", "ignore", "-c", FORKS, "30"], capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0 and done.stdout == "ok\n", done.stdout + done.stderr
