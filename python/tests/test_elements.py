"""Controllers and custom elements written in Python (stiction.Scene.set_source,
stiction.Impedance): against the command line's pd_arm, the C++ example's closed forms,
and the same scenes written with expressions and bundled elements."""

import csv
import math
import os
import random
import subprocess
from pathlib import Path

import numpy as np
import pytest

import stiction

SOURCE_DIR = Path(os.environ.get("STICTION_SOURCE_DIR", Path(__file__).resolve().parents[2]))


def stiction_binary():
    binary = os.environ.get("STICTION_BINARY")
    if binary:
        return binary
    for candidate in (Path("build/stiction"), Path("build/src/app/stiction")):
        if candidate.is_file():
            return str(candidate.resolve())
    pytest.skip("no stiction binary (set STICTION_BINARY)")


def pd_law(t, s):
    # pd_arm's expression, written in Python.
    theta = s["arm.theta.0"]
    return 20 * (1 - theta) - 0.5 * s["arm.omega.0"] + 1.0 * 9.8 * 0.25 * math.cos(theta)


def test_pd_controller_in_python_reproduces_pd_arm_overshoot(tmp_path):
    scene = stiction.Scene("pd_arm").set_source("controller", pd_law)
    assert scene.externals == {"sources": ["controller"], "elements": []}
    result = stiction.run(scene, accuracy=False)
    overshoot = result["arm.theta.0"].max() - 1.0

    out = tmp_path / "cli"
    subprocess.run([stiction_binary(), "run", "pd_arm", "--out", str(out), "--no-video", "--no-plots"],
                   check=True, capture_output=True, env={**os.environ, "STICTION_CACHE_DIR": "off"})
    with open(out / "trajectory.csv") as f:
        rows = list(csv.DictReader(f))
    cli_overshoot = max(float(r["arm.theta.0"]) for r in rows) - 1.0

    # The same law, in double precision both ways: the peaks agree far below the CSV's digits.
    assert overshoot == pytest.approx(cli_overshoot, abs=1e-9)
    # The figure (the continuous peak, 6 digits): rows are 1 ms apart, so the largest
    # row can sit below the peak by up to theta'' (0.5 ms)^2 / 2 = 240 * 0.54 * 1.25e-7 = 1.6e-5.
    assert overshoot == pytest.approx(0.537957, abs=2e-5)
    assert result["controller.tau"][0] == pytest.approx(20 + 9.8 * 0.25)


class ViscousCoulomb(stiction.Impedance):
    """examples/viscous_coulomb_joint in Python: Kikuuwe's Coulomb friction beside a damper b,
    f_c = sat_F((B + tau K) v + K e), e_dot = (f_c - K e) / (B + tau K), u = f_c + b v."""

    input_size, output_size, state_size = 2, 1, 1
    state_labels = ["e"]

    def __init__(self, stiffness=5000.0, damping=1.0, coulomb=0.5, viscous=0.2):
        self.K, self.B, self.F, self.b = stiffness, damping, coulomb, viscous
        self.stiffness = stiffness  # the step guard's advice (StiffnessHint)

    def evaluate(self, t, x_hat, y, tau):
        v, e = x_hat[1], y[0]
        bk = self.B + tau * self.K
        coulomb = min(max(bk * v + self.K * e, -self.F), self.F)
        return (coulomb + self.b * v,), ((coulomb - self.K * e) / bk,)

    def signals(self):
        return [("tau", "N·m", "torque on the joint"), ("e", "rad")]

    def write_signals(self, x_hat, y, u):
        return (-u[0], y[0])

    def slip_velocity(self, x_hat):
        return x_hat[1]  # stick/slip events on the joint's rate


ARM_WITH_JOINT = """
[simulation]
integrator = "rk4"
dt = 1e-4
duration = {duration}
output_rate = 1000.0

[bodies.arm]
type = "planar_arm"
links = [{{ length = 0.2, width = 0.02, mass = 0.2 }}]

[impedances.motor]
type = "torque_source"
body = "arm"
joint = 0
torque = "t < {released} ? {T0} : 0"

[impedances.joint]
type = "external"
body = "arm"
joint = 0
"""


