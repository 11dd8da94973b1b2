"""The result of a run: NumPy views of the rows, the summary, events and units."""

import json
import os

from . import _stiction


class Result:
    """What one run produced.

    ``t`` and ``result["sphere.v.x"]`` are NumPy arrays (read-only views of the run's rows, no
    copy; SI units, see ``units``). ``summary`` is the content of summary.json as a dict;
    ``events`` and ``intervals`` give each element's stick/slip events and regimes;
    ``status`` is "ok", "unstable" or "interrupted". ``save(dir)`` writes trajectory.csv and
    summary.json exactly as ``stiction run --no-video --no-plots`` does.
    """

    def __init__(self, handle, scene):
        self._handle = handle
        self.scene = scene
        self._rows = handle.rows()
        self.columns = list(handle.columns)
        self._index = {c: i for i, c in enumerate(self.columns)}
        infos = handle.units
        self.units = {name: unit for name, unit, _ in infos}
        self.descriptions = {name: text for name, _, text in infos}
        self.summary = handle.summary

    # --- the rows
    @property
    def rows(self):
        """All rows as a (rows, columns) float64 array (read-only, no copy)."""
        return self._rows

    @property
    def t(self):
        """Time of each row, s."""
        return self._rows[:, 0]

    def __getitem__(self, column):
        """The column named as in trajectory.csv's header (e.g. "sphere.v.x"), a view."""
        try:
            return self._rows[:, self._index[column]]
        except KeyError:
            near = [c for c in self.columns if c.startswith(column.split(".")[0] + ".")]
            hint = f"; columns of '{column.split('.')[0]}': {', '.join(near)}" if near else ""
            raise KeyError(f"no column '{column}'{hint}") from None

    def __contains__(self, column):
        return column in self._index

    def __len__(self):
        return self._rows.shape[0]

    def signals(self, prefix):
        """The columns that start with ``prefix`` (an element's name), as a dict of views."""
        return {c: self[c] for c in self.columns if c == prefix or c.startswith(prefix + ".")}

    # --- what summary.json says
    @property
    def status(self):
        """ "ok", "unstable" or "interrupted"."""
        return self._handle.status

    @property
    def events(self):
        """Stick and slip events per element: {element: [{"kind", "time", ...}, ...]}."""
        return {name: e.get("events", []) for name, e in self.summary.get("events", {}).items()}

    @property
    def intervals(self):
        """Stick/slip regimes per element: {element: [{"regime", "start", "end"}, ...]}."""
        return {name: e.get("intervals", []) for name, e in self.summary.get("events", {}).items()}

    @property
    def accuracy(self):
        """The run's error estimate (summary.json's ``accuracy``; docs/accuracy.md)."""
        return self.summary.get("accuracy")

    @property
    def final(self):
        """The last row's values by column name."""
        return {c: float(self._rows[-1, i]) for i, c in enumerate(self.columns)} if len(self) else {}

    @property
    def steps(self):
        return self._handle.steps

    @property
    def wall_seconds(self):
        """Wall-clock time of the simulation, s."""
        return self._handle.wall_seconds

    # --- conversions and files
    def to_dataframe(self):
        """A pandas DataFrame indexed by time, a copy of the rows (pandas must be installed:
        python3-pandas)."""
        try:
            import pandas as pd
        except ImportError as e:
            raise ImportError("to_dataframe() needs pandas (Debian: apt-get install python3-pandas)") from e
        # A copy: the rows themselves are read-only, a DataFrame is for editing too.
        frame = pd.DataFrame(self._rows[:, 1:].copy(), columns=self.columns[1:], index=pd.Index(self.t, name="t"))
        frame.attrs["units"] = dict(self.units)
        return frame

    def save(self, directory, overwrite=False):
        """Writes trajectory.csv and summary.json into ``directory`` (created if needed), as
        ``stiction run --no-video --no-plots --out directory`` does, under its rules: a
        non-empty directory that no stiction run wrote (no ``.stiction-output``) is refused
        with :class:`stiction.SceneError` unless ``overwrite=True`` (``--overwrite``).
        Returns their paths."""
        return self._handle.save(os.fspath(directory), overwrite)

    def summary_json(self):
        """The summary as JSON text (without ``files``; ``save`` writes summary.json itself)."""
        return json.dumps(self.summary, indent=2, ensure_ascii=False) + "\n"

    def __repr__(self):
        s = self.summary
        text = (f"<stiction.Result {s.get('scene')}: {s.get('integrator')}, dt = {s.get('dt'):g} s, "
                f"{len(self)} rows x {len(self.columns)} columns, status {self.status}")
        return text + ">"


_ = _stiction  # the extension is loaded with the package
