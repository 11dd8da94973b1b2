"""stiction.Scene: bundled names, files, TOML strings and dicts; set() as --set; errors
located as on the command line."""

import random

import pytest
import stiction

SLIDING_BLOCK = """
name = "block"
[simulation]
dt = 1e-4
duration = 0.5
[bodies.block]
type = "point_mass"
mass = {mass}
position = [0.0, 0.0, 0.0]
velocity = [{v0}, 0.0, 0.0]
[impedances.floor]
type = "kikuuwe_contact"
body = "block"
normal = [0.0, 0.0, 1.0]
stiffness = 1e6
damping = 2000.0
mu = {mu}
"""


def test_bundled_scenes_listed_with_descriptions():
    scenes = stiction.scenes()
    assert "sphere_roll" in scenes and scenes["sphere_roll"]
    scene = stiction.Scene("sphere_roll")
    assert scene.name == "sphere_roll" and scene.integrator == "rk4"
    assert scene.columns[0] == "t" and scene.units["sphere.v.x"] == "m/s"
    assert "sphere_roll" in repr(scene)


def test_file_and_text_give_the_same_scene(tmp_path):
    text = (stiction.Scene("sphere_roll").path).read_text()
    path = tmp_path / "mine.toml"
    path.write_text(text)
    from_file = stiction.Scene(path)
    from_text = stiction.Scene.from_toml(text)
    assert from_file.columns == from_text.columns == stiction.Scene("sphere_roll").columns
    assert from_text.toml == from_file.toml


def test_set_as_on_the_command_line(cli, tmp_path):
    scene = stiction.Scene("sphere_roll").set("impedances.ground.mu", 0.3).set({"simulation.duration": 0.4})
    assert scene.duration == 0.4
    assert scene.overrides == ["impedances.ground.mu=0.3", "simulation.duration=0.4"]
    cli("run", "sphere_roll", "--set", "impedances.ground.mu=0.3", "--set", "simulation.duration=0.4",
        "--no-video", "--no-plots", "--quiet", "--accuracy", "off", "--out", tmp_path / "cli")
    stiction.run(scene, accuracy=False).save(tmp_path / "py")
    assert (tmp_path / "py" / "trajectory.csv").read_bytes() == (tmp_path / "cli" / "trajectory.csv").read_bytes()


def test_a_bad_value_is_a_located_scene_error_and_changes_nothing():
    scene = stiction.Scene("sphere_roll")
    with pytest.raises(stiction.SceneError) as error:
        scene.set("impedances.ground.mu", -1.0)
    e = error.value
    assert isinstance(e, ValueError)
    assert e.key and "mu" in e.key
    assert e.line is not None and e.column is not None
    assert scene.overrides == []  # unchanged


def test_errors_in_a_text_name_its_line_and_key():
    text = SLIDING_BLOCK.format(mass=1.0, v0=1.0, mu=0.3).replace("mu = 0.3", "mu = \"x\"")
    with pytest.raises(stiction.SceneError) as error:
        stiction.Scene.from_toml(text, name="block.toml")
    e = error.value
    assert e.file == "block.toml"
    assert e.line == text.splitlines().index('mu = "x"') + 1
    assert e.key is not None and "mu" in e.key
    with pytest.raises(stiction.SceneError, match="no_such"):
        stiction.Scene("no_such_scene_anywhere")


def test_dict_scene_with_random_parameters_slides_to_the_closed_form_stop():
    rng = random.Random(20)
    for _ in range(4):
        mass, v0, mu = rng.uniform(0.2, 5.0), rng.uniform(0.1, 1.0), rng.uniform(0.1, 0.8)
        stiffness = 1e6
        document = {  # pressed in by its static deflection, critically damped: no bounce
            "name": "block",
            "simulation": {"dt": 1e-4, "duration": 1.2 * v0 / (mu * 9.8) + 0.05},
            "bodies": {"block": {"type": "point_mass", "mass": mass,
                                 "position": [0.0, 0.0, -mass * 9.8 / stiffness],
                                 "velocity": [v0, 0.0, 0.0]}},
            "impedances": {"floor": {"type": "kikuuwe_contact", "body": "block", "normal": [0.0, 0.0, 1.0],
                                     "stiffness": stiffness, "damping": 2 * (stiffness * mass) ** 0.5,
                                     "mu": mu}},
        }
        scene = stiction.Scene.from_dict(document)
        result = stiction.run(scene, accuracy=False)
        stop = result.summary["events"]["floor"]["stick_time"]
        assert stop == pytest.approx(v0 / (mu * 9.8), abs=2e-3)