def test_viscous_coulomb_joint_in_python_reproduces_the_closed_forms():
    T0, released, F, b = 1.5, 2.0, 0.5, 0.02
    scene = stiction.Scene.from_toml(ARM_WITH_JOINT.format(duration=4.0, released=released, T0=T0),
                                     name="viscous_coulomb",
                                     elements={"joint": ViscousCoulomb(viscous=b, coulomb=F)})
    result = stiction.run(scene, accuracy=False)
    t, omega, theta = result.t, result["arm.omega.0"], result["arm.theta.0"]

    # J about the joint: the box link's own inertia m (l^2 + w^2) / 12 plus m (l/2)^2.
    J = 0.2 * (0.2**2 + 0.02**2) / 12 + 0.2 * 0.1**2
    tc = J / b
    t_before = released - 1e-3  # RK4's last stage at 2 s already sees the release
    before = int(round(t_before * 1000))
    w_before = (T0 - F) / b * (1 - math.exp(-t_before / tc))
    w_release = (T0 - F) / b * (1 - math.exp(-released / tc))
    assert omega[before] == pytest.approx(w_before, rel=1e-6)

    def time_at(w):
        return released + tc * math.log((F / b + w_release) / (F / b + w))

    target = 0.01 * w_release
    r = before + np.argmax(omega[before:] < target)
    t_slowed = t[r - 1] + (omega[r - 1] - target) / (omega[r - 1] - omega[r]) * (t[r] - t[r - 1])
    assert t_slowed == pytest.approx(time_at(target), abs=1e-3)
    assert abs(omega[-1]) < 1e-9
    assert abs(theta[-1] - theta[-501]) < 1e-9  # no drift while stuck
    assert result["joint.tau"][before] == pytest.approx(-(F + b * omega[before]), rel=1e-6)
    # slip_velocity made it a sliding pair: the stop is a stick event.
    assert any(e["time"] > released for e in result.events.get("joint", []))


def random_box(rng):
    m, k, c = rng.uniform(0.5, 3), rng.uniform(10, 200), rng.uniform(0, 2)
    x0, v0 = rng.uniform(-0.3, 0.3), rng.uniform(-1, 1)
    text = f"""
gravity = [0.0, 0.0, 0.0]
[simulation]
integrator = "rk4"
dt = 1e-3
duration = 1.0
# A spring written as a force law (or as a Python element) holds energy the monitor cannot
# see: the box's kinetic energy rises from its lowest value as the spring gives it back.
energy_tolerance = 1.0
[bodies.box]
type = "point_mass"
mass = {m!r}
position = [{x0!r}, 0.0, 0.0]
velocity = [{v0!r}, 0.0, 0.0]
"""
    return k, c, text


class PointSpring(stiction.Impedance):
    """A spring-damper to the world origin at a point: u = K p + C v (3-D)."""

    input_size, output_size = 6, 3

    def __init__(self, k, c):
        self.k, self.c = k, c

    def evaluate(self, t, x_hat, y, tau):
        return self.k * x_hat[:3] + self.c * x_hat[3:], None


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_random_scenes_python_law_and_element_match_expression_and_bundled(seed):
    k, c, text = random_box(random.Random(seed))
    expression = text + f"""
[impedances.spring]
type = "force_source"
body = "box"
force = ["-{k!r}*box.p.x - {c!r}*box.v.x", 0, 0]
"""
    placeholder = text + '[impedances.spring]\ntype = "force_source"\nbody = "box"\n'
    bundled = text + f'[impedances.spring]\ntype = "spring_damper"\nbody = "box"\nstiffness = {k!r}\ndamping = {c!r}\n'
    external = text + '[impedances.spring]\ntype = "external"\nbody = "box"\n'

    def law(t, s):
        return (-k * s["box.p.x"] - c * s["box.v.x"], 0.0, 0.0)

    reference = stiction.run(stiction.Scene.from_toml(expression), accuracy=False)["box.p.x"]
    by_law = stiction.run(stiction.Scene.from_toml(placeholder, sources={"spring": (law, ["box.p.x", "box.v.x"])}),
                          accuracy=False)["box.p.x"]
    np.testing.assert_allclose(by_law, reference, rtol=0, atol=1e-12)
    assert np.ptp(reference) > 1e-3  # it oscillates

    spring = stiction.run(stiction.Scene.from_toml(bundled), accuracy=False)["box.p.x"]
    element_scene = stiction.Scene.from_toml(external, elements={"spring": PointSpring(k, c)})
    by_element = stiction.run(element_scene, accuracy=False)
    np.testing.assert_allclose(by_element["box.p.x"], spring, rtol=0, atol=1e-12)
    assert "spring.u.x" in by_element.columns


