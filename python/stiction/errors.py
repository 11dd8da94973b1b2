"""The exceptions of stiction.

Every error the package raises derives from :class:`Error`, except :class:`Interrupted`
(Ctrl-C), a ``KeyboardInterrupt``. A scene that cannot be read or
built raises :class:`SceneError` (also a ``ValueError``) with the place it names: ``file``,
``line``, ``column`` and ``key``, as the command line prints them (exit code 2 there).
"""

import re

_LOCATED = re.compile(r"^(?P<file>.*?):(?P<line>\d+):(?P<column>\d+): error: (?P<message>.*)$", re.S)
_KEY = re.compile(r"^(?P<key>[A-Za-z0-9_.\[\]\-]+): ")


class Error(Exception):
    """Base class of stiction's errors."""


class SceneError(Error, ValueError):
    """A scene that cannot be read, set or built.

    Attributes: ``file`` (str or None), ``line`` and ``column`` (int, 1-based, or None),
    ``key`` (the dotted key the message is about, or None) and ``message`` (the text after
    ``error:``).
    """

    def __init__(self, text):
        super().__init__(text)
        self.file = self.line = self.column = self.key = None
        self.message = text
        located = _LOCATED.match(text)
        if located:
            self.file = located["file"]
            self.line = int(located["line"])
            self.column = int(located["column"])
            self.message = located["message"]
        elif text.startswith("error: "):
            self.message = text[len("error: "):]
        key = _KEY.match(self.message)
        if key:
            self.key = key["key"]
        elif self.file and self.file.startswith("--set "):  # a value given to Scene.set
            self.key = self.file[len("--set "):]


class OutputError(Error, OSError):
    """A file or directory that cannot be written (the command line's exit code 1)."""


class UnstableError(Error):
    """The run became numerically unstable (the command line's exit code 3).

    Attributes: ``time`` (s), ``component`` (the element where it showed), ``reason``,
    ``suggested_dt`` (s, a step to try; for rk4_adaptive a tolerance is suggested in the
    message instead) and ``result`` (the rows up to the instability, a :class:`Result`).
    """

    def __init__(self, text, time=None, component=None, reason=None, suggested_dt=None, result=None):
        super().__init__(text)
        self.time = time
        self.component = component
        self.reason = reason
        self.suggested_dt = suggested_dt
        self.result = result


class StepRefused(UnstableError):
    """The step guard predicted the step unstable; nothing was simulated.

    ``suggested_dt`` is a step to use (confirmed by a trial when the message says "a step that
    works"); ``step_check`` the guard's findings (as summary.json's ``step_check``). Pass
    ``force_step=True`` to run anyway.
    """

    step_check = None


class Interrupted(KeyboardInterrupt):
    """Ctrl-C stopped the run; ``result`` holds what was simulated up to then.

    A KeyboardInterrupt and not an :class:`Error` (nor an ``Exception``), so that
    ``except Exception`` in a loop of runs does not swallow Ctrl-C."""

    def __init__(self, text, result=None):
        super().__init__(text)
        self.result = result


class SceneWarning(UserWarning):
    """A plausibility warning of the scene or the step guard's warning (summary.json's
    ``warnings``: a value that is valid but looks like a mistake, a step above the chatter
    limit), issued by :func:`stiction.run` as the command prints it on stderr."""


class AccuracyWarning(UserWarning):
    """The run's error estimate found it inaccurate (summary.json's ``accuracy.verdict``;
    ``result.accuracy["reasons"]`` says why; docs/accuracy.md)."""
