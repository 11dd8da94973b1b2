"""stiction: mechanical systems with Coulomb friction, simulated with Kikuuwe & Yamamoto's
modular RK4 architecture; the command line's services from Python (docs/python.md).

    import stiction
    scene = stiction.Scene("sphere_roll").set("impedances.ground.mu", 0.2)
    result = stiction.run(scene)
    result.t, result["sphere.v.x"]          # NumPy arrays, SI units (result.units)
    result.summary["events"]["ground"]      # the same dict as summary.json

Scenes: Scene, scenes(). Runs: run, Result. Tools: check, study, sweep, compare. Pictures:
frame, frames, Result.write_video, Result.write_plots. Elements in Python: Scene.set_source,
Impedance, Scene.set_element. Errors: Error, SceneError, UnstableError, StepRefused,
Interrupted, OutputError.
"""

import os as _os
from pathlib import Path as _Path

from . import _stiction
from ._elements import Impedance, State
from ._result import Result
from ._pictures import frame, frames
from ._run import run
from ._scene import Scene, scenes
from ._tools import Comparison, Study, Sweep, check, compare, study, sweep
from .errors import (AccuracyWarning, Error, Interrupted, OutputError, SceneError, SceneWarning,
                     StepRefused, UnstableError)


def _locate_install():
    # Installed as <prefix>/lib/python3.X/dist-packages/stiction/ (python/CMakeLists.txt):
    # the bundled scenes, the font and the render plugin are under the same prefix, wherever
    # it was moved. From the build tree (build/python/stiction/) no ancestor is such a prefix
    # and the compiled-in places apply (sys/data_dirs.hpp).
    package = _Path(__file__).resolve().parent
    for prefix in list(package.parents)[:4]:
        if (package.relative_to(prefix).parts[0] == "lib"
                and (prefix / "share" / "stiction" / "scenes").is_dir()):
            _stiction._set_install_root(str(prefix))
            # The render plugin (dlopen'ed with its own copy of the libraries) does not see the
            # root set above: it finds the font through the environment.
            _os.environ.setdefault("STICTION_DATA_DIR", str(prefix / "share" / "stiction"))
            return


_locate_install()

__all__ = ["Scene", "scenes", "run", "Result", "check", "study", "Study", "sweep", "Sweep",
           "compare", "Comparison", "frame", "frames", "Impedance", "State", "Error", "SceneError",
           "UnstableError", "StepRefused", "Interrupted", "OutputError", "SceneWarning",
           "AccuracyWarning"]
