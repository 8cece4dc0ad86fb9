"""The module's interface: errors that name their JSON paths, nothing written without `output`, the folder written
with it as the command line writes it, defaults and the version as the command line gives them, documented units."""
import concurrent.futures
import copy
import json
import multiprocessing
import os
import pathlib
import pickle
import sys

import numpy
import pytest

import fretwear
from conftest import SOURCE_DIR, cli, cli_run, example, without_timings


def files_under(folder):
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*"))


def test_bad_scenes_raise_scene_error_naming_every_path(in_empty_folder):
    scene = example("hertz_wear")
    scene["profile"]["R"] = -1.0
    scene["load"]["Q"]["ratio"] = "half"
    scene["grid"]["celss"] = 512
    with pytest.raises(fretwear.SceneError) as caught:
        fretwear.run(scene)
    problems = caught.value.problems
    for path in ("profile.R", "load.Q.ratio", "grid.celss"):
        assert any(p.startswith(path + ":") for p in problems), (path, problems)
    assert isinstance(caught.value, ValueError)
    assert fretwear.validate(scene) == problems
    assert files_under(in_empty_folder) == []


def test_validate_finds_every_problem_the_command_line_finds(in_empty_folder):
    bad_scenes = sorted((SOURCE_DIR / "tests" / "bad_scenes").glob("*.json"))
    assert bad_scenes
    for bad in bad_scenes:
        status, _, err = cli("validate", bad)
        assert status == 2, bad.name
        theirs = [line[2:] for line in err.splitlines() if line.startswith("  ")]
        assert fretwear.validate(bad) == theirs, bad.name
    assert files_under(in_empty_folder) == []


def test_values_that_are_not_json_are_problems_with_their_paths():
    scene = example("hertz_normal")
    scene["load"]["P"] = object()
    scene["grid"][3] = 1
    problems = fretwear.validate(scene)
    assert any(p.startswith("load.P: a object is not a JSON value") for p in problems), problems
    assert any(p.startswith("grid: the key 3 is a int") for p in problems), problems
    scene = example("hertz_normal", **{"load.P": numpy.float64(1e5), "grid.cells": numpy.int64(256)})
    assert fretwear.validate(scene) == []
    assert fretwear.validate([1, 2]) == ["(top): the scene is a list; give a dict (or the path of a scene file)"]


def test_every_numpy_scalar_is_its_number_and_nothing_hides_the_other_problems():
    # numpy.longdouble's item() is a longdouble again: taken as a float, not followed round forever.
    scene = example("hertz_normal", **{"load.P": numpy.longdouble(1e5), "grid.cells": numpy.uint16(256)})
    assert fretwear.validate(scene) == []
    # A value no JSON holds is reported with the scene's other problems, once, at its own path.
    problems = fretwear.validate({"load": {"P": 1 + 0j}, "name": "\udcff"})
    assert problems[0] == "load.P: a complex is not a JSON value; give a dict, list, str, number, bool or None"
    assert problems[1].startswith("name: the string '\\udcff' is not UTF-8 text")
    assert any(p.startswith("materials: missing") for p in problems), problems
    assert not any(p.startswith("load.P: null") for p in problems), problems
    # Not a number and nothing at all are named as what they are.
    assert "load.P: nan is not allowed; give a normal load" in fretwear.validate(example("hertz_normal", **{"load.P": float("nan")}))[0]
    assert fretwear.validate(example("hertz_normal", **{"load.P": None}))[0].startswith("load.P: null is not a value")


