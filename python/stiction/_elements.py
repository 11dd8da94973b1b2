"""Controllers and custom elements written in Python (docs/scene_format.md, "Elements
supplied in code").

A source law replaces the value of a ``torque_source`` or ``force_source`` of the scene::

    def pd(t, s):                     # t in s; s: signals by column name, SI units
        return 20 * (1 - s["arm.theta.0"]) - 0.5 * s["arm.omega.0"]   # N·m
    scene.set_source("controller", pd)

An impedance subclasses :class:`Impedance` and is wired by a table
``[impedances.NAME] type = "external"`` of the scene, which needs it to load::

    scene = stiction.Scene("arm.toml", elements={"joint": ViscousCoulomb(coulomb=0.5)})
    scene.set_element("joint", ViscousCoulomb, coulomb=0.2)   # a fresh object per build

Both are called at every integrator stage, with the GIL taken; a Python exception inside
them stops the run and is raised by :func:`stiction.run`.
"""

import collections.abc
import copy
import hashlib
import inspect
import pickle
import types

from . import _stiction
from ._scene import Scene

State = _stiction.State
collections.abc.Mapping.register(State)


class Impedance:
    """An impedance element written in Python (the paper's I(x_hat, y; tau)), wired to the
    scene by a table ``[impedances.NAME] type = "external"``:

    - on a planar_arm joint (``body``, ``joint``): x_hat = [angle (rad), rate (rad/s)],
      u = 1 torque (N·m);
    - about an axis of a rigid body (``body``, ``axis``, optional ``parent``): the same;
    - at a point of a body (``body``, ``point``, ``frame``): x_hat = [position (m, 3),
      velocity (m/s, 3)] of the point in the world, u = 3 force entries (N).

    u is what the moving side exerts on the element: the body receives -u (a damper returns
    u = b * v). Define in the subclass:

    input_size, output_size, state_size
        ints (attributes or properties); the defaults fit a joint element without state.
    evaluate(t, x_hat, y, tau) -> (u, y_dot)
        t stage time (s), x_hat and y read-only NumPy arrays (refilled before every call:
        copy what you keep), tau the stage step (s). Return sequences or arrays (a number
        for a size of 1; y_dot may be None without state).
    initial_state() -> sequence (optional; zeros otherwise), state_labels (optional names)
    signals() -> [(name, unit) or (name, unit, description), ...] and
    write_signals(x_hat, y, u) -> the values (optional; otherwise one signal "u")
        the element's columns in the trajectory ("NAME.<signal>").
    slip_velocity(x_hat) -> a number or 3 (optional): a sliding pair, with stick/slip
        events as the bundled friction elements (a joint returns x_hat[1]).
    stiffness (optional, N/m or N·m/rad): the largest stiffness it puts between its ports,
        for the step guard's and ``stiction.check``'s advice.
    stored_energy(x_hat, y) -> J (optional): the energy it holds (a spring's 1/2 k x^2). The
        energy monitor stops a run whose energy rises past what the sources put in; without
        this, an element that stores energy and gives it back looks like such a rise.
    """

    input_size = 2
    output_size = 1
    state_size = 0
    stiffness = None

    def evaluate(self, t, x_hat, y, tau):
        raise NotImplementedError(f"{type(self).__name__}.evaluate(t, x_hat, y, tau) -> (u, y_dot)")

    def __repr__(self):
        return (f"<{type(self).__name__} (stiction.Impedance): {self.input_size} in, "
                f"{self.output_size} out, {self.state_size} states>")


def set_source(self, name, law, signals=None):
    """Gives the torque_source or force_source ``name`` a law written in Python, replacing
    its ``torque`` / ``force`` value in the file (then only a placeholder, which may be left
    out).

    law(t, state) -> a number (torque, N·m) or 3 numbers (force, N), called at every
    integrator stage from the stage state. ``t`` is the stage time (s); ``state`` a read-only
    mapping (:class:`stiction.State`) from column name to value (SI units) of ``signals``:
    by default every signal of the scene's bodies (their states, e.g. "arm.theta.0"), or the
    columns listed (any signal of the scene, other elements' outputs too). ``law=None``
    removes it. Raises :class:`stiction.SceneError` for an unknown source or signal.
    Returns the scene.
    """
    if law is not None:
        law, signals = _law(name, (law, signals))
    _stiction._set_source(self._handle, name, law, signals)
    return self


def _value_text(value):
    """Bytes that change when a value does: its pickle, else its repr (an object's repr with
    an address changes between runs, which only costs a cache miss)."""
    try:
        return pickle.dumps(value, protocol=4)
    except Exception:
        return repr(value).encode()


