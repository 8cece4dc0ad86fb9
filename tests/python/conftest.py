"""What the Python module's tests share: the module, the command line beside it, and the example scenes.

ctest runs each file with PYTHONPATH naming build/python and FRETWEAR_EXE, FRETWEAR_SOURCE_DIR naming the program
and the checkout (tests/CMakeLists.txt)."""
import csv
import json
import os
import re
import pathlib
import subprocess

import pytest

import fretwear

SOURCE_DIR = pathlib.Path(os.environ.get("FRETWEAR_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
EXE = str(pathlib.Path(os.environ.get("FRETWEAR_EXE", SOURCE_DIR / "build" / "fretwear")).resolve())


def pytest_configure(config):
    # The runs' warnings (an under-resolved zone, a singular maximum) are the scenes', listed in their summaries.
    config.addinivalue_line("filterwarnings", "ignore::fretwear.FretwearWarning")


def example(name, **changes):
    """The example scene examples/<name>.json as a dict, with changes given as dotted keys ("grid.cells": 256)."""
    scene = json.loads((SOURCE_DIR / "examples" / f"{name}.json").read_text())
    scene.setdefault("name", name)
    for key, value in changes.items():
        node = scene
        *parents, last = key.split(".")
        for part in parents:
            node = node.setdefault(part, {})
        node[last] = value
    return scene


def cli(*args, cwd=None):
    """The command line's exit status, stdout and stderr."""
    done = subprocess.run([EXE, *map(str, args)], capture_output=True, text=True, errors="surrogateescape", cwd=cwd)
    return done.returncode, done.stdout, done.stderr


def cli_run(scene, folder):
    """Runs `scene` (a dict) through the command line into `folder`/cli; returns that folder."""
    scene = dict(scene, output=dict(scene.get("output", {}), dir=str(folder / "cli")))
    path = folder / "scene" / "scene.json"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(scene))
    status, _, err = cli("run", "-q", path, cwd=folder)
    assert status == 0, err
    return folder / "cli"


def without_timings(summary):
    """A summary without its wall times (timings, the normal solve's and the fatigue stage's), which no two runs
    share."""
    summary = json.loads(json.dumps(summary))
    summary.pop("timings", None)
    normal = summary.get("solver", {}).get("normal", {})
    normal.pop("seconds", None)
    if "brief" in normal:
        normal["brief"] = re.sub(r", [0-9.e+-]+ m?s$", "", normal["brief"])
    summary.get("stress", {}).pop("fatigue_seconds", None)
    return summary


@pytest.fixture
def in_empty_folder(tmp_path, monkeypatch):
    """The working folder is an empty temporary one."""
    monkeypatch.chdir(tmp_path)
    return tmp_path


def read_csv(path):
    """A CSV file of the command line's as {header: column}: floats (an empty value NaN) or, where a column holds
    words, str."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    columns = {}
    for k, name in enumerate(rows[0]):
        values = [row[k] for row in rows[1:]]
        try:
            columns[name] = [float(v) if v != "" else float("nan") for v in values]
        except ValueError:
            columns[name] = values
    return columns