def test_an_integer_too_long_to_print_and_a_duration_are_problems_with_their_paths():
    # Python refuses to print an int of over 4300 digits: it is named by its size, with the scene's other problems.
    scene = example("hertz_normal", **{"load.P": 10**5000, "grid.cells": 3})
    problems = fretwear.validate(scene)
    assert problems[0] == "load.P: an integer of 16610 bits does not fit in 64 bits; give a float"
    assert any(p.startswith("grid.cells: ") for p in problems), problems
    assert fretwear.validate(example("hertz_normal", **{"load.P": 2**64}))[0] == (
        "load.P: the integer 18446744073709551616 does not fit in 64 bits; give a float")
    # numpy makes timedelta64 one of its integers; a duration is not a load.
    assert fretwear.validate(example("hertz_normal", **{"load.P": numpy.timedelta64(5)})) == [
        "load.P: a timedelta64 is not a JSON value; give a dict, list, str, number, bool or None"]


def test_output_that_is_not_a_path_is_named(in_empty_folder):
    with pytest.raises(TypeError, match=r"^output must be a folder's path \(str, bytes or os.PathLike\) or None, "
                                        r"not int$"):
        fretwear.run(example("hertz_normal", **{"grid.cells": 128}), output=5)
    assert list(in_empty_folder.iterdir()) == []


def test_a_warning_names_the_line_that_called_fretwear(monkeypatch):
    # The long run of the test above, warned by validate as by run; fretwear's functions have no frame of their own.
    monkeypatch.setenv("FRETWEAR_CYCLE_SOLVE_SECONDS", "1e-5")
    scene = example("hertz_wear", **{"grid.cells": 256, "effects.wear.k": 2.5e-14, "effects.wear.cycles": 1e12,
                                     "effects.wear.stepper": "explicit"})
    with pytest.warns(fretwear.FretwearWarning, match="^long_run: ") as caught:
        fretwear.validate(scene); line = sys._getframe().f_lineno  # noqa: E702 (the call's own line)
    assert [(w.filename, w.lineno) for w in caught] == [(__file__, line)]


def test_paths_may_be_bytes_and_an_output_path_must_be_utf8(in_empty_folder):
    scene = example("hertz_normal", **{"grid.cells": 128})
    (in_empty_folder / "s.json").write_text(json.dumps(scene))
    assert fretwear.run(b"s.json").summary["status"] == "completed"
    result = fretwear.run(scene, output=b"out")
    assert result.output == pathlib.Path("out") and (in_empty_folder / "out" / "summary.json").exists()
    with pytest.raises(fretwear.SceneError) as caught:
        fretwear.run(scene, output=os.fsdecode(b"out\xff"))
    assert caught.value.problems[0].startswith("output.dir: ") and "is not UTF-8 text" in caught.value.problems[0]
    assert files_under(in_empty_folder) == sorted(["s.json", "out", *(f"out/{f}" for f in os.listdir("out"))])


def test_validate_gives_the_warnings_before_solving_as_the_command_line_prints_them(monkeypatch):
    # The explicit stepper over 1e12 cycles: 2.47e9 cycle solves, each fixed at 10 µs by the test hook
    # FRETWEAR_CYCLE_SOLVE_SECONDS, as tests/regression/regression_silent_nonsense.cpp times it: past the hour that
    # warns, short of the day that refuses.
    monkeypatch.setenv("FRETWEAR_CYCLE_SOLVE_SECONDS", "1e-5")
    scene = example("hertz_wear", **{"grid.cells": 256, "effects.wear.k": 2.5e-14, "effects.wear.cycles": 1e12,
                                     "effects.wear.stepper": "explicit"})
    with pytest.warns(fretwear.FretwearWarning, match=r"^long_run: 1e\+12 cycles with stepper \"explicit\""):
        assert fretwear.validate(scene) == []


def test_the_physics_checks_before_solving_are_the_command_lines():
    scene = example("hertz_normal", **{"load.P": 1e11})  # a contact strain far beyond linear elasticity
    problems = fretwear.validate(scene)
    assert len(problems) == 1 and problems[0].startswith("load.P: the mean contact pressure")
    with pytest.raises(fretwear.SceneError):
        fretwear.run(scene)


