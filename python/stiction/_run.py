"""stiction.run: `stiction run` from Python."""

import warnings

from . import _arguments, _stiction
from ._result import Result
from ._scene import as_scene
from .errors import AccuracyWarning, Interrupted, SceneWarning, UnstableError


def run(scene, integrator=None, dt=None, duration=None, tolerance=None, accuracy=None,
        force_step=False, progress=False):
    """Simulates a scene and returns a :class:`Result`.

    scene       a :class:`Scene`, or a bundled name or .toml path
    integrator  "rk4", "euler", "symplectic_euler", "rk4_adaptive", "implicit", "sdirk2",
                "sdirk4", ... (default: the scene's)
    dt          step size, s (default: the scene's)
    duration    simulated time, s (default: the scene's)
    tolerance   local error bound per state entry; runs the adaptive integrator named
                (rk4_adaptive, sdirk2, sdirk4), rk4_adaptive by default
    accuracy    True/False: estimate the run's error with a companion run at dt/2
                (docs/accuracy.md); None: when it costs little, as on the command line
    force_step  simulate even when the step guard predicts the step unstable
    progress    print progress to stderr

    Says what the command says on stderr as Python warnings: the scene's plausibility
    warnings and the step guard's (:class:`SceneWarning`) and an inaccurate run
    (:class:`AccuracyWarning`); the ``warnings`` module filters them as usual.

    Raises :class:`StepRefused` when the step guard refuses the step (nothing simulated),
    :class:`UnstableError` when the run becomes unstable (``.result`` holds the rows up to
    then), :class:`Interrupted` (a KeyboardInterrupt) on Ctrl-C (``.result`` holds what was
    simulated), :class:`SceneError` for bad options.
    """
    scene = as_scene(scene)
    ran = scene.copy()  # the scene as run: later set() calls on `scene` do not change it
    handle = _stiction._run(scene._handle, integrator=_arguments.text("integrator", integrator),
                            dt=_arguments.number("dt", dt),
                            duration=_arguments.number("duration", duration),
                            tolerance=_arguments.number("tolerance", tolerance),
                            accuracy=_arguments.flag("accuracy", accuracy, optional=True),
                            force_step=_arguments.flag("force_step", force_step),
                            progress=_arguments.flag("progress", progress))
    result = Result(handle, ran)
    _warn(result)
    if result.status == "interrupted":
        raise Interrupted(f"{scene.name}: interrupted at t = {result.t[-1] if len(result) else 0:g} s; "
                          "the rows so far are in .result", result=result)
    instability = handle.instability
    if instability is not None:
        suggested = result.summary.get("instability", {}).get("suggested_dt")
        text = (f"{scene.name}: numerical instability at t = {instability['time']:.6g} s in "
                f"'{instability['component']}' ({instability['reason']}) with {result.summary['integrator']}, "
                f"dt = {result.summary['dt']:g} s")
        if suggested:
            text += f"; try a smaller step, e.g. dt={suggested:g}"
        raise UnstableError(text, time=instability["time"], component=instability["component"],
                            reason=instability["reason"], suggested_dt=suggested, result=result)
    return result


def _warn(result):
    summary = result.summary
    for w in summary.get("warnings", []):
        warnings.warn(f"{w['file']}:{w['line']}:{w['column']}: {w['text']}", SceneWarning, stacklevel=3)
    accuracy = summary.get("accuracy") or {}
    if accuracy.get("verdict") == "inaccurate":
        # An adaptive integrator's summary has its tolerance (check --json lists the traits).
        setting = (f"tolerance {summary['tolerance']:g}" if summary.get("tolerance")
                   else f"dt = {summary['dt']:g} s")
        reasons = accuracy.get("reasons", [])
        text = (f"{summary['scene']}: the run is inaccurate with {summary['integrator']}, {setting}: "
                + "; ".join(reasons[:3]) + (f"; ... ({len(reasons) - 3} more in result.accuracy['reasons'])"
                                            if len(reasons) > 3 else "")
                + " (stiction.study measures the largest accurate step; docs/accuracy.md)")
        warnings.warn(text, AccuracyWarning, stacklevel=3)
