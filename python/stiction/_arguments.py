"""The arguments of the package's functions, checked before they reach the module: a wrong
type is a TypeError naming the argument (not an AttributeError from inside the module), a
value the command line would refuse a SceneError (issue 39: ``accuracy=nan`` and
``duration=True`` used to be taken)."""

import math
import numbers
import os

from .errors import SceneError


def _type_name(value):
    return type(value).__name__


def number(name, value, positive=True):
    """A finite real (not a bool), > 0 when ``positive``; None stays None."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name}: expected a number, got {_type_name(value)} {value!r}")
    value = float(value)
    if not math.isfinite(value) or (positive and not value > 0.0):
        raise SceneError(f"error: {name}: must be a finite number{' > 0' if positive else ''}, got {value!r}")
    return value


def integer(name, value, minimum=0):
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{name}: expected an integer, got {_type_name(value)} {value!r}")
    if value < minimum:
        raise SceneError(f"error: {name}: must be at least {minimum}, got {value!r}")
    return int(value)


def flag(name, value, optional=False):
    """True or False (NumPy's bool too); None when ``optional``."""
    if value is None and optional:
        return None
    if isinstance(value, bool) or type(value).__name__ == "bool_":
        return bool(value)
    raise TypeError(f"{name}: expected True or False{' or None' if optional else ''}, "
                    f"got {_type_name(value)} {value!r}")


def text(name, value, optional=True):
    if value is None and optional:
        return None
    if not isinstance(value, str):
        raise TypeError(f"{name}: expected a string, got {_type_name(value)} {value!r}")
    return value


def names(name, values):
    """A list of strings from any iterable of strings (a single string is one name)."""
    if values is None:
        return []
    if isinstance(values, str):
        return [values]
    try:
        items = list(values)
    except TypeError:
        raise TypeError(f"{name}: expected a list of strings, got {_type_name(values)} {values!r}") from None
    for item in items:
        text(name, item, optional=False)
    return items


def scene_source(value):
    """A bundled name or a path (str or os.PathLike)."""
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if not isinstance(value, str):
        raise TypeError(f"scene: expected a Scene, a bundled scene's name or a path, got "
                        f"{_type_name(value)} {value!r}")
    return value
