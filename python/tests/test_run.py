"""stiction.run against `stiction run`: the same rows and summary, bit for bit, for every
bundled scene; results as NumPy views; instability, refusal and Ctrl-C as exceptions."""

import math
import os
import signal
import threading

import numpy as np
import pytest
import stiction
from conftest import load_json, without_timings


# The accuracy estimate is switched on or off by a cost forecast (a timing) unless asked for:
# both sides are told, so that they run the same companion. Its verdicts are compared on the
# short scenes (accuracy on); the long ones run without it, to keep the suite short.
LONG = {"slope_hold", "slope_slide", "box_slope", "box_slope_hold", "two_link", "two_link_dahl",
        "two_link_lugre", "two_link_penalty"}


@pytest.mark.parametrize("name", sorted(stiction.scenes()))
def test_every_bundled_scene_equals_the_command_line(name, cli, tmp_path):
    accuracy = name not in LONG
    cli("run", name, "--no-video", "--no-plots", "--quiet", "--accuracy", "on" if accuracy else "off",
        "--out", tmp_path / "cli")
    result = stiction.run(name, accuracy=accuracy)
    result.save(tmp_path / "py")
    cli_csv = (tmp_path / "cli" / "trajectory.csv").read_bytes()
    py_csv = (tmp_path / "py" / "trajectory.csv").read_bytes()
    assert py_csv == cli_csv
    cli_summary = load_json(tmp_path / "cli" / "summary.json")
    py_summary = load_json(tmp_path / "py" / "summary.json")
    assert without_timings(py_summary) == without_timings(cli_summary)
    # The in-memory result is what was written: the summary, and every column to the bit.
    assert without_timings(result.summary) == without_timings({k: v for k, v in py_summary.items() if k != "files"})
    header = cli_csv.split(b"\n", 1)[0].decode().split(",")
    assert header == result.columns
    parsed = np.loadtxt(tmp_path / "cli" / "trajectory.csv", delimiter=",", skiprows=1, ndmin=2)
    assert np.array_equal(parsed, result.rows)


def test_columns_are_views_with_units():
    result = stiction.run("sphere_roll", duration=0.2, accuracy=False)
    v = result["sphere.v.x"]
    assert v.base is not None and not v.flags.writeable  # no copy, read-only
    assert np.shares_memory(v, result.rows)
    assert result.units["sphere.v.x"] == "m/s" and result.units["t"] == "s"
    assert result.t[0] == 0.0 and math.isclose(result.t[-1], 0.2)
    assert len(result) == len(result.t) == 201
    with pytest.raises(KeyError, match="sphere.v.x"):
        result["sphere.v.w"]
    del result  # the view keeps the rows alive
    assert float(v[-1]) == float(v[-1])


def test_events_and_intervals_per_element():
    result = stiction.run("roll_to_slip", accuracy=False)
    events = result.events
    assert set(events) == set(result.summary["events"])
    for element, items in events.items():
        assert all({"kind", "time"} <= set(e) for e in items)
        assert result.intervals[element] == result.summary["events"][element]["intervals"]


def test_dataframe_indexed_by_time():
    pd = pytest.importorskip("pandas")
    result = stiction.run("slope_slide", duration=0.5, accuracy=False)
    frame = result.to_dataframe()
    assert isinstance(frame, pd.DataFrame)
    assert list(frame.columns) == result.columns[1:]
    assert np.array_equal(frame.index.to_numpy(), result.t)
    assert frame.attrs["units"]["t"] == "s"


def test_options_as_on_the_command_line(cli, tmp_path):
    cli("run", "two_link", "--integrator", "euler", "--dt", "2e-5", "--duration", "0.3", "--no-video",
        "--no-plots", "--quiet", "--out", tmp_path / "cli")
    result = stiction.run("two_link", integrator="euler", dt=2e-5, duration=0.3)
    result.save(tmp_path / "py")
    assert (tmp_path / "py" / "trajectory.csv").read_bytes() == (tmp_path / "cli" / "trajectory.csv").read_bytes()
    assert result.summary["integrator"] == "euler" and result.summary["dt"] == 2e-5


def test_tolerance_selects_rk4_adaptive():
    result = stiction.run("slope_slide", tolerance=1e-8, duration=0.5, accuracy=False)
    assert result.summary["integrator"] == "rk4_adaptive"
    with pytest.raises(stiction.SceneError, match="tolerance"):
        stiction.run("slope_slide", integrator="rk4", tolerance=1e-8)


def test_refused_step_names_a_step_that_works():
    with pytest.raises(stiction.StepRefused) as refused:
        stiction.run("sphere_roll", dt=1e-2)
    e = refused.value
    assert isinstance(e, stiction.UnstableError)
    assert 0 < e.suggested_dt < 1e-3
    assert e.step_check["verdict"] == "unstable"
    # The suggestion runs.
    assert stiction.run("sphere_roll", dt=e.suggested_dt, duration=0.1, accuracy=False).status == "ok"


