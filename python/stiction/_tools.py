"""check, study, sweep and compare: the command line's tools from Python, through the same
services (docs/python.md, docs/sweeps.md, docs/study.md)."""

import math
import os
import tomllib

from . import _arguments, _stiction, _toml
from ._result import Result
from ._run import run
from ._scene import as_scene
from .errors import Interrupted, SceneError


def check(scene):
    """What ``stiction check SCENE --json`` prints, as a dict: the state layout, the stiffest
    elements (stiffness N/m or N m/rad, effective mass kg or kg m^2, omega rad/s) and
    ``step_limits``: per fixed-step integrator the step (s) above which a run goes unstable
    (``unstable_above``), above which stuck friction chatters (``chatters_above``), and a
    recommended step (``recommended_step``, s, confirmed by trial runs when
    ``recommended_confirmed``).

    ``scene`` is a :class:`Scene` or a bundled name or .toml path. A scene that cannot be read
    raises :class:`SceneError` (where the command prints ``{"ok": false, ...}``).
    """
    return _stiction._check(as_scene(scene)._handle)


# ---------------------------------------------------------------------------------- tables

def _numbers(texts):
    """A column of table text as float64 (empty: NaN), or None when some field is no number."""
    import numpy as np

    values = []
    for text in texts:
        if text == "":
            values.append(math.nan)
            continue
        try:
            values.append(float(text))
        except ValueError:
            return None
    return np.array(values, dtype=np.float64)


def _texts(texts):
    import numpy as np

    return np.array(list(texts), dtype=object)


def _dataframe(table):
    try:
        import pandas as pd
    except ImportError as e:  # pragma: no cover - pandas is optional
        raise ImportError("to_dataframe() needs pandas (python3-pandas)") from e
    return pd.DataFrame(table)


def _toml_value(text):
    """A TOML value's text as the Python value (the text itself if it is not one)."""
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        return text


# ---------------------------------------------------------------------------------- study

_STUDY_TEXT_COLUMNS = ("integrator", "status", "unstable_component", "worst_signal",
                       "accuracy_failure")


class Study:
    """The result of :func:`study`: speed against accuracy of the integrators on one scene.

    ``table``: dict column -> NumPy array, one entry per run, the columns of study.csv at full
    precision (``dt``, ``wall_seconds``, ``cpu_seconds`` in s; ``key_error`` and the
    ``*_relative_error_*`` relative; ``*_time_*`` and ``*_error_*`` of events in s; NaN where
    study.csv leaves a field empty); ``to_dataframe()`` the same as a pandas DataFrame.
    ``recommendation``: the cheapest run within ``target_error`` (integrator, dt in s,
    tolerance, cpu_per_second: CPU s per simulated s), or integrator None when no run met it.
    ``limits``: per fixed-step integrator the predicted, bisected and accurate step limits (s).
    ``orders``: observed order per integrator. ``markdown``: study.md's text.
    ``write(dir)`` writes study.csv, study.md and work_precision.png as ``stiction study`` does.
    """

    def __init__(self, handle):
        import numpy as np

        self._handle = handle
        self.scene = handle.scene
        table = {}
        for name, values in handle.table.items():
            if name in _STUDY_TEXT_COLUMNS:
                table[name] = _texts(values)
            elif name in ("steps", "evaluations", "repeats"):
                table[name] = np.array(values, dtype=np.int64)
            elif name == "meets_target":
                table[name] = np.array(values, dtype=bool)
            else:
                table[name] = np.array(values, dtype=np.float64)
        self.table = table
        self.recommendation = handle.recommendation
        self.candidates = handle.candidates
        self.limits = handle.limits
        self.orders = handle.orders
        self.reference = handle.reference
        self.key_signals = list(handle.key_signals)
        self.notes = list(handle.notes)
        self.target_error = handle.target_error
        self.seconds = handle.total_seconds

    @property
    def columns(self):
        return list(self.table)

    @property
    def markdown(self):
        """study.md's text (the tables ``stiction study`` prints)."""
        return self._handle.markdown()

    def to_dataframe(self):
        """The table as a pandas DataFrame (one row per run)."""
        return _dataframe(self.table)

    def write(self, dir):  # noqa: A002 - as on the command line
        """Writes study.csv, study.md and work_precision.png into ``dir``; returns their paths."""
        os.makedirs(dir, exist_ok=True)
        self._handle.write(os.fspath(dir))
        return [os.path.join(dir, f) for f in ("study.csv", "study.md", "work_precision.png")]

    def __len__(self):
        return len(self.table.get("integrator", ()))

    def _repr_markdown_(self):
        return self.markdown

    def __repr__(self):
        r = self.recommendation
        if r["integrator"] is None:
            best = f"no run within {self.target_error:g}"
        elif r.get("tolerance"):  # an adaptive integrator's setting is its tolerance
            best = f"{r['integrator']}, tolerance {r['tolerance']:g}"
        else:
            best = f"{r['integrator']}, dt = {r['dt']:g} s"
        return (f"<stiction.Study {self.scene!r}: {len(self)} runs in {self.seconds:.1f} s; "
                f"recommended: {best}>")