def test_a_wear_coefficient_that_reshapes_the_contact_in_a_cycle_is_refused_and_a_tenth_of_it_warns():
    # The Hertz wear case, whose first cycle wears 16.8 times k / 1e-6 of the contact's elastic depth P / (2 E*).
    scene = example("hertz_wear", **{"grid.cells": 256, "effects.wear.cycles": 1e3, "effects.wear.k": 1e-6})
    problems = fretwear.validate(scene)
    assert len(problems) == 1 and problems[0].startswith("effects.wear.k: one cycle wears the contact")
    with pytest.raises(fretwear.SceneError):
        fretwear.run(scene)
    scene["effects"]["wear"]["k"] = 1e-8
    with pytest.warns(fretwear.FretwearWarning, match=r"^wear_per_cycle: one cycle wears the contact"):
        assert fretwear.validate(scene) == []


def test_a_solve_stopped_short_raises_convergence_error_with_its_residual(in_empty_folder, monkeypatch):
    # The test hook FRETWEAR_NORMAL_MAX_ITERATIONS caps the normal solve at two iterations, as the command line's
    # test of exit status 3 does; no real scene fails to converge on demand.
    monkeypatch.setenv("FRETWEAR_NORMAL_MAX_ITERATIONS", "2")
    scene = example("hertz_normal", **{"grid.cells": 256})
    with pytest.raises(fretwear.ConvergenceError, match=r"normal contact: the solve stopped \(max_iterations\) "
                       r"with residual"):
        fretwear.run(scene)
    assert files_under(in_empty_folder) == []
    with pytest.raises(fretwear.ConvergenceError):
        fretwear.run(scene, output=str(in_empty_folder / "out"))
    summary = json.loads((in_empty_folder / "out" / "summary.json").read_text())
    assert summary["status"] == "not_converged" and "residual" in summary["message"]
    assert summary["failed_stage"] == "normal" and summary["effects_run"] == []  # as the command line writes it
    monkeypatch.delenv("FRETWEAR_NORMAL_MAX_ITERATIONS")
    assert fretwear.run(scene).summary["contact"]["cells_in_contact"] > 0


def test_nothing_is_written_without_output(in_empty_folder):
    scene = example("hertz_wear", **{"output.dir": str(in_empty_folder / "would_be_here")})
    result = fretwear.run(scene)
    assert result.output is None
    assert result.summary["plots"] == []
    assert files_under(in_empty_folder) == []


def test_with_output_the_folder_is_what_the_command_line_writes(tmp_path):
    scene = example("hertz_wear")
    result = fretwear.run(scene, output=tmp_path / "py")
    assert result.output == tmp_path / "py"
    cli_folder = cli_run(scene, tmp_path)
    assert files_under(tmp_path / "py") == files_under(cli_folder)
    for csv in cli_folder.glob("*.csv"):
        assert (tmp_path / "py" / csv.name).read_bytes() == csv.read_bytes(), csv.name
    written = json.loads((tmp_path / "py" / "summary.json").read_text())
    assert without_timings(written) == without_timings(result.summary)
    assert without_timings(written) == without_timings(json.loads((cli_folder / "summary.json").read_text()))
    assert result.summary["plots"] and os.path.exists(tmp_path / "py" / ".fretwear")


def test_output_follows_the_command_lines_folder_rules(in_empty_folder):
    (in_empty_folder / "mine").mkdir()
    (in_empty_folder / "mine" / "thesis.tex").write_text("keep me")
    scene = example("hertz_normal")
    with pytest.raises(fretwear.SceneError) as caught:
        fretwear.run(scene, output="mine")
    assert caught.value.problems[0].startswith("output.dir")
    assert fretwear.validate(scene, output="mine") == caught.value.problems
    assert files_under(in_empty_folder) == ["mine", "mine/thesis.tex"]


