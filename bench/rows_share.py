#!/usr/bin/env python3
"""The rows' share of `stiction run` per bundled scene and integrator (issue 36 item 4).

For every scene in scenes/ and every integrator, at the scene's dt (implicit also at 1/240 s)
and the scene's own output rate:

  after   bench_rows_share (bench/rows_share.cpp) runs the scene as `run --no-video` does
          and reads the run's own counters: the run loop's time on rows
          (RunResult::row_seconds) plus the wait for the CSV writer at the commit, over the
          wall time of simulate + commit ("wall share"); and the same rows' CPU (main
          thread's row time + the writer thread's CPU) over the process CPU ("CPU share").
  before  (--before BINARY, a `stiction` built from an earlier commit) the difference of
          summary.json's wall_seconds between the scene's output rate and 2 rows per run,
          over the former. For rk4_adaptive the step bound follows the output rate, so the
          sparse run takes longer steps and this overstates the rows (marked *).
  bytes   (with --before) trajectory.csv of the earlier binary and of this one, byte for
          byte, for every run (--accuracy off --no-plots --no-video).

Each timing is the smallest of --repeat runs. Durations are capped at --max-duration
(shares hardly depend on the length). Prints a Markdown table; --json FILE keeps the data.

  bench/rows_share.py --build build [--before OLD/stiction] [--scenes a,b] [--repeat 2]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
INTEGRATORS = ["euler", "symplectic_euler", "heun", "rk4", "rk4_adaptive", "implicit"]
TOLERANCE = "1e-6"  # rk4_adaptive's
IMPLICIT_DT = 1.0 / 240.0


def configs(scene_file, max_duration):
    sim = tomllib.loads(scene_file.read_text()).get("simulation", {})
    dt = float(sim.get("dt", 1e-4))
    duration = min(float(sim.get("duration", 1.0)), max_duration)
    rate = float(sim.get("output_rate", 1000.0))
    out = []
    for integrator in INTEGRATORS:
        args = ["--integrator", integrator, "--duration", repr(duration)]
        if integrator == "rk4_adaptive":
            out.append((integrator, dt, args + ["--dt", repr(dt), "--tolerance", TOLERANCE]))
        else:
            out.append((integrator, dt, args + ["--dt", repr(dt)]))
        if integrator == "implicit" and dt != IMPLICIT_DT:
            out.append((integrator, IMPLICIT_DT, args + ["--dt", repr(IMPLICIT_DT)]))
    return duration, rate, out


def bench_after(binary, scene, args, repeat):
    best = None
    for _ in range(repeat):
        line = subprocess.run([binary, scene] + args, capture_output=True, text=True).stdout
        r = json.loads(line.strip().splitlines()[-1])
        if r.get("status") != "ok":
            return r
        if best is None or r["wall"] < best["wall"]:
            best = r
    return best


def run_wall(binary, scene, args, out, rate=None):
    cmd = [binary, "run", scene, "--out", str(out), "--overwrite", "--accuracy", "off",
           "--no-plots", "--no-video", "--quiet"] + args
    if rate is not None:
        cmd += ["--set", f"simulation.output_rate={rate!r}"]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        return None, p.returncode
    return json.loads((out / "summary.json").read_text())["wall_seconds"], 0


def bench_before(binary, scene, args, duration, repeat, work):
    dense, sparse = [], []
    for _ in range(repeat):
        w, rc = run_wall(binary, scene, args, work / "before")
        if w is None:
            return None, rc
        dense.append(w)
        w, rc = run_wall(binary, scene, args, work / "sparse", rate=2.0 / duration)
        sparse.append(w)
    return (min(dense) - min(sparse)) / min(dense), 0


def same_bytes(before, after, scene, args, work):
    run_wall(before, scene, args, work / "old")
    run_wall(after, scene, args, work / "new")
    a, b = work / "old" / "trajectory.csv", work / "new" / "trajectory.csv"
    if not a.exists() or not b.exists():
        return None
    return a.read_bytes() == b.read_bytes()


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--before", help="a stiction binary from before the change")
    ap.add_argument("--scenes", help="comma-separated names (default: every scenes/*.toml)")
    ap.add_argument("--integrators", help="comma-separated (default: all)")
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--max-duration", type=float, default=3.0)
    ap.add_argument("--json", help="write the measurements here")
    a = ap.parse_args()
    build = Path(a.build)
    bench = build / "bench" / "bench_rows_share"
    stiction = build / "src" / "app" / "stiction"
    names = a.scenes.split(",") if a.scenes else sorted(p.stem for p in (ROOT / "scenes").glob("*.toml"))
    wanted = set(a.integrators.split(",")) if a.integrators else set(INTEGRATORS)
    results = []
    print(f"machine: {os.cpu_count()} cores, {os.uname().machine}, load {os.getloadavg()[0]:.1f}",
          file=sys.stderr)
    print("| scene | integrator | dt | rows | before: rows share (wall) | after: wall share | after: CPU share | CSV bytes |")
    print("|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory(prefix="rows_share_") as tmp:
        work = Path(tmp)
        for name in names:
            duration, rate, runs = configs(ROOT / "scenes" / f"{name}.toml", a.max_duration)
            for integrator, dt, args in runs:
                if integrator not in wanted:
                    continue
                after = bench_after(str(bench), name, args, a.repeat)
                row = {"scene": name, "integrator": integrator, "dt": dt, "duration": duration,
                       "output_rate": rate, "after": after}
                before_text, bytes_text = "", ""
                if a.before and after.get("status") == "ok":
                    share, rc = bench_before(a.before, name, args, duration, a.repeat, work)
                    row["before_share"] = share
                    mark = "*" if integrator == "rk4_adaptive" else ""
                    before_text = f"{100 * share:.0f}%{mark}" if share is not None else f"exit {rc}"
                    same = same_bytes(a.before, str(stiction), name, args, work)
                    row["same_bytes"] = same
                    bytes_text = {True: "identical", False: "DIFFER", None: "-"}[same]
                results.append(row)
                if after.get("status") != "ok":
                    status = after.get("status")
                    print(f"| {name} | {integrator} | {dt:.3g} | - | {before_text} | {status} | | |")
                else:
                    print(f"| {name} | {integrator} | {dt:.3g} | {after['rows']} | {before_text} | "
                          f"{100 * after['wall_share']:.0f}% | {100 * after['cpu_share']:.0f}% | {bytes_text} |")
                sys.stdout.flush()
    if a.json:
        Path(a.json).write_text(json.dumps(results, indent=1))


if __name__ == "__main__":
    main()