def _function_text(fn, seen):
    """The source of a function with the values it reads: defaults, closure cells and the
    globals it names (functions among them followed once)."""
    parts = [inspect.getsource(fn).encode()]
    parts.append(_value_text(fn.__defaults__))
    parts.append(_value_text(fn.__kwdefaults__))
    for cell in fn.__closure__ or ():
        try:
            parts.append(_value_text(cell.cell_contents))
        except ValueError:  # an empty cell
            parts.append(b"<empty>")
    for name in fn.__code__.co_names:
        if name not in fn.__globals__:
            continue
        value = fn.__globals__[name]
        if isinstance(value, types.ModuleType):
            parts.append(name.encode() + b"=module " + value.__name__.encode())
        elif isinstance(value, types.FunctionType):
            if value not in seen:
                seen.add(value)
                parts.append(_function_text(value, seen))
        elif isinstance(value, type):
            parts.append(inspect.getsource(value).encode())
        else:
            parts.append(name.encode() + b"=" + _value_text(value))
    return b"\0".join(parts)


def _fingerprint(obj):
    """A text that changes whenever a law's or an element's behaviour may (its source code and
    the values it reads), for the step check's cache; None when it cannot be read (a law typed
    at an interactive prompt, a builtin): then the scene is not cached."""
    try:
        target = getattr(obj, "_stiction_made_from", obj)
        if isinstance(target, tuple):  # (class or instance, args, kwargs) of an element maker
            element, args, kwargs = target
            cls = element if isinstance(element, type) else type(element)
            text = b"\0".join([inspect.getsource(cls).encode(), _value_text(args),
                               _value_text(kwargs),
                               b"" if isinstance(element, type) else _value_text(element.__dict__)])
        elif isinstance(target, types.MethodType):
            text = _function_text(target.__func__, set()) + _value_text(target.__self__)
        elif isinstance(target, types.FunctionType):
            text = _function_text(target, set())
        else:  # a callable object
            text = inspect.getsource(type(target)).encode() + _value_text(target.__dict__)
        return hashlib.sha256(text).hexdigest()
    except Exception:
        return None


def _maker(element, args=(), kwargs=None):
    """A zero-argument callable making a fresh Python element for every scene build."""
    kwargs = kwargs or {}
    if element is None:
        return None
    if isinstance(element, type):
        if not issubclass(element, Impedance):
            raise TypeError(f"{element.__name__} is not a subclass of stiction.Impedance")
        maker = lambda: element(*args, **kwargs)  # noqa: E731
        maker._stiction_made_from = (element, args, kwargs)
        return maker
    if isinstance(element, Impedance):
        if args or kwargs:
            raise TypeError("arguments are for a class, not for an instance")
        maker = lambda: copy.deepcopy(element)  # noqa: E731
        maker._stiction_made_from = (element, (), {})
        return maker
    raise TypeError(f"expected a subclass of stiction.Impedance or an instance, got {element!r}")


def _law(name, law):
    """(law, signals) from a callable or a (callable, signals) pair."""
    signals = None
    if isinstance(law, tuple):
        law, signals = law
    if not callable(law):
        raise TypeError(f"source {name!r}: the law must be callable as law(t, state), got {law!r}")
    if isinstance(signals, str):
        signals = [signals]
    return law, None if signals is None else list(signals)


def load(name_or_path, text, origin, assignments, sources, elements):
    """A scene handle loaded with its sources and elements in code (Scene(..., sources=...,
    elements=...)): a file whose torque_source has no value, or with `type = "external"`
    tables, needs them to load at all."""
    source_items = [(name, *_law(name, law)) for name, law in (sources or {}).items()]
    element_items = [(name, _maker(element)) for name, element in (elements or {}).items()]
    return _stiction._load_with_elements(name_or_path or "", text or "", origin or "",
                                         assignments, source_items, element_items)


def set_element(self, name, element, *args, **kwargs):
    """Supplies the impedance of the table ``[impedances.NAME] type = "external"``.

    ``element`` is a subclass of :class:`Impedance` (made as ``element(*args, **kwargs)``)
    or an instance (deep-copied): every build of the scene (each run, each sweep point) gets
    a fresh object, so state kept in it does not leak from one run to the next. ``None``
    removes it. Raises :class:`stiction.SceneError` when its sizes do not fit the table's
    wiring. Returns the scene.
    """
    _stiction._set_element(self._handle, name, _maker(element, args, kwargs))
    return self


def _externals(self):
    """The names of the sources and elements supplied in code: {"sources": [...], "elements": [...]}."""
    sources, elements = _stiction._externals(self._handle)
    return {"sources": list(sources), "elements": list(elements)}


# Methods of Scene, kept here with the rest of the Python elements.
Scene.set_source = set_source
Scene.set_element = set_element
Scene.externals = property(_externals)
