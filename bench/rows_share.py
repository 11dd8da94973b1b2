#!/usr/bin/env python3
"""The rows' share of `stiction run` per bundled scene and integrator (issue 36 item 4).

For every scene in scenes/ and every integrator, at the scene's dt (implicit also at 1/240 s)
and the scene's own output rate:

  after   bench_rows_share (bench/rows_share.cpp) runs the scene as `run --no-video` does
          and reads the run's own counters: the run loop's time on rows
          (RunResult::row_seconds) plus the wait for the CSV writer at the commit, over the
          wall time of simulate + commit ("wall share"); and the process CPU time (both
          threads) of simulate + commit less that of the same run at 2 rows per run, over
          the former ("CPU share": what the rows cost in CPU, whatever the load; marked * for
          rk4_adaptive, whose sparse run also takes longer steps).
  before  (--before BINARY, a `stiction` built from an earlier commit) the difference of
          summary.json's wall_seconds between the scene's output rate and 2 rows per run,
          over the former. For rk4_adaptive the step bound follows the output rate, so the
          sparse run takes longer steps and this overstates the rows (marked *).
  bytes   (with --before) trajectory.csv of the earlier binary and of this one, byte for
          byte, for every run (--accuracy off --no-plots --no-video).
  baseline (--baseline BUILD, another build directory with bench_rows_share, e.g. main's) the
          same two shares of that build, its runs alternating with this build's, so that both
          see the same load; replaces the `before` column's estimate.

Each timing is the smallest of --repeat runs. Durations are capped at --max-duration
(shares hardly depend on the length). Prints a Markdown table; --json FILE keeps the data.

  bench/rows_share.py --build build [--before OLD/stiction] [--baseline OLD_BUILD]
                      [--scenes a,b] [--repeat 2]
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


def bench_once(binary, scene, args):
    line = subprocess.run([binary, scene] + args, capture_output=True, text=True).stdout
    return json.loads(line.strip().splitlines()[-1])


def bench_after(binary, scene, args, repeat, duration, baseline=None):
    """The fastest of `repeat` runs of each binary, the two alternating. Each also runs at 2
    rows per run: its CPU time is the run's without rows, so `cpu_share` = (CPU - that) / CPU
    counts what the rows cost in CPU on both threads, however long either waited (the
    run's own `rows_cpu` counts the run loop's row time on the clock, waits included)."""
    best, sparse = {}, {}
    binaries = [binary] + ([baseline] if baseline else [])
    sparse_args = args + ["--set", f"simulation.output_rate={2.0 / duration!r}"]
    for _ in range(repeat):
        for b in binaries:
            r = bench_once(b, scene, args)
            if r.get("status") != "ok":
                best.setdefault(b, r)
                continue
            if b not in best or (best[b].get("status") == "ok" and r["wall"] < best[b]["wall"]):
                best[b] = r
            q = bench_once(b, scene, sparse_args)
            if q.get("status") == "ok" and (b not in sparse or q["cpu"] < sparse[b]):
                sparse[b] = q["cpu"]
            if b in sparse and best[b].get("status") == "ok":
                best[b]["cpu_dense_min"] = min(best[b].get("cpu_dense_min", 1e30), r["cpu"])
    for b, r in best.items():
        if r.get("status") == "ok" and b in sparse:
            dense_cpu = r.get("cpu_dense_min", r["cpu"])
            r["cpu_share"] = (dense_cpu - sparse[b]) / dense_cpu if dense_cpu > 0 else 0.0
            r["cpu_sparse"] = sparse[b]
    return best[binary], best.get(baseline)


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
    ap.add_argument("--baseline", help="a build directory to measure alongside (bench_rows_share)")
    ap.add_argument("--scenes", help="comma-separated names (default: every scenes/*.toml)")
    ap.add_argument("--integrators", help="comma-separated (default: all)")
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--max-duration", type=float, default=3.0)
    ap.add_argument("--json", help="write the measurements here")
    a = ap.parse_args()
    build = Path(a.build)
    bench = build / "bench" / "bench_rows_share"
    stiction = build / "src" / "app" / "stiction"
    baseline = str(Path(a.baseline) / "bench" / "bench_rows_share") if a.baseline else None
    names = a.scenes.split(",") if a.scenes else sorted(p.stem for p in (ROOT / "scenes").glob("*.toml"))
    wanted = set(a.integrators.split(",")) if a.integrators else set(INTEGRATORS)
    results = []
    print(f"machine: {os.cpu_count()} cores, {os.uname().machine}, load {os.getloadavg()[0]:.1f}",
          file=sys.stderr)
    if baseline:
        print("| scene | integrator | dt | rows | baseline: wall share | baseline: CPU share | "
              "after: wall share | after: CPU share | CSV bytes |")
        print("|---|---|---|---|---|---|---|---|---|")
    else:
        print("| scene | integrator | dt | rows | before: rows share (wall) | after: wall share | "
              "after: CPU share | CSV bytes |")
        print("|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory(prefix="rows_share_") as tmp:
        work = Path(tmp)
        for name in names:
            duration, rate, runs = configs(ROOT / "scenes" / f"{name}.toml", a.max_duration)
            for integrator, dt, args in runs:
                if integrator not in wanted:
                    continue
                after, base = bench_after(str(bench), name, args, a.repeat, duration, baseline)
                row = {"scene": name, "integrator": integrator, "dt": dt, "duration": duration,
                       "output_rate": rate, "after": after, "baseline": base}
                before_text, bytes_text = "", ""
                if base is not None:
                    star = "*" if integrator == "rk4_adaptive" else ""
                    before_text = (f"{100 * base['wall_share']:.0f}% | {100 * base['cpu_share']:.0f}%{star}"
                                   if base.get("status") == "ok" else f"{base.get('status')} |")
                elif a.before and after.get("status") == "ok":
                    share, rc = bench_before(a.before, name, args, duration, a.repeat, work)
                    row["before_share"] = share
                    mark = "*" if integrator == "rk4_adaptive" else ""
                    before_text = f"{100 * share:.0f}%{mark}" if share is not None else f"exit {rc}"
                if a.before and after.get("status") == "ok":
                    same = same_bytes(a.before, str(stiction), name, args, work)
                    row["same_bytes"] = same
                    bytes_text = {True: "identical", False: "DIFFER", None: "-"}[same]
                results.append(row)
                if after.get("status") != "ok":
                    status = after.get("status")
                    if base is not None and base.get("status") != "ok":
                        before_text = f"{base.get('status')} |"
                    print(f"| {name} | {integrator} | {dt:.3g} | - | {before_text} | {status} | | |")
                else:
                    star = "*" if integrator == "rk4_adaptive" else ""
                    print(f"| {name} | {integrator} | {dt:.3g} | {after['rows']} | {before_text} | "
                          f"{100 * after['wall_share']:.0f}% | {100 * after['cpu_share']:.0f}%{star} | "
                          f"{bytes_text} |")
                sys.stdout.flush()
    if a.json:
        Path(a.json).write_text(json.dumps(results, indent=1))


if __name__ == "__main__":
    main()
