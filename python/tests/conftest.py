"""Shared by the Python tests: the command-line binary and the source tree (set by ctest)."""

import json
import os
import subprocess
from pathlib import Path

import pytest

SOURCE_DIR = Path(os.environ.get("STICTION_SOURCE_DIR", Path(__file__).resolve().parents[2]))
BINARY = os.environ.get("STICTION_BINARY", str(SOURCE_DIR / "build" / "src" / "app" / "stiction"))

# summary.json values that measure the machine, not the run: they differ between any two runs.
TIMING_KEYS = {"wall_seconds", "analysis_seconds", "cpu_seconds", "why"}


@pytest.fixture
def cli(tmp_path):
    """Runs `stiction ARGS...` and returns the CompletedProcess (stdout and stderr as text)."""

    def run(*args, check=True):
        env = dict(os.environ, STICTION_CACHE_DIR="off")
        done = subprocess.run([BINARY, *map(str, args)], capture_output=True, text=True, env=env,
                              cwd=tmp_path)
        if check and done.returncode != 0:
            raise AssertionError(f"stiction {' '.join(map(str, args))} exited {done.returncode}:\n{done.stderr}")
        return done

    return run


def without_timings(value):
    """A summary with the machine's timings (TIMING_KEYS) removed, at any depth."""
    if isinstance(value, dict):
        return {k: without_timings(v) for k, v in value.items() if k not in TIMING_KEYS}
    if isinstance(value, list):
        return [without_timings(v) for v in value]
    return value


def load_json(path):
    with open(path) as f:
        return json.load(f)
