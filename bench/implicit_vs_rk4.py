#!/usr/bin/env python3
"""Every bundled scene run with `--integrator implicit` at a step 10 to 1000 times the
scenes' own, against rk4 at 1e-5 s: the key event times of every element (first stick and
first slip; not the last stick, which a stiff contact's bounces set) and the difference of
their event counts, the largest difference of the final state and the CPU time of each run.

    bench/implicit_vs_rk4.py [--stiction build/src/app/stiction] [--dts 1e-3,1e-4] [SCENE...]

Prints one Markdown table (docs/study.md quotes it). Runs `stiction run` with
--no-plots --no-video --accuracy off --force-step into a temporary directory.
"""
import argparse
import json
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent


def run(stiction, scene, integrator, dt, out):
    cmd = [stiction, "run", str(scene), "--integrator", integrator, "--dt", repr(dt),
           "--no-plots", "--no-video", "--accuracy", "off", "--force-step", "--quiet",
           "--out", str(out)]
    done = subprocess.run(cmd, capture_output=True, text=True)
    summary = out / "summary.json"
    if not summary.exists():
        return None, done.returncode, done.stderr.strip().splitlines()[-1:] or [""]
    return json.loads(summary.read_text()), done.returncode, []


KEY_EVENTS = ("stick_time", "first_slip")


def compare_events(reference, other):
    """Largest difference of the key event times (first stick, first slip) of
    every element both runs have, and the difference of the elements' event counts (the
    bounces of a stiff contact that one method damps and the other keeps)."""
    worst, where, count = 0.0, "", 0
    for element, ref in (reference.get("events") or {}).items():
        got = (other.get("events") or {}).get(element, {})
        count += abs(len(ref.get("events", [])) - len(got.get("events", [])))
        for key in KEY_EVENTS:
            a, b = ref.get(key), got.get(key)
            if not isinstance(a, (int, float)) or not isinstance(b, (int, float)):
                if (a is None) != (b is None):
                    where += f" {element}.{key} only in one"
                continue
            if a < 0 and b < 0:
                continue
            if abs(a - b) > worst:
                worst = abs(a - b)
                where = f"{element}.{key}"
    return worst, where, count


def final_difference(reference, other):
    worst, where = 0.0, ""
    for name, value in reference["final"].items():
        v = other["final"].get(name)
        if not isinstance(value, (int, float)) or not isinstance(v, (int, float)):
            continue
        if name.endswith(".e") or ".e." in name or name == "t":
            continue  # friction states: spring offsets of size F/K, compared as drift below
        d = abs(v - value)
        if d > worst:
            worst, where = d, name
    return worst, where


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--stiction", default=str(ROOT / "build/src/app/stiction"))
    parser.add_argument("--dts", default="1e-3")
    parser.add_argument("scenes", nargs="*")
    args = parser.parse_args()
    scenes = [pathlib.Path(s) for s in args.scenes] or sorted((ROOT / "scenes").glob("*.toml"))
    dts = [float(d) for d in args.dts.split(",")]
    print("| scene | run | CPU s | first stick and first slip: worst difference "
          "| event count difference | largest final difference |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        for scene in scenes:
            ref, code, err = run(args.stiction, scene, "rk4", 1e-5, tmp / (scene.stem + "_rk4"))
            if ref is None:
                print(f"| {scene.stem} | rk4 1e-5 | | exit {code}: {err[0]} | | |")
                continue
            print(f"| {scene.stem} | rk4 1e-5 ({ref['status']}) | {ref['wall_seconds']:.3g} | "
                  f"(reference) | | |")
            for dt in dts:
                out = tmp / f"{scene.stem}_implicit_{dt}"
                got, code, err = run(args.stiction, scene, "implicit", dt, out)
                if got is None:
                    print(f"| {scene.stem} | implicit {dt:g} | | exit {code}: {err[0]} | | |")
                    continue
                worst, which, unpaired = compare_events(ref, got)
                final, where = final_difference(ref, got)
                print(f"| {scene.stem} | implicit {dt:g} ({got['status']}) | "
                      f"{got['wall_seconds']:.3g} | {worst:.3g} s ({which}) | {unpaired} | "
                      f"{final:.3g} ({where}) |")
            sys.stdout.flush()


if __name__ == "__main__":
    main()
