"""Scenes: a bundled name, a .toml file, a TOML string or a dict, with keys set as ``--set`` does."""

import os

from . import _arguments, _stiction, _toml


class Scene:
    """A scene (docs/scene_format.md), loaded and checked at once.

    ``Scene("sphere_roll")`` loads a bundled scene, ``Scene("my.toml")`` a file,
    ``Scene.from_toml(text)`` and ``Scene.from_dict(d)`` a scene written in Python.
    ``set`` changes any key as the command line's ``--set KEY=VALUE`` does, and reports a bad
    value as :class:`stiction.SceneError` (file, line, column, key) without changing the scene.
    ``sources={"name": law}`` and ``elements={"name": Impedance}`` supply laws and elements in
    Python from the start (as ``set_source`` and ``set_element`` do later).

    Read: ``name``, ``description``, ``integrator``, ``dt`` (s), ``duration`` (s),
    ``output_rate`` (rows/s), ``tolerance``, ``columns`` (the trajectory's column names),
    ``units`` (column -> SI unit), ``state_size``, ``warnings`` (plausibility warnings) and
    ``toml`` (the document after every override).
    """

    def __init__(self, name_or_path, set=None, sources=None, elements=None):  # noqa: A002 - `set` as on the command line
        if isinstance(name_or_path, _stiction._Scene):
            self._handle = name_or_path
            return
        if sources or elements:  # laws and elements in Python: set_source, set_element
            from ._elements import load
            self._handle = load(os.fspath(name_or_path), None, None, _assignments(set, {}), sources, elements)
            return
        self._handle = _stiction._Scene.load(os.fspath(name_or_path), _assignments(set, {}))

    @classmethod
    def from_toml(cls, text, name="<string>", set=None, sources=None, elements=None):  # noqa: A002
        """A scene from TOML text; ``name`` stands for the file in error messages and names the
        scene when the text has no ``name`` key."""
        if sources or elements:
            from ._elements import load
            return cls(load(None, text, name, _assignments(set, {}), sources, elements))
        return cls(_stiction._Scene.from_text(text, name, _assignments(set, {})))

    @classmethod
    def from_dict(cls, document, name="<dict>", set=None, sources=None, elements=None):  # noqa: A002
        """A scene from nested dicts shaped as the TOML file (tables as dicts, [[plots]] as a
        list of dicts)."""
        return cls.from_toml(_toml.document(document), name=name, set=set, sources=sources,
                             elements=elements)

    def set(self, key_or_dict=None, value=None, **keys):
        """Sets keys as ``--set KEY=VALUE`` does: ``scene.set("impedances.ground.mu", 0.2)``,
        ``scene.set({"impedances.ground.mu": 0.2, "simulation.dt": 1e-5})``. Values are Python values
        (numbers, strings, bools, lists, dicts). Returns the scene, so calls chain."""
        if isinstance(key_or_dict, str):
            keys = {key_or_dict: value, **keys}
        elif key_or_dict is not None:
            keys = {**dict(key_or_dict), **keys}
        self._handle.set(_assignments(keys, {}))
        return self

    def copy(self):
        """An independent copy (set() on one leaves the other as it is)."""
        return Scene(self._handle.copy())

    def run(self, **options):
        """Runs this scene: ``stiction.run(scene, **options)``."""
        from ._run import run

        return run(self, **options)

    name = property(lambda self: self._handle.name)
    description = property(lambda self: self._handle.description)
    path = property(lambda self: self._handle.path, doc="The file it came from (or the name given to a text).")
    integrator = property(lambda self: self._handle.integrator)
    dt = property(lambda self: self._handle.dt, doc="Step size, s.")
    duration = property(lambda self: self._handle.duration, doc="Simulated time, s.")
    output_rate = property(lambda self: self._handle.output_rate, doc="Rows per simulated second.")
    tolerance = property(lambda self: self._handle.tolerance, doc="rk4_adaptive's tolerance (0: none).")
    state_size = property(lambda self: self._handle.state_size)
    toml = property(lambda self: self._handle.toml, doc="The document after every override, as TOML.")
    overrides = property(lambda self: list(self._handle.overrides), doc="The KEY=VALUE assignments set so far.")
    warnings = property(lambda self: self._handle.warnings)

    @property
    def columns(self):
        """The trajectory's column names, "t" first."""
        return [name for name, _, _ in self._handle.columns]

    @property
    def units(self):
        """Column name -> SI unit ("" for dimensionless)."""
        return {name: unit for name, unit, _ in self._handle.columns}

    def describe(self, column):
        """What a column holds, with its unit."""
        for name, unit, text in self._handle.columns:
            if name == column:
                return f"{name}: {text}" + (f" [{unit}]" if unit else "")
        raise KeyError(column)

    def __repr__(self):
        return (f"<stiction.Scene {self.name!r}: {self.integrator}, dt = {self.dt:g} s, "
                f"duration {self.duration:g} s, {self.state_size} states, {len(self.columns)} columns>")


def scenes():
    """The bundled scenes: {name: one-line description}."""
    return dict(_stiction._bundled_scenes())


def as_scene(scene):
    """A Scene from a Scene or a name/path."""
    return scene if isinstance(scene, Scene) else Scene(_arguments.scene_source(scene))


def _assignments(mapping, keys):
    items = dict(mapping or {})
    items.update(keys)
    return [f"{k}={_toml.value(v)}" for k, v in items.items()]
