"""fretwear.run against `fretwear run` on the same scenes (docs/PERFORMANCE.md, "Python module").

    PYTHONPATH=build/python python3 tests/python/benchmark_run.py [repeats]

For each scene, `repeats` times in turn (default 5): the command line as a process with plots off (it writes its CSV
files, which the module does not), and fretwear.run in memory. Reports the medians of the wall time of the whole
call (the process; the function call with its arrays), and of timings.total, the solve inside each (Simulation::run,
files aside), and the module's over the command line's."""
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


def main(repeats):
    print(f"fretwear {fretwear.__version__}, {repeats} runs each, medians")
    print(f"{'scene':<22}{'cli wall s':>11}{'py wall s':>11}{'ratio':>8}{'cli solve s':>13}{'py solve s':>12}{'ratio':>8}")
    with tempfile.TemporaryDirectory() as tmp:
        folder = pathlib.Path(tmp)
        for name in SCENES:
            scene = example(name, **{"output.plots": False, "output.dir": str(folder / name)})
            path = folder / f"{name}.json"
            path.write_text(json.dumps(scene))
            cli_wall, cli_solve, py_wall, py_solve = [], [], [], []
            for _ in range(repeats):
                t0 = time.perf_counter()
                subprocess.run([EXE, "run", "-q", str(path)], check=True, cwd=folder, stderr=subprocess.DEVNULL)
                cli_wall.append(time.perf_counter() - t0)
                cli_solve.append(json.loads((folder / name / "summary.json").read_text())["timings"]["total"])
                t0 = time.perf_counter()
                result = fretwear.run(scene)
                py_wall.append(time.perf_counter() - t0)
                py_solve.append(result.summary["timings"]["total"])
            cw, pw = statistics.median(cli_wall), statistics.median(py_wall)
            cs, ps = statistics.median(cli_solve), statistics.median(py_solve)
            print(f"{name:<22}{cw:>11.3f}{pw:>11.3f}{pw / cw:>8.3f}{cs:>13.3f}{ps:>12.3f}{ps / cs:>8.3f}")


if __name__ == "__main__":
    import warnings

    warnings.simplefilter("ignore", fretwear.FretwearWarning)
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 5)