def test_a_law_gets_every_body_signal_by_default_as_a_mapping():
    seen = {}

    def law(t, s):
        seen.update(dict(s))
        seen["repr"] = repr(s)
        return 0.0

    stiction.run(stiction.Scene("pd_arm").set_source("controller", law), duration=0.01, accuracy=False)
    assert "arm.theta.0" in seen and "arm.omega.0" in seen
    assert seen["repr"].startswith("<stiction.State arm.theta.0=")


def test_an_exception_in_a_law_stops_the_run_and_is_raised():
    calls = []

    def law(t, s):
        calls.append(t)
        if t > 0.05:
            raise ZeroDivisionError("the controller failed at t > 0.05")
        return 0.0

    scene = stiction.Scene("pd_arm").set_source("controller", law)
    with pytest.raises(ZeroDivisionError, match="controller failed"):
        stiction.run(scene, accuracy=False, force_step=True)
    assert max(calls) < 0.06  # stopped there, not carried on

    scene.set_source("controller", lambda t, s: "not a number")
    with pytest.raises(TypeError, match="source 'controller' returned 'not a number'"):
        stiction.run(scene, accuracy=False, force_step=True)


def test_an_exception_in_an_element_is_raised():
    class Broken(ViscousCoulomb):
        def evaluate(self, t, x_hat, y, tau):
            if t > 0.01:
                raise RuntimeError("broken joint")
            return super().evaluate(t, x_hat, y, tau)

    scene = stiction.Scene.from_toml(ARM_WITH_JOINT.format(duration=0.1, released=2.0, T0=1.0),
                                     elements={"joint": Broken})
    with pytest.raises(RuntimeError, match="broken joint"):
        stiction.run(scene, accuracy=False, force_step=True)


def test_mistakes_are_scene_errors_naming_the_component():
    scene = stiction.Scene("pd_arm")
    with pytest.raises(stiction.SceneError, match=r"impedances\.controller.*'arm\.nothing'.*not a signal"):
        scene.set_source("controller", pd_law, signals=["arm.nothing"])
    with pytest.raises(stiction.SceneError, match="no torque_source or force_source"):
        scene.set_source("motor", pd_law)
    assert scene.externals == {"sources": [], "elements": []}  # unchanged after a failure

    text = ARM_WITH_JOINT.format(duration=0.1, released=2.0, T0=1.0)
    with pytest.raises(stiction.SceneError, match="no element named 'joint' was supplied"):
        stiction.Scene.from_toml(text)
    with pytest.raises(stiction.SceneError, match="takes 6 inputs and gives 3 outputs"):
        stiction.Scene.from_toml(text, elements={"joint": PointSpring(1.0, 0.0)})


