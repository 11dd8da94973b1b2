"""Sweeps on a real cluster engine (issue 25): the job-array script and the dependent merge job
of docs/sweeps.md, taken from the document's code blocks as they stand, run on a single-node
Slurm started here (single_node_slurm.py); the merged table must equal an unsharded run of
the same command bit for bit (every column but wall_s).

Then a shard SIGKILLed while it writes (kill -9 of a running array task's stiction process,
in a variant of the script that keeps every point's files, so that a point's temporaries
exist whenever a task runs; scancel --signal=KILL --full marked the task CANCELLED but left
the process running to its end here, so it proved nothing), the array resubmitted and merged: the table must again equal
the unsharded one and no temporary (".NAME.tmp-XXXXXXXXXXXXXXXX") may remain.

Usage: slurm_sweep.py STICTION_BINARY DOCS_SWEEPS_MD. Exit 77 (skipped) without the Debian
packages slurm-wlm and munge, or when not root (a failure instead with
STICTION_REQUIRE_SLURM=1, as .ci/run sets); 0 passed; 1 failed.
"""

import csv
import os
import re
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from single_node_slurm import SingleNodeSlurm, missing_programs  # noqa: E402

SKIP = 77
TEMPORARY = re.compile(r"^\..*\.tmp-[0-9a-f]{16}$")


def skip(why):
    """Skipped; a failure when STICTION_REQUIRE_SLURM=1 (CI, which installs the packages)."""
    if os.environ.get("STICTION_REQUIRE_SLURM") == "1":
        fail(f"STICTION_REQUIRE_SLURM=1 but {why}")
    print(f"SKIPPED: {why}", flush=True)
    sys.exit(SKIP)


def fail(why):
    print(f"FAILED: {why}", flush=True)
    sys.exit(1)


def code_blocks(markdown):
    return re.findall(r"^```sh\n(.*?)^```", markdown, flags=re.S | re.M)


def docs_scripts(docs):
    """The job-array script and the submit-and-merge lines of docs/sweeps.md, unchanged."""
    blocks = code_blocks(docs.read_text())
    array = [b for b in blocks if b.startswith("#!/bin/bash") and "#SBATCH --array=" in b]
    submit = [b for b in blocks if "sbatch --parsable sweep.sbatch" in b and "--dependency=afterok" in b]
    if len(array) != 1 or len(submit) != 1:
        fail(f"{docs}: expected one job-array script and one submit block, found {len(array)} and {len(submit)}")
    return array[0], submit[0]


def table(path):
    """sweep.csv without wall_s (the one column that differs between two runs)."""
    if not path.exists():
        fail(f"no {path}")
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    keep = [i for i, name in enumerate(rows[0]) if name != "wall_s"]
    return [[row[i] for i in keep] for row in rows]


def compare(merged, reference, what):
    a, b = table(merged), table(reference)
    if a != b:
        diff = next((i, x, y) for i, (x, y) in enumerate(zip(a + [None], b + [None])) if x != y)
        fail(f"{what}: {merged} differs from the unsharded {reference} "
             f"({len(a)} against {len(b)} rows; first difference at row {diff[0]}: {diff[1]} / {diff[2]})")
    print(f"{what}: the merged table equals the unsharded run's ({len(a) - 1} points, every column but wall_s)")


def temporaries(directory):
    return sorted(str(p.relative_to(directory)) for p in directory.rglob("*") if TEMPORARY.match(p.name))


def unsharded(script, home, env):
    """The script's command outside Slurm (no array variables: the whole sweep in one run)."""
    env = {k: v for k, v in env.items() if not k.startswith("SLURM_")}
    env.update(HOME=str(home), SLURM_CPUS_PER_TASK=str(os.cpu_count() or 2))
    home.mkdir(parents=True)
    done = subprocess.run(["bash", "-c", script], cwd=home, env=env, capture_output=True, text=True,
                          timeout=1800, check=False)
    if done.returncode != 0:
        fail(f"the unsharded run exited {done.returncode}: {done.stderr[-2000:]}")


def check_completed(jobs, expected, what, logs):
    states = {j: f["JobState"] for j, f in jobs.items()}
    bad = {j: s for j, s in states.items() if s != "COMPLETED"}
    if bad or len(states) != expected:
        outputs = "".join(f"\n--- {p.name}\n{p.read_text(errors='replace')[-1500:]}"
                          for p in sorted(logs.glob("*.out")))
        fail(f"{what}: expected {expected} completed jobs, got {states}{outputs}")


def job_array(script, submit, cluster, root, env):
    """The docs' array and merge job as written; the merged table against an unsharded run."""
    work, home = root / "submit", root / "home"
    (work / "logs").mkdir(parents=True)
    home.mkdir()
    (work / "sweep.sbatch").write_text(script)
    env = dict(env, HOME=str(home))
    low, high = map(int, re.search(r"#SBATCH --array=(\d+)-(\d+)", script).groups())
    tasks = high - low + 1
    start = time.monotonic()
    done = subprocess.run(["bash", "-euo", "pipefail", "-c", submit], cwd=work, env=env,
                          capture_output=True, text=True, timeout=120, check=False)
    if done.returncode != 0:
        fail(f"the submit block exited {done.returncode}: {done.stderr}")
    jobs = cluster.wait_until_done(1800)
    check_completed(jobs, tasks + 1, "job array and merge job", work / "logs")
    print(f"job array: {tasks} tasks and the dependent merge job completed in {time.monotonic() - start:.0f} s")
    unsharded(script, root / "reference", env)
    compare(home / "sweeps/mu/sweep.csv", root / "reference/sweeps/mu/sweep.csv", "job array")
    return tasks


