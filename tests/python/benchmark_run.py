"""fretwear.run against `fretwear run` on the same scenes (docs/PERFORMANCE.md, "Python module").

    PYTHONPATH=build/python python3 tests/python/benchmark_run.py [repeats] [other_fretwear]

For each scene, `repeats` times in turn (default 5): the command line as a process with plots off (it writes its CSV
files, which the module does not), and fretwear.run in memory. Reports the medians of the wall time of the whole
call (the process; the function call with its arrays), and of timings.total, the solve inside each (Simulation::run,
files aside), and the module's over the command line's. With other_fretwear (a `fretwear` built otherwise, e.g.
with -DFRETWEAR_PYTHON=OFF, whose libraries are not position-independent), its solve too, over this build's."""
import json
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

import fretwear
from conftest import EXE, example

SCENES = ["hertz_cycle", "hertz_wear", "hertz_wear_crack", "life_slip_amplitude"]


def cli_solve_seconds(exe, path, summary):
    """The command line's wall time and its summary's timings.total (s)."""
    t0 = time.perf_counter()
    subprocess.run([exe, "run", "-q", str(path)], check=True, cwd=path.parent, stderr=subprocess.DEVNULL)
    wall = time.perf_counter() - t0
    return wall, json.loads(summary.read_text())["timings"]["total"]


def main(repeats, other):
    print(f"fretwear {fretwear.__version__}, {repeats} runs each, medians")
    print(f"{'scene':<22}{'cli wall s':>11}{'py wall s':>11}{'ratio':>8}{'cli solve s':>13}{'py solve s':>12}{'ratio':>8}"
          + (f"{'other solve s':>15}{'ratio':>8}" if other else ""))
    with tempfile.TemporaryDirectory() as tmp:
        folder = pathlib.Path(tmp)
        for name in SCENES:
            scene = example(name, **{"output.plots": False, "output.dir": str(folder / name)})
            path = folder / f"{name}.json"
            path.write_text(json.dumps(scene))
            cli_wall, cli_solve, py_wall, py_solve, other_solve = [], [], [], [], []
            for _ in range(repeats):
                wall, solve = cli_solve_seconds(EXE, path, folder / name / "summary.json")
                cli_wall.append(wall)
                cli_solve.append(solve)
                if other:
                    other_solve.append(cli_solve_seconds(other, path, folder / name / "summary.json")[1])
                t0 = time.perf_counter()
                result = fretwear.run(scene)
                py_wall.append(time.perf_counter() - t0)
                py_solve.append(result.summary["timings"]["total"])
            cw, pw = statistics.median(cli_wall), statistics.median(py_wall)
            cs, ps = statistics.median(cli_solve), statistics.median(py_solve)
            line = f"{name:<22}{cw:>11.3f}{pw:>11.3f}{pw / cw:>8.3f}{cs:>13.3f}{ps:>12.3f}{ps / cs:>8.3f}"
            if other:
                os_ = statistics.median(other_solve)
                line += f"{os_:>15.3f}{os_ / cs:>8.3f}"
            print(line)


if __name__ == "__main__":
    import warnings

    warnings.simplefilter("ignore", fretwear.FretwearWarning)
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 5, sys.argv[2] if len(sys.argv) > 2 else None)
