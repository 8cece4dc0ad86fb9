"""fretwear.run gives what `fretwear run` gives: the same summary (timings aside) and, as numpy arrays, the same fields
as its CSV files."""
import json

import numpy
import pytest

import fretwear
from conftest import cli_run, example, read_csv, without_timings

# The CSV files write 10 significant digits ({:.10g}): a value read back is within half a unit of the 10th digit.
CSV_RELATIVE = 0.5e-9

# A scene of each kind, and one for each optional column: normal; cycle; dissimilar bodies (the coupled pressure
# and the loop); wear; wear under load blocks (the block column); a crack; wear with the crack, the stresses and the
# fatigue measures; the life. Plots off: the command line's summary then lists none, as the module's does.
SCENES = {
    "normal": example("hertz_normal"),
    "cycle": example("hertz_cycle"),
    "dissimilar": example("dissimilar_cycle"),
    "wear": example("hertz_wear"),
    "wear_blocks": example("hertz_wear_blocks"),
    "crack": example("inclined_crack"),
    "wear_crack": example("hertz_wear_crack", **{"grid.cells": 512}),
    "life": example("life_slip_amplitude", **{"grid.cells": 512}),
}
for scene in SCENES.values():
    scene.setdefault("output", {})["plots"] = False


@pytest.fixture(scope="module", params=sorted(SCENES))
def both(request, tmp_path_factory):
    """The scene run by the module in memory and by the command line into a folder."""
    folder = tmp_path_factory.mktemp(request.param)
    scene = SCENES[request.param]
    return fretwear.run(scene), cli_run(scene, folder)


def test_the_summary_is_the_command_lines_bit_for_bit(both):
    result, folder = both
    written = json.loads((folder / "summary.json").read_text())
    assert without_timings(result.summary) == without_timings(written)
    assert set(result.summary["timings"]) == set(written["timings"])


def test_every_csv_file_is_a_table_with_its_columns_and_values(both):
    result, folder = both
    files = sorted(p.name for p in folder.glob("*.csv"))
    assert sorted(t.file for t in result.tables.values()) == files
    for table in result.tables.values():
        header = (folder / table.file).read_text().splitlines()[0].split(",")
        assert len(header) == len(table.columns)
        for name, column in zip(table.columns, header):
            assert column == name or column.startswith(name + "_"), (table.file, column, name)
        data = read_csv(folder / table.file)
        assert len(table) == table.rows == len(data[header[0]])
        for name, column in zip(table.columns, header):
            ours, theirs = table[name], data[column]
            if ours.dtype.kind == "U":
                assert list(ours) == theirs, (table.file, name)
            else:
                numpy.testing.assert_allclose(ours, theirs, rtol=CSV_RELATIVE, atol=0, equal_nan=True,
                                              err_msg=f"{table.file}: {name}")


def test_every_array_is_read_only_and_a_copy_is_the_callers_own(both):
    # table.x, table["x"] and to_dict() hand out one array: read-only, so that no caller changes another's data, and
    # for good (its WRITEABLE flag cannot be set again); .copy() is writeable and leaves the table's as it was.
    result, _ = both
    for table in result.tables.values():
        for name in table.columns:
            column = table[name]
            assert column is getattr(table, name) is table.to_dict()[name], (table.file, name)
            assert not column.flags.writeable, (table.file, name)
            with pytest.raises(ValueError, match="read-only"):
                column[...] = column[::-1]
            with pytest.raises(ValueError):
                column.flags.writeable = True
            before = column.copy()
            mine = column.copy()
            assert mine.flags.writeable
            mine[...] = mine[::-1]
            assert table[name].tobytes() == before.tobytes(), (table.file, name)


def test_the_resolved_scene_is_the_command_lines(both):
    result, folder = both
    written = json.loads((folder / "scene.resolved.json").read_text())
    written["output"].pop("dir")
    ours = dict(result.scene)
    ours["output"] = {k: v for k, v in ours["output"].items() if k != "dir"}
    assert ours == written
