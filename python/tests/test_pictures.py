"""Pictures from Python (stiction.frame, result.write_video, result.write_plots) against what
`stiction run` writes for the same run: frames pixel for pixel, figures byte for byte, the
video's frame count and size (and bytes)."""

import math
import os
import random
import re
import signal
import struct
import subprocess
import threading
import time
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import stiction

SMALL = [320, 180]


def cli(*args, cwd):
    binary = os.environ.get("STICTION_BINARY")
    if not binary:
        pytest.fail("STICTION_BINARY is not set (ctest sets it to the stiction program)")
    done = subprocess.run([binary, *args, "--quiet"], cwd=cwd, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return Path(cwd)


def png(path):
    return np.asarray(Image.open(path).convert("RGBA"))


def cli_frames(out):
    return sorted((out / "frames").glob("*.png"))


# --- MP4: the frame count and the picture size from the index, as a player reads them.
def _boxes(data, start, end):
    while start + 8 <= end:
        size, kind = struct.unpack(">I4s", data[start:start + 8])
        header = 8
        if size == 1:
            size = struct.unpack(">Q", data[start + 8:start + 16])[0]
            header = 16
        elif size == 0:
            size = end - start
        yield kind.decode("latin-1"), start + header, start + size
        start += size


def _find(data, path, start=0, end=None):
    end = len(data) if end is None else end
    for kind, body, stop in _boxes(data, start, end):
        if kind == path[0]:
            return (body, stop) if len(path) == 1 else _find(data, path[1:], body, stop)
    return None


def mp4_frames_and_size(path):
    """(frames, width, height) of the video track: stsz's sample count, tkhd's size."""
    data = Path(path).read_bytes()
    assert data[4:8] == b"ftyp", f"{path} is not an MP4"
    stsz = _find(data, ["moov", "trak", "mdia", "minf", "stbl", "stsz"])
    tkhd = _find(data, ["moov", "trak", "tkhd"])
    assert stsz and tkhd, f"{path} has no finalized index (moov)"
    frames = struct.unpack(">I", data[stsz[0] + 8:stsz[0] + 12])[0]
    width, height = struct.unpack(">II", data[tkhd[1] - 8:tkhd[1]])
    return frames, width >> 16, height >> 16


# --- one bundled run, drawn by both
@pytest.fixture(scope="module")
def sphere(tmp_path_factory):
    work = tmp_path_factory.mktemp("sphere")
    out = cli("run", "sphere_roll", "--duration", "0.3", "--set", "render.size=[320,180]",
              "--frames", "--out", "cli", cwd=work) / "cli"
    result = stiction.run(stiction.Scene("sphere_roll").set("render.size", SMALL), duration=0.3)
    return result, out, work


def test_every_frame_equals_the_png_the_command_line_writes(sphere):
    result, out, _ = sphere
    times = result.frame_times()
    pngs = cli_frames(out)
    assert len(times) == len(pngs) == 19  # 0.3 s at 60 fps, both ends
    assert np.allclose(np.diff(times), 1 / 60)
    frames = result.frames(times)
    assert frames.shape == (19, 180, 320, 4) and frames.dtype == np.uint8
    for i, path in enumerate(pngs):
        assert np.array_equal(frames[i], png(path)), f"frame {i} differs from {path.name}"


def test_one_frame_is_the_same_as_from_frames_and_follows_the_motion(sphere):
    result, out, work = sphere
    t = result.frame_times()[7]
    picture = stiction.frame(result, t)
    assert picture.shape == (180, 320, 4)
    assert np.array_equal(picture, png(cli_frames(out)[7]))
    assert np.array_equal(result.frame(t), picture)
    # The sphere moves: the first and last frames differ.
    first, last = result.frames([0.0, result.t[-1]])
    assert not np.array_equal(first, last)
    Image.fromarray(picture).save(work / "frame_7.png")  # for a look by hand


def test_size_overrides_the_scenes(sphere):
    result, _, _ = sphere
    assert stiction.frame(result, 0.1, size=(160, 90)).shape == (90, 160, 4)
    with pytest.raises(ValueError, match="outside the run"):
        stiction.frame(result, 1.0)
    with pytest.raises(ValueError, match="size"):
        stiction.frame(result, 0.1, size=(0, 90))


def test_write_plots_gives_the_command_lines_files(sphere, tmp_path):
    result, out, _ = sphere
    written = result.write_plots(tmp_path / "plots")
    assert [p.name for p in written] == sorted(p.name for p in (out / "plots").iterdir())
    for path in written:
        assert path.read_bytes() == (out / "plots" / path.name).read_bytes(), path.name


def test_write_plots_svg_as_plot_format_svg(tmp_path):
    cli("run", "two_link", "--no-video", "--plot-format", "svg", "--duration", "1", "--out", "cli",
        cwd=tmp_path)
    result = stiction.run("two_link", duration=1)
    written = result.write_plots(tmp_path / "py", format="svg")
    assert {p.name for p in written} == {p.name for p in (tmp_path / "cli" / "plots").iterdir()}
    # cairo numbers its surfaces per process ("surface6"): a process that drew other figures
    # before gives other ids. Everything else is the same byte for byte.
    ids = re.compile(rb'surface\d+')
    for path in written:
        ours = ids.sub(b"surface", path.read_bytes())
        theirs = ids.sub(b"surface", (tmp_path / "cli" / "plots" / path.name).read_bytes())
        assert ours == theirs, path.name
    with pytest.raises(ValueError, match="png, svg or pdf"):
        result.write_plots(tmp_path / "bad", format="gif")


def test_write_video_as_the_command_line(sphere, tmp_path):
    result, out, _ = sphere
    video = result.write_video(tmp_path / "dir", frames=True)
    assert video == tmp_path / "dir" / "video.mp4"
    ours = mp4_frames_and_size(video)
    assert ours == mp4_frames_and_size(out / "video.mp4") == (19, 320, 180)
    # libx264 is deterministic for the same frames and settings: the same file.
    assert video.read_bytes() == (out / "video.mp4").read_bytes()
    assert [p.name for p in cli_frames(tmp_path / "dir")] == [p.name for p in cli_frames(out)]
    # A file name: the video goes there, and nothing else is left beside it.
    named = result.write_video(tmp_path / "named" / "clip.mp4")
    assert named.read_bytes() == video.read_bytes()
    assert sorted(p.name for p in named.parent.iterdir()) == ["clip.mp4"]
    with pytest.raises(ValueError, match="directory"):
        result.write_video(tmp_path / "x.mp4", frames=True)


def random_slope_scene(rng):
    """A point mass on a plane at a random angle and friction, with a random push."""
    angle = rng.uniform(5, 35)
    mu = rng.uniform(0.1, 0.7)
    push = rng.uniform(0.0, 2.0)
    s, c = math.sin(math.radians(angle)), math.cos(math.radians(angle))
    k, m = 1e6, rng.uniform(0.5, 3.0)
    sink = m * 9.8 * c / k  # the static deflection: no bounce at the start
    trail = rng.choice(["true", "false"])
    return f"""
name = "random_slope"
gravity = [0.0, 0.0, -9.8]
[simulation]
integrator = "rk4"
dt = 1e-4
duration = {rng.uniform(0.2, 0.45):.3f}
output_rate = 1000.0
[bodies.block]
type = "point_mass"
mass = {m}
position = [{sink * s}, 0.0, {-sink * c}]
velocity = [{-push * c}, 0.0, {-push * s}]
[impedances.slope]
type = "kikuuwe_contact"
body = "block"
normal = [{-s}, 0.0, {c}]
stiffness = {k}
damping = {2 * math.sqrt(k * m)}
mu = {mu}
[render]
size = [{rng.choice([160, 240, 320])}, {rng.choice([90, 120, 180])}]
fps = 30
[camera]
follow = "block"
[overlay]
signal = "slope.slip"
trail = {trail}
[[plots]]
name = "random_slope"
title = "Random slope: angle {angle:.1f} deg, mu = {mu:.2f}"
  [[plots.panels]]
  signals = ["block.v.x", "block.v.z"]
  label = "Block velocity"
  unit = "m/s"
"""


@pytest.mark.parametrize("seed", [random.randrange(1 << 30) for _ in range(2)])
def test_a_generated_scene_draws_as_the_command_line(seed, tmp_path):
    path = tmp_path / "random_slope.toml"
    path.write_text(random_slope_scene(random.Random(seed)))
    out = cli("run", str(path), "--frames", "--no-video", "--accuracy", "off", "--out", "cli",
              cwd=tmp_path) / "cli"
    result = stiction.run(stiction.Scene(path), accuracy=False)
    times = result.frame_times()
    pngs = cli_frames(out)
    assert len(times) == len(pngs), f"seed {seed}"
    frames = result.frames(times)
    for i in range(len(pngs)):
        assert np.array_equal(frames[i], png(pngs[i])), f"seed {seed}: frame {i}"
    for p in result.write_plots(tmp_path / "plots"):
        assert p.read_bytes() == (out / "plots" / p.name).read_bytes(), f"seed {seed}: {p.name}"


def test_slow_motion_around_events_draws_the_videos_frames(tmp_path):
    # The video slows down around the box's stick/slip events: frame times bunch up there, and
    # those frames are drawn at a lower playback speed (the overlay says so).
    settings = ["--set", "render.size=[160,90]", "--set", "render.slow_motion_around_events=0.05"]
    out = cli("run", "box_slope", "--duration", "1.5", *settings, "--frames", "--no-video",
              "--no-plots", "--accuracy", "off", "--out", "cli", cwd=tmp_path) / "cli"
    scene = stiction.Scene("box_slope").set({"render.size": [160, 90],
                                            "render.slow_motion_around_events": 0.05})
    result = stiction.run(scene, duration=1.5, accuracy=False)
    times = result.frame_times()
    steps = np.diff(times)
    assert steps.min() < 0.5 / 60 < steps.max(), "no slowed stretch to test"
    pngs = cli_frames(out)
    assert len(times) == len(pngs)
    frames = result.frames(times)
    for i in range(len(pngs)):
        assert np.array_equal(frames[i], png(pngs[i])), f"frame {i} at t = {times[i]:g} s"


@pytest.mark.skipif(threading.current_thread() is not threading.main_thread(),
                    reason="SIGINT reaches the main thread only")
def test_ctrl_c_during_the_video_keeps_the_partial_file(tmp_path):
    scene = stiction.Scene("sphere_roll").set({"render.size": [160, 90], "render.slow_motion": 8})
    result = stiction.run(scene, duration=0.3)
    total = len(result.frame_times())  # 145 frames: far more than are drawn before the signal
    out = tmp_path / "video"

    def interrupt_after_two_frames():
        deadline = time.monotonic() + 60
        while not (out / "frames" / "000002.png").exists() and time.monotonic() < deadline:
            time.sleep(0.005)
        os.kill(os.getpid(), signal.SIGINT)

    killer = threading.Thread(target=interrupt_after_two_frames)
    killer.start()
    try:
        with pytest.raises(stiction.Interrupted) as caught:
            result.write_video(out, frames=True)
    finally:
        killer.join()
    error = caught.value
    assert isinstance(error, KeyboardInterrupt)
    assert error.path == out / "video.partial.mp4"
    assert not (out / "video.mp4").exists()
    frames, width, height = mp4_frames_and_size(error.path)
    assert 3 <= frames == error.frames < total
    assert (width, height) == (160, 90)
    # Python's own Ctrl-C handling is back afterwards.
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