def test_hostile_returns_and_sizes_are_errors_naming_the_callback():
    # Found by fuzz/fuzz_python.py (issue 39 item 8): a NumPy array of strings returned by a
    # law or an element raised pybind11's "Internal error: pybind11::error_already_set called
    # while Python error indicator not set", an int beyond a double an OverflowError naming
    # nothing, and a size of 10**20 "Unable to cast Python instance to C++ type".
    scene = stiction.Scene("pd_arm").set_source("controller", lambda t, s: np.array(["a"]))
    with pytest.raises(TypeError, match=r"source 'controller' returned array\(\['a'\].*dtype <U1.*expected a number"):
        stiction.run(scene, accuracy=False, force_step=True, duration=0.01)
    scene.set_source("controller", lambda t, s: 10 ** 400)
    with pytest.raises(OverflowError, match=r"source 'controller' returned 1000.*beyond the range of a double"):
        stiction.run(scene, accuracy=False, force_step=True, duration=0.01)
    scene.set_source("controller", lambda t, s: 10 ** 5000)  # its repr() fails: the type is named
    with pytest.raises(OverflowError, match=r"source 'controller' returned a int, beyond"):
        stiction.run(scene, accuracy=False, force_step=True, duration=0.01)

    class Strings(ViscousCoulomb):
        def evaluate(self, t, x_hat, y, tau):
            return np.array(["x"]), (0.0,)

    text = ARM_WITH_JOINT.format(duration=0.01, released=2.0, T0=1.0)
    with pytest.raises(TypeError, match=r"array\(\['x'\].*expected a number"):
        stiction.run(stiction.Scene.from_toml(text, elements={"joint": Strings}), accuracy=False,
                     force_step=True)

    class Huge(ViscousCoulomb):
        output_size = 10 ** 20

    with pytest.raises(stiction.SceneError, match=r"output_size must be an int in 0\.\.1000000, got 1000"):
        stiction.Scene.from_toml(text, elements={"joint": Huge})


def test_every_build_gets_a_fresh_element():
    made = []

    class Counting(ViscousCoulomb):
        def __init__(self):
            super().__init__()
            made.append(self)

    scene = stiction.Scene.from_toml(ARM_WITH_JOINT.format(duration=0.05, released=2.0, T0=1.0),
                                     elements={"joint": Counting})
    before = len(made)
    stiction.run(scene, accuracy=False)
    assert len(made) > before
    assert len({id(m) for m in made}) == len(made)


def test_the_accuracy_companion_runs_the_python_law_too():
    calls = {"n": 0}

    def law(t, s):
        calls["n"] += 1
        return pd_law(t, s)

    scene = stiction.Scene("pd_arm").set_source("controller", law)
    # Twice: the first may also run the step analysis' pilot (not yet in the step-check
    # cache), which would make `alone` as large as a run with its companion.
    stiction.run(scene, duration=0.2, accuracy=False, force_step=True)
    calls["n"] = 0
    stiction.run(scene, duration=0.2, accuracy=False, force_step=True)
    alone = calls["n"]
    calls["n"] = 0
    result = stiction.run(scene, duration=0.2, accuracy=True, force_step=True)
    assert "verdict" in result.summary["accuracy"]
    assert calls["n"] > alone  # the companion (dt/2, its own scene load) called the law too


SPRING_SCENE = """
name = "py_spring"
gravity = [0.0, 0.0, 0.0]
[simulation]
dt = 1e-4
duration = 0.05
[bodies.m]
type = "point_mass"
mass = {mass}
position = [{x0}, 0.0, 0.0]
[impedances.spring]
type = "external"
body = "m"
"""


class StoringSpring(stiction.Impedance):
    """u = k x at a point: a spring to the origin, with the energy it holds."""

    input_size, output_size, state_size = 6, 3, 0

    def __init__(self, k):
        self.k = k

    def evaluate(self, t, x_hat, y, tau):
        return self.k * x_hat[:3], None

    def stored_energy(self, x_hat, y):
        return 0.5 * self.k * float(x_hat[:3] @ x_hat[:3])


class HiddenSpring(StoringSpring):
    stored_energy = None


def test_a_python_spring_that_says_its_energy_oscillates_as_the_closed_form():
    rng = random.Random(7)
    for _ in range(3):
        k, mass, x0 = rng.uniform(1e4, 1e6), rng.uniform(0.2, 3.0), rng.uniform(0.001, 0.02)
        scene = stiction.Scene.from_toml(SPRING_SCENE.format(mass=mass, x0=x0), elements={"spring": StoringSpring(k)})
        result = stiction.run(scene, accuracy=False)
        omega = math.sqrt(k / mass)
        # RK4's phase error at omega dt <= 0.23 over the run: well under 1e-3 of the amplitude.
        assert np.allclose(result["m.p.x"], x0 * np.cos(omega * result.t), atol=1e-3 * x0)


