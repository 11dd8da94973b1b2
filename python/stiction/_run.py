"""stiction.run: `stiction run` from Python."""

from . import _stiction
from ._result import Result
from ._scene import as_scene
from .errors import Interrupted, UnstableError


def run(scene, integrator=None, dt=None, duration=None, tolerance=None, accuracy=None,
        force_step=False, progress=False):
    """Simulates a scene and returns a :class:`Result`.

    scene       a :class:`Scene`, or a bundled name or .toml path
    integrator  "rk4", "euler", "symplectic_euler", "rk4_adaptive", ... (default: the scene's)
    dt          step size, s (default: the scene's)
    duration    simulated time, s (default: the scene's)
    tolerance   local error bound per state entry; selects rk4_adaptive
    accuracy    True/False: estimate the run's error with a companion run at dt/2
                (docs/accuracy.md); None: when it costs little, as on the command line
    force_step  simulate even when the step guard predicts the step unstable
    progress    print progress to stderr

    Raises :class:`StepRefused` when the step guard refuses the step (nothing simulated),
    :class:`UnstableError` when the run becomes unstable (``.result`` holds the rows up to
    then), :class:`Interrupted` (a KeyboardInterrupt) on Ctrl-C (``.result`` holds what was
    simulated), :class:`SceneError` for bad options.
    """
    scene = as_scene(scene)
    ran = scene.copy()  # the scene as run: later set() calls on `scene` do not change it
    handle = _stiction._run(scene._handle, integrator=integrator, dt=dt, duration=duration,
                            tolerance=tolerance, accuracy=accuracy, force_step=force_step,
                            progress=progress)
    result = Result(handle, ran)
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