def test_forced_unstable_run_raises_with_its_rows():
    with pytest.raises(stiction.UnstableError) as unstable:
        stiction.run("sphere_roll", dt=2e-3, force_step=True)
    e = unstable.value
    assert e.time > 0 and e.component
    assert e.suggested_dt is not None and e.suggested_dt < 2e-3
    assert e.result.status == "unstable" and len(e.result) > 0
    assert e.result.t[-1] <= e.time + 1e-12


def test_ctrl_c_stops_the_run_and_keeps_its_rows():
    scene = stiction.Scene("slope_hold").set({"simulation.duration": 1e4})
    # The step check comes first (a second or two here); a signal during it stops the run with
    # nothing simulated (result None). Wait longer until the signal falls in the simulation.
    for delay in (3.0, 8.0, 20.0):
        timer = threading.Timer(delay, lambda: os.kill(os.getpid(), signal.SIGINT))
        timer.start()
        with pytest.raises(KeyboardInterrupt) as stopped:
            stiction.run(scene, accuracy=False)
        timer.join()
        e = stopped.value
        assert isinstance(e, stiction.Interrupted)
        assert not isinstance(e, Exception)  # `except Exception` in a loop of runs lets it through
        if e.result is not None:
            break
    assert e.result.status == "interrupted"
    assert 0 < e.result.t[-1] < 1e4
    assert e.result.summary["interrupted"]["phase"] == "simulate"
    # Python's own handler is back: a later SIGINT is a plain KeyboardInterrupt again.
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_runs_on_threads_in_parallel():
    results = [None] * 2

    def work(i):
        results[i] = stiction.run("pendulum_friction", duration=0.5, accuracy=False)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert np.array_equal(results[0].rows, results[1].rows)


def test_a_result_keeps_the_scene_it_ran():
    scene = stiction.Scene("sphere_roll").set("simulation.duration", 0.1)
    first = stiction.run(scene, accuracy=False)
    scene.set("impedances.ground.mu", 0.3)
    assert first.scene.overrides == ["simulation.duration=0.1"]
    assert first.summary["scene"] == "sphere_roll"


def test_dataframe_is_a_copy_to_edit():
    pytest.importorskip("pandas")
    result = stiction.run("slope_slide", duration=0.2, accuracy=False)
    frame = result.to_dataframe()
    frame.iloc[0, 0] = 123.0
    assert result.rows[0, 1] != 123.0


def test_what_the_command_warns_of_is_a_python_warning():
    with pytest.warns(stiction.AccuracyWarning, match="sphere_roll: the run is inaccurate with rk4"):
        stiction.run("sphere_roll", accuracy=True)
    block = {
        "name": "slippery",
        "simulation": {"dt": 1e-4, "duration": 0.1},
        "bodies": {"block": {"type": "point_mass", "mass": 1.0, "position": [0.0, 0.0, -9.8e-6]}},
        "impedances": {"floor": {"type": "kikuuwe_contact", "body": "block", "normal": [0.0, 0.0, 1.0],
                                 "stiffness": 1e6, "damping": 2000.0, "mu": 20.0}},
    }
    scene = stiction.Scene.from_dict(block, name="slippery.toml")
    assert scene.warnings, "mu = 20 is a plausibility warning"
    with pytest.warns(stiction.SceneWarning, match=r"slippery.toml:\d+:\d+: impedances.floor.mu"):
        stiction.run(scene, accuracy=False)


def test_save_refuses_a_directory_it_does_not_own(tmp_path):
    # As `run --out`: a non-empty directory without .stiction-output is the user's (issue 25).
    result = stiction.run("slope_slide", duration=0.05, accuracy=False)
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "trajectory.csv").write_text("the user's\n")
    with pytest.raises(stiction.SceneError, match="overwrite"):
        result.save(mine)
    assert (mine / "trajectory.csv").read_text() == "the user's\n"
    paths = result.save(mine, overwrite=True)
    assert [p.rsplit("/", 1)[1] for p in paths] == ["trajectory.csv", "summary.json"]
    assert (mine / "trajectory.csv").read_text() != "the user's\n"
    assert (mine / ".stiction-output").is_file()
    result.save(mine)  # now its own: saved again without overwrite


def test_arguments_of_the_wrong_type_or_value_are_refused_by_name():
    # Issue 39: accuracy=nan and duration=True were taken; wrong types raised AttributeError
    # from inside the module.
    import math

    for kwargs, error, match in (
        ({"accuracy": math.nan}, TypeError, "accuracy: expected True or False or None"),
        ({"duration": True}, TypeError, "duration: expected a number"),
        ({"dt": "1e-4"}, TypeError, "dt: expected a number"),
        ({"dt": math.inf}, stiction.SceneError, "dt: must be a finite number > 0"),
        ({"duration": -1.0}, stiction.SceneError, "duration: must be a finite number > 0"),
        ({"integrator": 4}, TypeError, "integrator: expected a string"),
        ({"force_step": "yes"}, TypeError, "force_step: expected True or False"),
    ):
        with pytest.raises(error, match=match):
            stiction.run("sphere_roll", **kwargs)
    with pytest.raises(TypeError, match="scene: expected a Scene"):
        stiction.run(42)
    with pytest.raises(TypeError, match="repeats: expected an integer"):
        stiction.study("sphere_roll", repeats=2.5)
