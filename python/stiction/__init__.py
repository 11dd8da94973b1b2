"""stiction: mechanical systems with Coulomb friction, simulated with Kikuuwe & Yamamoto's
modular RK4 architecture; the command line's services from Python (docs/python.md).

    import stiction
    scene = stiction.Scene("sphere_roll").set("ground.mu", 0.2)
    result = stiction.run(scene)
    result.t, result["sphere.v.x"]          # NumPy arrays, SI units (result.units)
    result.summary["events"]["ground"]      # the same dict as summary.json

Scenes: Scene, scenes(). Runs: run, Result. Errors: Error, SceneError, UnstableError,
StepRefused, Interrupted, OutputError.
"""

import os as _os
from pathlib import Path as _Path

from . import _stiction
from ._result import Result
from ._pictures import frame, frames
from ._run import run
from ._scene import Scene, scenes
from .errors import Error, Interrupted, OutputError, SceneError, StepRefused, UnstableError


def _locate_install():
    # Installed as <prefix>/lib/python3.X/dist-packages/stiction/: the render plugin and the
    # bundled scenes are under the same prefix, wherever it was moved.
    prefix = _Path(__file__).resolve().parents[3]
    if (prefix / "share" / "stiction" / "scenes").is_dir():
        _stiction._set_install_root(str(prefix))
        # The render plugin is a library of its own: it finds fonts and scenes through this.
        _os.environ.setdefault("STICTION_DATA_DIR", str(prefix / "share" / "stiction"))


_locate_install()

__all__ = ["Scene", "scenes", "run", "Result", "frame", "frames", "Error", "SceneError", "UnstableError",
           "StepRefused", "Interrupted", "OutputError"]