def study(scene, integrators=None, dts=None, tolerances=None, reference_dt=None, repeats=3,
          target_error=1e-3, progress=False):
    """Speed against accuracy of the integrators on a scene, as ``stiction study`` measures it
    (docs/study.md); returns a :class:`Study`.

    integrators   names to study (default: every integrator)
    dts           fixed steps to run, s (default: around the limits ``check`` predicts)
    tolerances    rk4_adaptive's tolerances (default 1e-4 .. 1e-10)
    reference_dt  the reference run's step, s (default: the scene's dt / 16)
    repeats       timing repeats per run (the median is kept)
    target_error  relative accuracy a run must meet (event times, final values), in (0, 1)
    progress      print one line per run to stderr
    """
    handle = _stiction._study(as_scene(scene)._handle, _arguments.names("integrators", integrators),
                              [_arguments.number("dts", d) for d in (dts if dts is not None else [])],
                              [_arguments.number("tolerances", t)
                               for t in (tolerances if tolerances is not None else [])],
                              _arguments.number("reference_dt", reference_dt),
                              _arguments.integer("repeats", repeats, minimum=1),
                              _arguments.number("target_error", target_error),
                              _arguments.flag("progress", progress))
    return Study(handle)


# ---------------------------------------------------------------------------------- sweep

class Sweep:
    """The result of :func:`sweep`: one row per point, the columns of ``stiction sweep``'s
    sweep.csv (docs/sweeps.md).

    ``table``: dict column -> NumPy array: ``point`` (int), each varied key (float when its
    values are numbers, else their TOML text), ``status`` ("ok", "unstable", "refused",
    "error"), ``steps``, ``wall_s`` (simulation wall time, s), ``suggested_dt`` (s), ``note``,
    per contact or joint ``<name>.stick_time``, ``.first_slip``, ``.last_stick`` (s, NaN:
    none) and ``.events`` ("stick:0.58;slip:0.91"), then the final value of each recorded
    signal (SI units, as the run's columns). ``to_dataframe()`` gives a pandas DataFrame;
    ``points`` each point's values as a dict; ``write(dir)`` writes sweep.csv, sweep.md,
    sweep.png, sweep.svg and sweep.plan.json as the command does.
    """

    def __init__(self, handle):
        import numpy as np

        self._handle = handle
        self.scene = handle.scene
        self.keys = [key for key, _ in handle.keys]
        self.columns = list(handle.header)
        rows = handle.rows
        by_column = list(zip(*rows)) if rows else [() for _ in self.columns]
        text_columns = {"status", "note"}
        table = {}
        for name, texts in zip(self.columns, by_column):
            if name == "point":
                table[name] = np.array([int(t) for t in texts], dtype=np.int64)
                continue
            numbers = None if name in text_columns or name.endswith(".events") else _numbers(texts)
            table[name] = numbers if numbers is not None else _texts(texts)
        self.table = table
        self._texts = {name: list(texts) for name, texts in zip(self.columns, by_column)}
        self.points = [dict(zip(self.keys, (_toml_value(v) for v in values)))
                       for values in handle.points]

    def text(self, column):
        """A column's fields exactly as sweep.csv writes them (list of str)."""
        return list(self._texts[column])

    def to_dataframe(self):
        """The table as a pandas DataFrame, indexed by point."""
        return _dataframe(self.table).set_index("point")

    def write(self, dir, overwrite=False):  # noqa: A002 - as on the command line
        """Writes sweep.csv, sweep.md, sweep.plan.json and, when a column has values to plot,
        sweep.png and sweep.svg into ``dir``, as ``stiction sweep`` does; returns their paths.
        A directory holding another sweep, or other files and no sweep, is refused with
        :class:`stiction.SceneError` unless ``overwrite=True`` (``--overwrite``)."""
        figure = self._handle.write(os.fspath(dir), overwrite)
        names = ["sweep.csv", "sweep.md", "sweep.plan.json"]
        if figure:
            names += ["sweep.png", "sweep.svg"]
        return [os.path.join(dir, n) for n in names]

    @property
    def status(self):
        """{status: number of points}."""
        counts = {}
        for s in self._texts.get("status", []):
            counts[s] = counts.get(s, 0) + 1
        return counts

    def __len__(self):
        return len(self._texts.get("point", []))

    def __repr__(self):
        counts = ", ".join(f"{n} {s}" for s, n in sorted(self.status.items()))
        return (f"<stiction.Sweep {self.scene!r}: {len(self)} points over "
                f"{', '.join(self.keys)} ({counts}); {len(self.columns)} columns>")


