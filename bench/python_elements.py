"""What a Python source law and a Python impedance cost per call (docs/python.md quotes it).

    PYTHONPATH=build/python /usr/bin/python3 bench/python_elements.py

Each Python run is timed against the same scene with the law as an expression, or with a
bundled element doing the same work; the difference over the number of stage evaluations
(RK4: 4 per step) is the cost of one call from C++ into Python and back. The simulation's
own wall time is used (Result.wall_seconds: no step guard, no scene loading); best of 5.
Not a test: timings depend on the machine."""

import math
import sys

import stiction

REPEATS = 5


def best_wall(scene):
    best = math.inf
    for _ in range(REPEATS):
        result = stiction.run(scene, accuracy=False, force_step=True)
        best = min(best, result.wall_seconds)
    return best, result.steps * 4


def per_call(label, python_scene, reference_scene):
    python_wall, stages = best_wall(python_scene)
    reference_wall, _ = best_wall(reference_scene)
    cost = (python_wall - reference_wall) / stages * 1e6
    print(f"{label:58s} {stages:7d} stages  {python_wall:7.3f} s vs {reference_wall:6.3f} s"
          f"  -> {cost:5.2f} us per call")


def main():
    # pd_arm: the controller as pd_arm's expression, or as a Python function of the state.
    def pd(t, s):
        theta = s["arm.theta.0"]
        return 20 * (1 - theta) - 0.5 * s["arm.omega.0"] + 9.8 * 0.25 * math.cos(theta)

    per_call("source law (pd_arm, default signals, 2 lookups)",
             stiction.Scene("pd_arm").set_source("controller", pd), stiction.Scene("pd_arm"))
    per_call("source law (pd_arm, returns a constant, no lookup)",
             stiction.Scene("pd_arm").set_source("controller", lambda t, s: 1.0),
             stiction.Scene("pd_arm", set={"impedances.controller.torque": 1.0}))

    # A joint damper: the bundled spring_damper (K = 0) against a Python impedance.
    class Damper(stiction.Impedance):
        def __init__(self, b):
            self.b = b

        def evaluate(self, t, x_hat, y, tau):
            return self.b * x_hat[1], None

    arm = """
[simulation]
integrator = "rk4"
dt = 1e-4
duration = 2.0
[bodies.arm]
type = "planar_arm"
links = [{ length = 0.5, mass = 1.0 }]
rates = [3.0]
[impedances.joint]
body = "arm"
joint = 0
"""
    per_call("impedance (joint damper, u = b v)",
             stiction.Scene.from_toml(arm + 'type = "external"\n', elements={"joint": Damper(0.05)}),
             stiction.Scene.from_toml(arm + 'type = "spring_damper"\nstiffness = 0\ndamping = 0.05\n'))
    return 0


if __name__ == "__main__":
    sys.exit(main())