def test_an_invalid_scene_and_its_output_folder_are_listed_together_as_on_the_command_line(in_empty_folder):
    (in_empty_folder / "mine").mkdir()
    (in_empty_folder / "mine" / "thesis.tex").write_text("keep me")
    scene = example("hertz_normal")
    scene["profile"]["R"] = -1.0
    with pytest.raises(fretwear.SceneError) as caught:
        fretwear.run(scene, output="mine")
    problems = caught.value.problems
    assert len(problems) == 2 and problems[0].startswith("profile.R:"), problems
    assert problems[1].startswith('output.dir: the folder "') and '/mine" holds files' in problems[1], problems
    assert fretwear.validate(scene, output="mine") == problems
    # The command line, given the same folder in the scene, lists the same two (its dict read from a file).
    scene["output"] = {"dir": "mine"}
    (in_empty_folder / "s.json").write_text(json.dumps(scene))
    status, _, err = cli("validate", "s.json")
    assert status == 2 and [line[2:] for line in err.splitlines() if line.startswith("  ")] == problems
    # A scene file that cannot be read, and a scene that is not a dict, likewise.
    assert fretwear.validate("missing.json", output="mine") == ["missing.json: no such file", problems[1]]
    assert fretwear.validate(5, output="mine")[1:] == [problems[1]]
    assert files_under(in_empty_folder) == ["mine", "mine/thesis.tex", "s.json"]


def test_arrays_have_the_grids_length_and_si_units():
    result = fretwear.run(example("hertz_cycle", **{"grid.cells": 512}))
    cells = result.summary["grid"]["cells"]
    assert cells == 512
    for table in (result.contact, result.cycle):
        assert len(table) == cells
        for name in table.columns:
            assert table[name].shape == (cells,) and table[name].dtype == numpy.float64
    # SI: the cell centres span the window in m, the peak is summary.json's p_max in Pa, the load balances P (N/m).
    h = result.summary["grid"]["h"]
    window = result.summary["grid"]["window"]
    numpy.testing.assert_allclose(result.contact.x[[0, -1]], [window[0] + h / 2, window[1] - h / 2], rtol=1e-12)
    assert result.contact.p.max() == result.summary["contact"]["p_max"]
    P = result.scene["load"]["P"]
    assert abs(result.contact.p.sum() * h - P) < 1e-6 * P
    assert result.contact.units["x"] == "m" and result.contact.units["p"] == "Pa"
    assert result.cycle.units["energy_density"] == "J/m^2"
    assert result.wear_history is None and result.stress is None


def test_defaults_and_version_are_the_command_lines():
    _, out, _ = cli("defaults")
    assert fretwear.defaults() == json.loads(out)
    _, out, _ = cli("defaults", "--effect", "crack")
    assert fretwear.defaults("crack") == json.loads(out)
    with pytest.raises(ValueError, match=r'^effect: "nothing" is not an effect; use '):
        fretwear.defaults("nothing")
    _, out, _ = cli("--version")
    assert out.split() == ["fretwear", fretwear.__version__]


def test_a_scene_file_is_read_as_the_command_line_reads_it(tmp_path):
    result = fretwear.run(SOURCE_DIR / "examples" / "hertz_normal.json")
    assert result.summary["scene"] == "hertz_normal"


def test_help_names_the_units():
    for text in (fretwear.run.__doc__, fretwear.Result.__doc__, fretwear.Table.__doc__):
        assert " m" in text and "Pa" in text
    assert "SceneError" in fretwear.run.__doc__ and "output" in fretwear.run.__doc__
    assert "problems" in fretwear.SceneError.__doc__
    assert "json.path" in fretwear.validate.__doc__
    assert "m^2" in fretwear.Result.wear_history.__doc__
    assert "Pa" in repr(fretwear.run(example("hertz_normal")).contact)


def test_defaults_doc_gives_the_default_scenes_own_numbers():
    scene = fretwear.defaults()
    doc = fretwear.defaults.__doc__
    assert f"radius R = {scene['profile']['R']:g} m" in doc
    assert f"P = {scene['load']['P']:g} N/m" in doc
    assert f"E = {scene['materials']['both']['E']:g} Pa, nu = {scene['materials']['both']['nu']:g}" in doc
    for effect in scene["effects"]:
        assert f'"{effect}"' in doc


