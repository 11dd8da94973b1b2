"""A single-node Slurm cluster (munged, slurmctld, slurmd on localhost) started from a
configuration written into a temporary directory, for tests/cluster/slurm_sweep.py.

Nothing system-wide is read or written: the daemons get their configuration through
SLURM_CONF and -f, their munge socket through AuthInfo, and keep their state, spool, logs and
PID files in the directory. Root is needed: slurmd starts each job's steps as the job's user
(setgroups/setuid), which an ordinary user cannot do.
"""

import ctypes
import os
import shutil
import signal
import socket
import subprocess
import time
from pathlib import Path

DAEMONS = ("munged", "slurmctld", "slurmd", "sbatch", "squeue", "scontrol", "scancel")


def missing_programs():
    return [name for name in DAEMONS if shutil.which(name) is None
            and not Path("/usr/sbin", name).exists()]


def program(name):
    return shutil.which(name) or str(Path("/usr/sbin", name))


def die_with_parent():
    """In the daemon before exec: SIGTERM when the driver dies, even by SIGKILL (a ctest
    timeout), so that no daemon outlives the test."""
    ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class SingleNodeSlurm:
    """Use as a context manager; env is the environment the clients (and jobs) need."""

    def __init__(self, root: Path, cpus: int):
        self.root = root
        self.cpus = cpus
        self.host = socket.gethostname().split(".")[0]
        self.processes = []
        self.env = dict(os.environ, SLURM_CONF=str(root / "slurm.conf"))

    def __enter__(self):
        try:
            self._start_munge()
            self._write_config()
            self._start("slurmctld", "-D", "-c", "-f", str(self.root / "slurm.conf"))
            self._start("slurmd", "-D", "-f", str(self.root / "slurm.conf"), "-N", self.host)
            self._wait_for_idle_node()
        except BaseException:
            self.__exit__(None, None, None)
            raise
        return self

    def __exit__(self, *exc):
        subprocess.run([program("scancel"), "--user", str(os.getuid())], env=self.env,
                       capture_output=True, timeout=30, check=False)
        for p in reversed(self.processes):
            if p.poll() is None:
                p.send_signal(signal.SIGTERM)
        for p in reversed(self.processes):
            try:
                p.wait(timeout=15)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()
        return False

    def _start(self, name, *args):
        log = open(self.root / f"{name}.console", "wb")
        self.processes.append(subprocess.Popen([program(name), *args], env=self.env,
                                               stdout=log, stderr=subprocess.STDOUT,
                                               preexec_fn=die_with_parent))

    def _start_munge(self):
        munge = self.root / "munge"
        munge.mkdir(mode=0o700)
        key = munge / "munge.key"
        key.write_bytes(os.urandom(1024))
        key.chmod(0o400)
        self.munge_socket = munge / "munge.socket"
        self._start("munged", "-F", "--force", f"--key-file={key}", f"--socket={self.munge_socket}",
                    f"--pid-file={munge / 'munged.pid'}", f"--log-file={munge / 'munged.log'}",
                    f"--seed-file={munge / 'munged.seed'}")
        deadline = time.monotonic() + 20
        while not self.munge_socket.exists():
            if self.processes[-1].poll() is not None or time.monotonic() > deadline:
                raise RuntimeError("munged did not start: " + self.log("munged.console")
                                   + self.log("munge/munged.log"))
            time.sleep(0.1)

    def _write_config(self):
        r = self.root
        for d in ("state", "spool"):
            (r / d).mkdir()
        user = subprocess.run(["id", "-un"], capture_output=True, text=True, check=True).stdout.strip()
        # config_overrides: the node has the CPUs written here whatever the machine has, so
        # that the docs' --cpus-per-task=4 is accepted on a 2-core runner.
        (r / "slurm.conf").write_text(f"""\
ClusterName=stictionci
SlurmctldHost={self.host}(127.0.0.1)
SlurmctldPort={free_port()}
SlurmdPort={free_port()}
SlurmUser={user}
SlurmdUser={user}
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket={self.munge_socket}
StateSaveLocation={r / 'state'}
SlurmdSpoolDir={r / 'spool'}
SlurmctldPidFile={r / 'slurmctld.pid'}
SlurmdPidFile={r / 'slurmd.pid'}
SlurmctldLogFile={r / 'slurmctld.log'}
SlurmdLogFile={r / 'slurmd.log'}
SlurmdParameters=config_overrides
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SwitchType=switch/none
MpiDefault=none
MailProg=/bin/true
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MinJobAge=3600
DependencyParameters=kill_invalid_depend
NodeName={self.host} NodeAddr=127.0.0.1 CPUs={self.cpus} State=UNKNOWN
PartitionName=ci Nodes=ALL Default=YES MaxTime=INFINITE State=UP
""")

    def _wait_for_idle_node(self):
        deadline = time.monotonic() + 60
        state = ""
        while time.monotonic() < deadline:
            for p in self.processes:
                if p.poll() is not None:
                    raise RuntimeError(f"{p.args[0]} exited with {p.returncode}: " + self.logs())
            q = subprocess.run([program("sinfo") if shutil.which("sinfo") else "sinfo",
                                "-h", "-o", "%t"], env=self.env, capture_output=True, text=True,
                               check=False)
            state = q.stdout.strip()
            if state == "idle":
                return
            time.sleep(0.5)
        raise RuntimeError(f"the node is not idle after 60 s (sinfo: {state!r}): " + self.logs())

    def log(self, name):
        path = self.root / name
        text = path.read_text(errors="replace") if path.exists() else ""
        return f"\n--- {name} (last lines)\n" + "\n".join(text.splitlines()[-20:])

    def logs(self):
        return "".join(self.log(n) for n in ("munged.console", "slurmctld.console", "slurmctld.log",
                                             "slurmd.console", "slurmd.log"))

    def run(self, *args, cwd=None, env=None):
        """A client command (sbatch, squeue, ...); its stdout, stripped."""
        done = subprocess.run([program(args[0]), *args[1:]], env=env or self.env, cwd=cwd,
                              capture_output=True, text=True, timeout=60, check=False)
        if done.returncode != 0:
            raise RuntimeError(f"{' '.join(args)}: exit {done.returncode}: {done.stderr}")
        return done.stdout.strip()

    def jobs(self):
        """{job id (ARRAYJOB_TASK for a task): its scontrol fields} for every job slurmctld holds."""
        out = self.run("scontrol", "-o", "show", "job")
        jobs = {}
        for line in out.splitlines():
            fields = dict(f.split("=", 1) for f in line.split() if "=" in f)
            if "JobId" not in fields:
                continue
            # An array task as squeue and scancel name it (ARRAYJOB_TASK); a pending rest of
            # an array is one record with a range of tasks.
            task = fields.get("ArrayTaskId")
            jobs[f"{fields['ArrayJobId']}_{task}" if task else fields["JobId"]] = fields
        return jobs

    def wait_until_done(self, seconds):
        """Waits until no job is pending or running; the jobs' final fields."""
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            jobs = self.jobs()
            if all(j["JobState"] not in ("PENDING", "RUNNING", "CONFIGURING", "COMPLETING")
                   for j in jobs.values()):
                return jobs
            time.sleep(1)
        raise RuntimeError(f"jobs still queued after {seconds} s: "
                           + self.run("squeue") + self.logs())
