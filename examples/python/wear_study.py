"""A wear study in Python: run the Hertz wear scene in memory, plot its worn profiles, and sweep the tangential load
into a pandas table. Notebook-style: each "# %%" cell runs on its own in Jupyter or VS Code.

    PYTHONPATH=build/python python3 examples/python/wear_study.py [folder]

Writes worn_profiles.png and sweep.csv into `folder` (default output/python_wear_study); examples/README.md gives
what it prints. Needs python3-matplotlib and python3-pandas (scripts/setup.sh installs them)."""
# %% The scene: PHYSICS.md's Hertz contact (R = 10 mm, P = 100 kN/m, f = 0.5) at Q/fP = 0.5, Archard k = 1e-12 1/Pa
import json
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")  # files only; in a notebook, drop this line to see the figure inline
import matplotlib.pyplot as plt
import pandas

import fretwear

here = pathlib.Path(__file__).resolve().parent
folder = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "output/python_wear_study")
folder.mkdir(parents=True, exist_ok=True)
scene = json.loads((here.parent / "hertz_wear.json").read_text())  # or fretwear.defaults("wear")
assert fretwear.validate(scene) == []

# %% The wear run: 1e7 cycles, in memory (nothing written)
result = fretwear.run(scene)
wear = result.summary["wear"]
print(f"worn area {wear['worn_area']:.4e} m^2 after {wear['cycles_reached']:.3g} cycles, "
      f"{100 * wear['fraction_of_asymptote']:.2f} % of the asymptote; max depth {wear['max_depth'] * 1e6:.4f} um")
history = result.wear_history
print(f"{len(history)} records; the stick zone stays at [{history.stick_left[0] * 1e3:.6f}, "
      f"{history.stick_right[0] * 1e3:.6f}] mm from the first to the last "
      f"([{history.stick_left[-1] * 1e3:.6f}, {history.stick_right[-1] * 1e3:.6f}] mm)")

# %% The worn profiles: profiles holds one block of grid cells per record, then the asymptote (cycles = inf)
profiles = result.profiles
cells = result.summary["grid"]["cells"]
blocks = len(profiles) // cells  # the records, and the asymptote when the run has one
fig, (depth, pressure) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
for k in range(blocks):
    rows = slice(k * cells, (k + 1) * cells)
    cycles = profiles.cycles[rows][0]
    x_mm = profiles.x[rows] * 1e3
    asymptote = cycles == float("inf")
    style = dict(color="black", linestyle="--", label="asymptote") if asymptote else dict(
        color=plt.cm.plasma(k / blocks), label=f"N = {cycles:.3g}" if k % 4 == 0 or k == len(history) - 1 else None)
    depth.plot(x_mm, profiles.wear[rows] * 1e6, **style)
    pressure.plot(x_mm, profiles.p[rows] * 1e-6, **style)
depth.set_ylabel("worn depth (um)")
depth.invert_yaxis()
pressure.set_ylabel("pressure (MPa)")
pressure.set_xlabel("x (mm)")
pressure.set_xlim(-0.2, 0.2)
depth.legend(fontsize=8)
depth.set_title(f"{scene['name']}: the worn profile and the pressure at each record")
fig.savefig(folder / "worn_profiles.png", dpi=120)
print(f"{len(history)} records and the asymptote drawn in {folder / 'worn_profiles.png'}")

# %% A sweep: the worn area and the stick zone against Q/fP, one run each, into a pandas table
rows = []
for ratio in (0.2, 0.4, 0.6, 0.8):
    scene["load"]["Q"]["ratio"] = ratio
    run = fretwear.run(scene)
    w = run.summary["wear"]
    rows.append({"Q_over_fP": str(ratio), "worn_area_m2": w["worn_area"], "max_depth_m": w["max_depth"],
                 "stick_half_width_m": w["stick_zone_final"][1], "fraction_of_asymptote": w["fraction_of_asymptote"]})
sweep = pandas.DataFrame(rows).set_index("Q_over_fP")
sweep.to_csv(folder / "sweep.csv")
with pandas.option_context("display.float_format", "{:.4e}".format, "display.width", 120):
    print(sweep)
# The last run's cycle as a data frame, one row per cell, columns named as in cycle.csv without the units
cycle = pandas.DataFrame(run.cycle.to_dict())
print(f"cycle at Q/fP = 0.8: {len(cycle)} cells, peak slip range {cycle.slip_range.max() * 1e6:.4f} um")