def test_a_nul_byte_in_a_path_is_refused_before_anything_is_computed(in_empty_folder):
    # The file system would take the part before the NUL for the path: "a" here, another folder than the one named.
    scene = example("hertz_normal", **{"grid.cells": 128})
    problem = ('output.dir: "a\\u0000b" holds a NUL byte, where the file system would end the path; give the path '
               "without it")
    for output in ("a\x00b", b"a\x00b", pathlib.Path("a\x00b")):
        assert fretwear.validate(scene, output=output) == [problem]
        with pytest.raises(fretwear.SceneError) as caught:
            fretwear.run(scene, output=output)
        assert caught.value.problems == [problem]
        assert str(caught.value) == "the scene is invalid:\n  " + problem
    # A scene file's path likewise: the file "s" is not read for "s\0.json".
    (in_empty_folder / "s").write_text(json.dumps(scene))
    with pytest.raises(fretwear.SceneError) as caught:
        fretwear.run("s\x00.json")
    assert caught.value.problems == ['"s\\u0000.json": holds a NUL byte, where the file system would end the path; '
                                     "give the path without it"]
    assert fretwear.validate(b"s\x00.json") == caught.value.problems
    assert files_under(in_empty_folder) == ["s"]


def test_the_path_dash_is_not_standard_input_here_and_a_file_named_dash_is_read(in_empty_folder):
    # "-" is the command line's word for standard input (docs/SCENES.md); the module never reads the caller's stdin.
    with pytest.raises(fretwear.SceneError) as caught:
        fretwear.run("-")
    (problem,) = caught.value.problems
    assert problem.startswith('"-": is standard input on the command line; here give the scene as a dict')
    assert fretwear.validate("-") == [problem]
    (in_empty_folder / "-").write_text(json.dumps(example("hertz_normal", **{"grid.cells": 128})))
    assert fretwear.validate("./-") == []
    assert files_under(in_empty_folder) == ["-"]


def test_a_folder_that_cannot_be_written_after_all_is_one_problem_said_once(in_empty_folder):
    # A file of the caller's where the results are staged (docs/SCENES.md, "Output folders") is found only when they
    # are written: its problem is raised as it is, once.
    staging = in_empty_folder / f"out.partial-{os.getpid()}"
    staging.write_text("mine")
    with pytest.raises(fretwear.SceneError) as caught:
        fretwear.run(example("hertz_normal", **{"grid.cells": 128}), output="out")
    (problem,) = caught.value.problems
    assert problem.startswith(f'output.dir: "{staging.name}" exists and is not a staging folder')
    assert str(caught.value) == "the scene is invalid:\n  " + problem
    assert files_under(in_empty_folder) == [staging.name] and staging.read_text() == "mine"


def test_a_table_iterates_over_its_column_names_as_a_dict_does():
    table = fretwear.run(example("hertz_normal", **{"grid.cells": 128})).contact
    assert list(table) == table.columns == table.keys() == ["x", "gap0", "p", "gap", "p_closed_form"]
    assert all(name in table for name in table)
    assert dict(table).keys() == table.to_dict().keys() and dict(table)["p"] is table.p
    assert len(table) == 128  # the rows
    # A key that names no column, of whatever type, as a dict's.
    assert 5 not in table and None not in table
    with pytest.raises(KeyError, match="contact.csv has no column 5; its columns are named by str"):
        table[5]


def same_result(a, b):
    assert a.summary == b.summary and a.scene == b.scene and a.output == b.output
    assert sorted(a.tables) == sorted(b.tables)
    for name, table in a.tables.items():
        other = b.tables[name]
        assert repr(table) == repr(other) and table.units == other.units and table.file == other.file
        for column in table:
            numpy.testing.assert_array_equal(table[column], other[column])
            assert table[column].dtype == other[column].dtype and not other[column].flags.writeable


def run_elsewhere(scene):
    """fretwear.run for a pool of processes, which takes a function by its module and name: pybind11's functions
    (fretwear.run itself) do not pickle."""
    return fretwear.run(scene)