def sweep(scene, vary, zip=False, jobs=0, record=None, plot=None, integrator=None, dt=None,  # noqa: A002
          duration=None, tolerance=None, force_step=False, progress=False):
    """Runs a scene once per point of a grid of key values, as ``stiction sweep`` does
    (docs/sweeps.md), on ``jobs`` threads (0: every core) with the GIL released; returns a
    :class:`Sweep`.

    vary        {key: values}: a key as ``Scene.set`` spells it ("impedances.ground.mu",
                "bodies.sphere.velocity[0]") and its values as a list (Python values) or as
                the command line's LIST text ("0.05:0.5:10", "0.01:1:20:log", "1,2,4")
    zip         pair the lists element-wise instead of the grid of all combinations (the last
                key varies fastest in a grid)
    record      signals whose final value goes into the table (default: every signal)
    plot        table columns write() plots (default: every contact's stick and slip times)
    integrator, dt (s), duration (s), tolerance: for every point, as on the command line
    force_step  simulate the points the step guard predicts unstable
    progress    print the count of finished points to stderr

    A point that fails is a row with its status (never an exception). Ctrl-C stops the sweep
    and raises :class:`Interrupted` whose ``result`` is the Sweep of the finished points.
    """
    if not vary:
        raise SceneError("error: sweep: vary at least one key")
    keys = []
    for key, values in vary.items():
        if isinstance(values, str):
            keys.append((key, values))
        else:
            keys.append((key, [_toml.value(v) for v in values]))
    handle = _stiction._sweep(as_scene(scene)._handle, keys, _arguments.flag("zip", zip),
                              _arguments.integer("jobs", jobs), _arguments.names("record", record),
                              _arguments.names("plot", plot), _arguments.text("integrator", integrator),
                              _arguments.number("dt", dt), _arguments.number("duration", duration),
                              _arguments.number("tolerance", tolerance),
                              _arguments.flag("force_step", force_step),
                              _arguments.flag("progress", progress))
    result = Sweep(handle)
    if handle.interrupted:
        raise Interrupted(f"sweep of {result.scene}: interrupted after {len(result)} of "
                          f"{len(handle.points)} points; the finished ones are in .result",
                          result=result)
    return result


# ---------------------------------------------------------------------------------- compare

class Comparison(list):
    """The runs :func:`compare` overlaid (a list of :class:`Result`), with ``labels`` and the
    figure's ``path``."""

    def __init__(self, results, labels, path):
        super().__init__(results)
        self.labels = labels
        self.path = path

    def __repr__(self):
        return f"<stiction.Comparison of {len(self)} runs ({'; '.join(self.labels)}) -> {self.path}>"


def compare(runs, out=os.path.join("out", "compare"), signals=None, duration=None, format="png",  # noqa: A002
            force_step=False):
    """Overlays runs in one figure, ``out/compare.png``, as ``stiction compare`` does: the arm
    scenes' drift comparison, else the signals the runs have in common, or ``signals``.

    runs        scenes (Scene, name or path), finished :class:`Result` objects, or
                (either, label) pairs; a run's default label is its scene name plus the
                overrides set on it that the other runs do not share
    signals     columns (or "<element>.<signal>" groups) to plot
    duration    simulated time of the scenes run here, s (default: each scene's)
    format      "png", "svg" or "pdf"
    force_step  run a step the step guard predicts unstable

    Scenes are run as ``stiction.run(scene, duration=duration, accuracy=False)`` would (so
    :class:`StepRefused` / :class:`UnstableError` as there). Returns a :class:`Comparison`:
    the list of Results, with ``labels`` and ``path``.
    """
    entries = []
    for item in runs:
        label = None
        if isinstance(item, tuple):
            item, label = item
        entries.append((item, label))
    if len(entries) < 2:
        raise SceneError(f"error: compare needs at least two scenes (got {len(entries)})")
    scenes = [item.scene if isinstance(item, Result) else as_scene(item) for item, _ in entries]
    labels = _stiction._comparison_labels([s.name for s in scenes], [s.overrides for s in scenes])
    labels = [given if given is not None else default
              for (_, given), default in zip(entries, labels)]
    columns = [(item.columns if isinstance(item, Result) else s.columns)[1:]
               for (item, _), s in zip(entries, scenes)]
    _stiction._check_comparison_signals(labels, columns, list(signals or []))
    results = []
    for (item, _), s in zip(entries, scenes):
        results.append(item if isinstance(item, Result)
                       else run(s, duration=duration, accuracy=False, force_step=force_step))
    path = _stiction._compare([(label, r.rows, r.columns, r.scene._handle)
                               for label, r in zip(labels, results)],
                              list(signals or []), os.fspath(out), format)
    return Comparison(results, labels, str(path))


__all__ = ["check", "study", "Study", "sweep", "Sweep", "compare", "Comparison"]
