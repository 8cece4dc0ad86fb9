"""run(..., progress=f): f is told where the run stands at every increment of a marched cycle, every wear step and
every part of the later stages, the last call of a stage with all of it done; what f raises stops the run, nothing
written; a non-callable is refused."""
import pytest

import fretwear
from conftest import example

# A worn contact with maps, cracks and a life: every stage that reports its parts, in a second or two.
SCENE = example("life_slip_amplitude", **{"grid.cells": 256, "effects.stress": {"nx": 41, "ny": 20},
                                          "effects.crack": {"at": "trailing_edge", "lengths": [1e-5, 2e-5]}})


def test_progress_follows_every_stage_to_its_end():
    calls = []
    result = fretwear.run(SCENE, progress=lambda *args: calls.append(args))
    assert result.summary["status"] == "completed"
    stages = {}
    for stage, done, total, unit in calls:
        assert 0 <= done <= total
        stages.setdefault((stage, unit), []).append((done, total))
    # The slip amplitude is prescribed: the load cycle is marched, by the checks before the wear run.
    assert set(stages) == {("tangential", "increments"), ("wear", "cycles"), ("stress", "map columns"), ("stress", "rows of the SWT maps"),
                           ("crack", "records"), ("life", "parts (initiation, growth)")}
    records = result.summary["wear"]["records"]
    assert stages[("crack", "records")][-1] == (records, records)
    assert stages[("wear", "cycles")][-1] == (1e6, 1e6)
    assert len(stages[("wear", "cycles")]) >= result.summary["wear"]["steps"]  # at every step's end at least
    for key, seen in stages.items():
        dones = [d for d, _ in seen]
        assert dones == sorted(dones), key
        assert seen[-1][0] == seen[-1][1], key  # the stage's last call: all of it done
        assert len({t for _, t in seen}) == 1, key
        assert len(set(dones)) == len(dones), key  # each place once (a record that ends a step, too)


def test_a_load_historys_march_is_told_against_the_most_it_may_take_and_ends_with_what_it_took():
    """A history is marched until a cycle repeats the one before (at most 10 cycles): its total is that most, and the
    last call, where it stopped, gives what it marched as done and total."""
    calls = []
    result = fretwear.run(example("hertz_history_out_of_phase", **{"grid.cells": 256}),
                          progress=lambda *args: calls.append(args))
    told = [(done, total) for stage, done, total, unit in calls if (stage, unit) == ("tangential", "increments")]
    increments = 160
    cycles = result.summary["cycle"]["history_cycles"]
    marched = increments // 4 + cycles * increments  # its four segments are equal: each takes a quarter of them
    assert cycles < 10 and told[-1] == (marched, marched)
    assert told[:-1] == [(k, increments // 4 + 10 * increments) for k in range(1, marched + 1)]


class Enough(Exception):
    pass


def test_an_exception_from_progress_stops_the_run_and_is_raised(in_empty_folder):
    def stop_in_stress(stage, done, total, unit):
        if stage == "stress" and done >= 10:
            raise Enough(f"{done} of {total} {unit}")

    with pytest.raises(Enough, match="10.0 of"):
        fretwear.run(SCENE, output=in_empty_folder / "out", progress=stop_in_stress)
    assert list(in_empty_folder.iterdir()) == []
    assert fretwear.run(example("hertz_normal")).summary["status"] == "completed"


def test_progress_must_be_callable():
    with pytest.raises(TypeError, match="progress must be a callable"):
        fretwear.run(example("hertz_normal"), progress=3)
    with pytest.raises(TypeError):
        fretwear.run(example("hertz_normal"), None, print)  # keyword only