def test_a_result_pickles_and_a_pool_of_processes_can_return_one(tmp_path):
    scene = example("dissimilar_cycle", **{"grid.cells": 256})  # a label column (loop.phase) among the tables
    result = fretwear.run(scene, output=tmp_path / "out")
    for protocol in range(pickle.HIGHEST_PROTOCOL + 1):  # 0 and 1 too, which rebuild an object otherwise
        same_result(result, pickle.loads(pickle.dumps(result, protocol)))
        table = pickle.loads(pickle.dumps(result.loop, protocol))
        assert repr(table) == repr(result.loop) and not table.P.flags.writeable
    same_result(result, copy.deepcopy(result))
    with pytest.raises(ValueError, match="read-only"):
        pickle.loads(pickle.dumps(result.loop)).P[0] = 0.0
    with concurrent.futures.ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn")) as pool:
        theirs = pool.submit(run_elsewhere, scene).result()
    assert without_timings(theirs.summary) == without_timings(dict(result.summary, plots=[]))
    numpy.testing.assert_array_equal(theirs.cycle.q_top, result.cycle.q_top)


def test_an_object_made_without_run_is_an_empty_one_and_cannot_be_a_half_made_one():
    """Cls.__new__(Cls) is what unpickling calls before __setstate__, and anyone may call it: it gives an empty table
    or result, never an object whose attributes read memory nothing wrote (a crash, or garbage such as len 3)."""
    table = fretwear.Table.__new__(fretwear.Table)
    assert len(table) == 0 and table.columns == [] and table.units == {} and "x" not in table and table.file == ""
    assert repr(table) == "an empty fretwear.Table: no file, no columns"
    with pytest.raises(AttributeError, match='has no column "x"'):
        table.x
    result = fretwear.Result.__new__(fretwear.Result)
    assert result.summary == {} and result.scene == {} and result.output is None and result.tables == {}
    assert result.contact is None and repr(result) == '<fretwear.Result of scene "": >'
    # Every other way to an instance is refused by name, and neither class can be subclassed around that.
    for cls in (fretwear.Table, fretwear.Result):
        name = f"fretwear.{cls.__name__}"
        for make, message in [(lambda: cls(), "No constructor defined"),
                              (lambda: cls.__new__(cls, 1), "takes no arguments: fretwear.run makes one"),
                              (lambda: cls.__new__(int), f"not {name}"),
                              (lambda: object.__new__(cls), "is not safe"),
                              (lambda: cls.__base__.__new__(cls), "is not safe"),
                              (lambda: type("Mine", (cls,), {}), "not an acceptable base type")]:
            with pytest.raises(TypeError, match=message):
                make()
    # __setstate__ fills what __new__ made, and refuses a state of another shape without touching it.
    made = fretwear.run(example("hertz_normal", **{"grid.cells": 128}))
    result.__setstate__(made.__getstate__())
    same_result(made, result)
    with pytest.raises(RuntimeError, match="holds 4 items"):
        result.__setstate__((1, 2, 3, {}))
    with pytest.raises(RuntimeError, match="a table that is not one"):
        result.__setstate__(({}, {}, None, {"contact": 1}))
    same_result(made, result)
    table.__setstate__(made.contact.__getstate__())
    assert repr(table) == repr(made.contact) and table.p is not made.contact.p
    numpy.testing.assert_array_equal(table.p, made.contact.p)


def test_a_column_name_with_a_nul_is_named_whole():
    table = fretwear.run(example("hertz_normal", **{"grid.cells": 128})).contact
    with pytest.raises(KeyError) as caught:  # a KeyError's str() is its message's repr
        table["p\0q"]
    assert caught.value.args == ('contact.csv has no column "p\\x00q"; its columns: x, gap0, p, gap, p_closed_form',)
    with pytest.raises(AttributeError, match=r'has no column "p\\x1fq"'):
        getattr(table, "p\x1fq")
