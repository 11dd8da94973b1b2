"""Pictures of a run: frames as NumPy arrays, the video and the figures as ``stiction run``
writes them (video.mp4, frames/NNNNNN.png, plots/)."""

import os
import shutil
import tempfile
from pathlib import Path

import numpy as np

from . import _stiction
from ._result import Result
from .errors import Interrupted


def _pictures(result):
    # Made on first use and kept with the result: the rows the video and the plots are drawn
    # from (those `stiction run` would have kept) are computed once.
    if not isinstance(result, Result):
        raise TypeError(f"expected a stiction.Result, got {type(result).__name__}")
    pictures = result.__dict__.get("_pictures")
    if pictures is None:
        pictures = result.__dict__["_pictures"] = _stiction._Pictures(result._handle)
    return pictures


def _size(size):
    if size is None:
        return None, None
    try:
        width, height = size
    except (TypeError, ValueError):
        raise ValueError(f"size must be (width, height) in pixels, got {size!r}") from None
    return int(width), int(height)


def _check_times(result, times):
    if len(result) == 0:
        raise ValueError("the run has no rows to draw")
    start, end = float(result.t[0]), float(result.t[-1])
    slack = 1e-9 * max(1.0, abs(end))
    for t in times:
        if not start - slack <= t <= end + slack:
            raise ValueError(f"t = {t:g} s is outside the run ({start:g} to {end:g} s)")


def frame(result, t, size=None):
    """The frame the renderer draws at simulated time ``t`` (s) for ``result``, as an
    (H, W, 4) uint8 RGBA array, top row first.

    It is the picture of the video at that time: the same pixels as
    ``stiction run --frames`` writes to frames/NNNNNN.png for the frame at ``t``
    (``result.frame_times()[NNNNNN]``), overlay included. ``size=(width, height)`` in pixels
    overrides the scene's ``[render] size`` (default: the scene's, 1280 x 720 unless set).
    """
    return frames(result, [t], size=size)[0]


def frames(result, times, size=None):
    """Several frames at once (one GL context for all): an (N, H, W, 4) uint8 array for the
    N simulated times ``times`` (s). See :func:`frame`."""
    times = [float(t) for t in np.atleast_1d(np.asarray(times, dtype=float))]
    _check_times(result, times)
    width, height = _size(size)
    return _pictures(result).frames(times, width=width, height=height)


def frame_times(result):
    """The simulated time (s) of every frame of the run's video: frame i of video.mp4 and
    frames/NNNNNN.png (NNNNNN = i) shows ``frame_times()[i]``. Frames are 1 / (fps *
    slow_motion) apart, closer around stick/slip events when [render]
    slow_motion_around_events is set."""
    return _pictures(result).frame_times()


def write_video(result, path, frames=False, progress=False):
    """Writes the run's video as ``stiction run`` does (H.264 MP4, the scene's [render]
    settings) and returns its path.

    ``path`` is a file ending in .mp4, or a directory that gets video.mp4 (and with
    ``frames=True`` also frames/NNNNNN.png, as ``--frames``). ``progress`` draws a progress
    bar on stderr. Ctrl-C stops the render, keeps what was rendered as a playable
    ``*.partial.mp4`` and raises :class:`stiction.Interrupted` (its ``path`` is the partial
    video, its ``frames`` the number of frames in it).
    """
    path = Path(os.fspath(path))
    if path.suffix.lower() == ".mp4":
        if frames:
            raise ValueError("frames=True needs a directory, not a .mp4 file")
        path.parent.mkdir(parents=True, exist_ok=True)
        # Rendered into a scratch directory beside the file, then renamed over it: another
        # video.mp4 in the same directory is left alone.
        scratch = Path(tempfile.mkdtemp(prefix=f".{path.stem}.render-", dir=path.parent))
        try:
            outcome = _render(result, scratch, True, False, progress)
            if outcome["interrupted"]:
                partial = path.with_name(path.stem + ".partial.mp4")
                os.replace(outcome["video"], partial)
                _interrupted(result, partial, outcome)
            os.replace(outcome["video"], path)
        finally:
            shutil.rmtree(scratch, ignore_errors=True)
        return path
    path.mkdir(parents=True, exist_ok=True)
    # An earlier render's leftovers would be mistaken for this one's.
    (path / "video.partial.mp4").unlink(missing_ok=True)
    if frames and (path / "frames").is_dir():
        for old in (path / "frames").glob("[0-9][0-9][0-9][0-9][0-9][0-9].png"):
            old.unlink()
    outcome = _render(result, path, True, frames, progress)
    if outcome["interrupted"]:
        _interrupted(result, Path(outcome["video"]), outcome)
    return Path(outcome["video"])


def _render(result, directory, video, frames, progress):
    pictures = _pictures(result)
    return pictures.write_video(os.fspath(directory), video=video, frames=frames, progress=progress)


def _interrupted(result, partial, outcome):
    error = Interrupted(f"interrupted: rendered {outcome['frames']} frames; the partial video is {partial}",
                       result=result)
    error.path = Path(partial)
    error.frames = outcome["frames"]
    raise error


def write_plots(result, directory, format=None):  # noqa: A002 - the command line's word
    """Writes the scene's figures (its [[plots]], or the default ones) into ``directory`` as
    ``stiction run`` writes plots/: the same files, names and pixels. ``format`` ("png",
    "svg" or "pdf") overrides each figure's own, as ``--plot-format`` does. Returns the
    paths written. Ctrl-C between two figures raises :class:`stiction.Interrupted`
    (``written``: the figures done)."""
    written, interrupted = _pictures(result).write_plots(os.fspath(directory), format=format)
    written = [Path(p) for p in written]
    if interrupted:
        error = Interrupted(f"interrupted after {len(written)} figures", result=result)
        error.written = written
        raise error
    return written


# The methods of Result that draw (result.frame(t), result.write_video(path), ...).
def _frame_method(self, t, size=None):
    return frame(self, t, size=size)


def _frames_method(self, times, size=None):
    return frames(self, times, size=size)


_frame_method.__doc__ = frame.__doc__
_frames_method.__doc__ = frames.__doc__
Result.frame = _frame_method
Result.frames = _frames_method
Result.frame_times = frame_times
Result.write_video = write_video
Result.write_plots = write_plots