def task_processes(job, task):
    """The pids of the stiction processes of array task JOB_TASK (from their environment)."""
    want = {f"SLURM_ARRAY_JOB_ID={job}".encode(), f"SLURM_ARRAY_TASK_ID={task}".encode()}
    pids = []
    for proc in Path("/proc").iterdir():
        try:
            if proc.name.isdigit() and (proc / "comm").read_text().strip() == "stiction" \
                    and want <= set((proc / "environ").read_bytes().split(b"\0")):
                pids.append(int(proc.name))
        except OSError:
            continue  # gone meanwhile
    return pids


def kill_a_writing_task(out, job, tasks):
    """SIGKILL to the stiction process of a task while one of its points' temporaries exists;
    the task's name."""
    deadline = time.monotonic() + 600
    while time.monotonic() < deadline:
        for name in temporaries(out) if out.exists() else []:
            point = re.search(r"points/(\d+)/", name)
            if not point:
                continue
            task = int(point.group(1)) % tasks
            pids = task_processes(job, task)
            if pids and (out / name).exists():
                for pid in pids:
                    os.kill(pid, signal.SIGKILL)
                return f"{job}_{task}"
        time.sleep(0.02)
    fail("no running task was seen writing a temporary within 600 s")


def killed_shard(script, cluster, root, env, tasks):
    """A task SIGKILLed while a point's files are being written, the array resubmitted."""
    variant = script.replace("--keep none", "--keep all").replace("0.01:1:400:log", "0.01:1:32:log")
    if variant.count("--keep all") != 1 or "0.01:1:32:log" not in variant:
        fail("the docs' script no longer has '--keep none' and '0.01:1:400:log' for the variant")
    work, home = root / "kill", root / "kill-home"
    (work / "logs").mkdir(parents=True)
    home.mkdir()
    (work / "sweep.sbatch").write_text(variant)
    env = dict(env, HOME=str(home))
    out = home / "sweeps/mu"
    first = cluster.run("sbatch", "--parsable", "sweep.sbatch", cwd=work, env=env)
    killed = kill_a_writing_task(out, first, tasks)
    jobs = cluster.wait_until_done(1800)
    if jobs[killed]["JobState"] == "COMPLETED":
        fail(f"task {killed} completed although its process was sent SIGKILL")
    left = temporaries(out)
    print(f"killed task {killed} ({jobs[killed]['JobState']}, {jobs[killed].get('ExitCode')}); "
          f"it left {len(left)} temporaries: {left[:4]}")
    if not left:
        fail("the SIGKILL left no temporary: it missed the point being written, the check shows nothing")
    second = cluster.run("sbatch", "--parsable", "sweep.sbatch", cwd=work, env=env)
    merge = cluster.run("sbatch", "--parsable", f"--dependency=afterok:{second}", "--wrap",
                        f"stiction sweep --merge {out}", cwd=work, env=env)
    jobs = cluster.wait_until_done(1800)
    resubmitted = {j: f for j, f in jobs.items() if j.startswith(f"{second}_") or j == merge}
    check_completed(resubmitted, tasks + 1, "resubmitted array and merge job", work / "logs")
    unsharded(variant, root / "kill-reference", env)
    compare(out / "sweep.csv", root / "kill-reference/sweeps/mu/sweep.csv", "killed and resubmitted")
    left = temporaries(out)
    if left:
        fail(f"the resubmitted array left {len(left)} temporaries in {out}: {left[:10]}")
    print("killed and resubmitted: no temporary left")


def main():
    if len(sys.argv) != 3:
        fail("usage: slurm_sweep.py STICTION_BINARY DOCS_SWEEPS_MD")
    stiction, docs = Path(sys.argv[1]).resolve(), Path(sys.argv[2])
    missing = missing_programs()
    if missing:
        skip(f"no {', '.join(missing)}: install the Debian packages slurm-wlm and munge "
             "(scripts/bootstrap.sh --slurm) to run sweeps on a single-node Slurm")
    if os.getuid() != 0:
        skip("not root: slurmd must start each job as its user (setuid), which needs root")
    script, submit = docs_scripts(docs)
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))  # stop the daemons on the way out
    with tempfile.TemporaryDirectory(prefix="stiction-slurm-") as tmp:
        root = Path(tmp)
        (root / "slurm").mkdir()
        with SingleNodeSlurm(root / "slurm", cpus=max(4, os.cpu_count() or 1)) as cluster:
            env = dict(cluster.env, PATH=f"{stiction.parent}:{os.environ.get('PATH', '/usr/bin:/bin')}")
            # STICTION_CLUSTER_PARTS=array or =kill runs one of the two parts alone.
            parts = os.environ.get("STICTION_CLUSTER_PARTS", "array,kill").split(",")
            low, high = map(int, re.search(r"#SBATCH --array=(\d+)-(\d+)", script).groups())
            if "array" in parts:
                job_array(script, submit, cluster, root, env)
            if "kill" in parts:
                killed_shard(script, cluster, root, env, high - low + 1)
    print("PASSED")


if __name__ == "__main__":
    main()
