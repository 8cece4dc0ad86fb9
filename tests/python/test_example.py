"""examples/python/wear_study.py runs as examples/README.md says: its plot, its sweep table, its numbers."""
import csv
import os
import subprocess
import sys

from conftest import SOURCE_DIR


def test_the_wear_study_example_runs(tmp_path):
    done = subprocess.run([sys.executable, SOURCE_DIR / "examples" / "python" / "wear_study.py", tmp_path / "study"],
                          capture_output=True, text=True, env=dict(os.environ, MPLCONFIGDIR=str(tmp_path / "mpl")))
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert lines[0].startswith("worn area 9.092") and "99.96 % of the asymptote" in lines[0]
    assert lines[1].startswith("17 records; the stick zone stays at [-0.0761")
    assert (tmp_path / "study" / "worn_profiles.png").stat().st_size > 10_000
    with open(tmp_path / "study" / "sweep.csv", newline="") as f:
        sweep = list(csv.DictReader(f))
    assert [row["Q_over_fP"] for row in sweep] == ["0.2", "0.4", "0.6", "0.8"]
    areas = [float(row["worn_area_m2"]) for row in sweep]
    assert areas == sorted(areas)  # more slip, more wear
    assert lines[-1].startswith("cycle at Q/fP = 0.8: 1024 cells")