def test_a_python_spring_that_hides_its_energy_is_stopped_by_the_energy_monitor():
    scene = stiction.Scene.from_toml(SPRING_SCENE.format(mass=1.0, x0=0.01),
                                     elements={"spring": HiddenSpring(1e6)})
    with pytest.raises(stiction.UnstableError, match="energy grew"):
        stiction.run(scene, accuracy=False, force_step=True)


GAIN = 20.0


def gain_law(t, s):
    return GAIN * (1 - s["arm.theta.0"]) - 0.5 * s["arm.omega.0"]


def test_step_check_of_a_python_law_is_cached_by_its_source(tmp_path, monkeypatch):
    # Issue 35: a scene with an element in code was never cached (2.8 s against 0.16 s for
    # the same law built in). Its fingerprint (source, closure, the globals it reads) keys
    # the cache: the same law again is a hit, a changed global is a miss.
    global GAIN
    monkeypatch.setenv("STICTION_CACHE_DIR", str(tmp_path / "cache"))
    cached = []
    for gain in (20.0, 20.0, 30.0):
        GAIN = gain
        scene = stiction.Scene("pd_arm").set_source("controller", gain_law)
        cached.append(stiction.run(scene, accuracy=False).summary["step_check"]["cached"])
    GAIN = 20.0
    assert cached == [False, True, False]
    # A law whose source cannot be read (a builtin) keeps the scene out of the cache.
    from stiction import _elements
    assert _elements._fingerprint(max) is None
    assert _elements._fingerprint(gain_law) == _elements._fingerprint(gain_law)


def test_a_non_finite_value_from_python_is_blamed_on_the_element_with_its_inputs():
    # Issue 39: a NaN force became a NaN state blamed on the step ("try dt = 3.9e-8"), and a
    # NaN stored_energy() switched the energy monitor off.
    class NanForce(StoringSpring):
        def evaluate(self, t, x_hat, y, tau):
            u, _ = super().evaluate(t, x_hat, y, tau)
            return (u * float("nan") if t > 0.005 else u), None

    class NanEnergy(StoringSpring):
        def stored_energy(self, x_hat, y):
            return float("nan")

    for element, what in ((NanForce(1e4), r"evaluate\(\)'s u is not finite .* at t = "),
                          (NanEnergy(1e4), r"stored_energy\(\) is not finite")):
        scene = stiction.Scene.from_toml(SPRING_SCENE.format(mass=1.0, x0=0.01),
                                         elements={"spring": element})
        with pytest.raises(ValueError, match=r"element 'spring': " + what + r".*x_hat = \["):
            stiction.run(scene, accuracy=False, force_step=True)

    scene = stiction.Scene("pd_arm")
    scene.set_source("controller", lambda t, s: float("nan") if t > 0.01 else 0.0)
    with pytest.raises(ValueError, match=r"source 'controller' returned a non-finite value .*arm\.theta\.0"):
        stiction.run(scene, accuracy=False, force_step=True)


def test_signal_names_and_state_labels_that_would_break_the_csv_are_refused():
    # Issue 39: a comma, quote or newline in a name broke trajectory.csv's header.
    for bad in ("a,b", 'say "x"', "two\nlines", "", ".x"):
        class Named(StoringSpring):
            signals = [(bad, "N")]

            def write_signals(self, x_hat, y, u):
                return [0.0]

        with pytest.raises(stiction.SceneError, match="signal name"):
            stiction.Scene.from_toml(SPRING_SCENE.format(mass=1.0, x0=0.01), elements={"spring": Named(1e4)})

    class Labelled(StoringSpring):
        state_size = 1
        state_labels = ["e,1"]

        def evaluate(self, t, x_hat, y, tau):
            return self.k * x_hat[:3], [0.0]

    with pytest.raises(stiction.SceneError, match=r"state_labels: 'e,1'"):
        stiction.Scene.from_toml(SPRING_SCENE.format(mass=1.0, x0=0.01), elements={"spring": Labelled(1e4)})
