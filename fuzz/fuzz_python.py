#!/usr/bin/env python3
"""Fuzzes the Python module's elements (issue 39 item 8): source laws (Scene.set_source) and
impedances written in Python (stiction.Impedance, `type = "external"`), driven through
stiction.run with random callbacks that return NaN, inf, huge or tiny numbers, the wrong
types or lengths, or raise (any exception, KeyboardInterrupt and SystemExit among them),
elements whose sizes, signal names, energies, slip velocities and stiffness are hostile, and
random run options. Cases are made from (--seed, case number) alone, so one case replays with
--only N.

Invariant, per case: the run returns a result, or raises a Python exception; it never kills
the interpreter (a signal), never hangs (--timeout per case), and a result with status "ok"
has only finite numbers in its rows and its summary's `final`. Every other exception is
counted by kind: raised by the callback itself (propagated), stiction's own errors
(SceneError, UnstableError, StepRefused), TypeError/ValueError/OverflowError with a message
(clear), anything else (unclear: listed, not a failure).

The cases run in a worker process that the parent restarts after a crash or a hang, so every
case is counted. Exit 0 when no case crashed, hung or ended ok with non-finite output; 1
otherwise (the failing case numbers are printed with the command that replays each).

    PYTHONPATH=build/python python3 fuzz/fuzz_python.py --cases 2000 --seed 1 --seconds 600
    PYTHONPATH=build/python python3 fuzz/fuzz_python.py --seed 1 --only 17 --verbose
"""

import argparse
import json
import math
import os
import random
import select
import signal
import subprocess
import sys
import time

# --- the values a callback may return ------------------------------------------------------

NON_FINITE = [float("nan"), float("inf"), -float("inf")]


class BadStr:
    """An exception argument whose str() itself raises."""

    def __str__(self):
        raise RuntimeError("str() of the exception argument failed")


class HostileError(Exception):
    pass


def raise_something(rng):
    """A thunk that raises one of many kinds of exception (what it raises, for the record)."""
    kind = rng.choice(["value", "zero", "recursion", "memory", "keyboard", "system_exit", "bad_str",
                       "custom", "stop_iteration", "attribute", "type", "assertion"])

    def thunk():
        if kind == "value":
            raise ValueError("fuzz: bad value")
        if kind == "zero":
            return 1 / 0
        if kind == "recursion":
            def deep(n):
                return deep(n + 1)
            return deep(0)
        if kind == "memory":
            raise MemoryError("fuzz: out of memory")
        if kind == "keyboard":
            raise KeyboardInterrupt
        if kind == "system_exit":
            raise SystemExit(3)
        if kind == "bad_str":
            raise HostileError(BadStr())
        if kind == "custom":
            raise HostileError("fuzz: custom")
        if kind == "stop_iteration":
            raise StopIteration
        if kind == "attribute":
            raise AttributeError("fuzz: attribute")
        if kind == "type":
            raise TypeError("fuzz: type")
        raise AssertionError("fuzz: assertion")
    return kind, thunk


def hostile_numbers(rng, n):
    """n values, or something that is not n finite floats."""
    import numpy as np
    choice = rng.randrange(24)
    good = [rng.uniform(-1.0, 1.0) for _ in range(n)]
    if choice == 0:
        return [float("nan")] * n
    if choice == 1:
        return [rng.choice(NON_FINITE)] + good[1:]
    if choice == 2:
        return [1e308] * n
    if choice == 3:
        return [5e-324] * n
    if choice == 4:
        return good + [0.0]  # one too many
    if choice == 5:
        return good[:-1]  # one too few
    if choice == 6:
        return "1.0" if n == 1 else ["1.0"] * n
    if choice == 7:
        return None
    if choice == 8:
        return np.full((n, 2), 0.5)
    if choice == 9:
        return np.array([np.float32("nan")] * n, dtype=np.float32)
    if choice == 10:
        return [complex(1, 1)] * n
    if choice == 11:
        return [10 ** 400] * n
    if choice == 12:
        return [True] * n
    if choice == 13:
        return {"x": 1.0}
    if choice == 14:
        return (x for x in good)
    if choice == 15:
        return np.array(["a"] * n)
    if choice == 16:
        return object()
    if choice == 17:
        return np.array(good, dtype=np.int64)
    if choice == 18:
        return [[x] for x in good]
    if choice == 19:
        return np.array(good)[::-1]  # a strided view
    if choice == 20:
        return [float("nan")] * n if rng.random() < 0.5 else [-float("inf")] * n
    if choice == 21:
        return []
    if choice == 22:
        return np.ma.masked_array(good, mask=[True] * n)
    return b"\x00" * n


def scalar_or(values, n):
    return values[0] if n == 1 and isinstance(values, list) and len(values) == 1 else values


HOSTILE_NAMES = ["u,v", 'a"b', "a\nb", "", "\x1b[31mred", "é", "x" * 5000, "t", "u", "a.b", " ",
                 "semi;colon", "tab\there", "\x00", "x,y\r\n", None, 3, b"bytes"]

INTEGRATORS = [None, "rk4", "euler", "heun", "symplectic_euler", "implicit", "rk4_adaptive",
               "sdirk2", "sdirk4", "bogus", 3, ""]


# --- the scenes --------------------------------------------------------------------------

ARM = """
[simulation]
integrator = "rk4"
dt = 1e-4
duration = 0.03
[bodies.arm]
type = "planar_arm"
links = [{ length = 0.2, width = 0.02, mass = 0.2 }]
[impedances.motor]
type = "torque_source"
body = "arm"
joint = 0
torque = "0.3"
[impedances.el]
type = "external"
body = "arm"
joint = 0
"""

BOX = """
gravity = [0.0, 0.0, 0.0]
[simulation]
integrator = "rk4"
dt = 1e-3
duration = 0.05
energy_tolerance = 1.0
[bodies.box]
type = "point_mass"
mass = 1.0
position = [0.1, 0.0, 0.0]
velocity = [0.5, 0.0, 0.0]
[impedances.el]
type = "external"
body = "box"
"""

# Two spheres touching (a pair contact) and a floor, a Python element at a point of one.
PAIR = """
[simulation]
integrator = "rk4"
dt = 1e-4
duration = 0.02
energy_tolerance = 1.0
[bodies.a]
type = "rigid_body"
shape = "sphere"
mass = 1.0
radius = 0.1
position = [0.0, 0.0, 0.1]
velocity = [1.0, 0.0, 0.0]
[bodies.b]
type = "rigid_body"
shape = "sphere"
mass = 1.0
radius = 0.1
position = [0.19, 0.0, 0.1]
[impedances.touch]
type = "kikuuwe_contact"
body = "a"
other = "b"
stiffness = 1e5
damping = 10.0
mu = 0.3
[impedances.floor]
type = "kikuuwe_contact"
body = "a"
stiffness = 1e5
damping = 10.0
[impedances.el]
type = "external"
body = "b"
point = [0.0, 0.0, 0.1]
"""

FORCE = """
gravity = [0.0, 0.0, 0.0]
[simulation]
integrator = "rk4"
dt = 1e-3
duration = 0.05
energy_tolerance = 1.0
[bodies.box]
type = "point_mass"
mass = 1.0
position = [0.0, 0.0, 0.0]
[impedances.push]
type = "force_source"
body = "box"
"""


def behaviour(rng, good_fn, n, label):
    """A callable (t, ...) -> value: good_fn's value until a random time or call, then a
    hostile value or an exception; also what it does, for the record."""
    mode = rng.choice(["good", "values", "values", "raise", "flaky"])
    after_t = rng.choice([0.0, rng.uniform(0.0, 0.03), rng.uniform(0.0, 0.03)])
    every = rng.choice([1, 1, 2, 7])
    record = {"what": label, "mode": mode, "after_t": after_t}
    if mode == "raise":
        kind, thunk = raise_something(rng)
        record["raise"] = kind
    bad = hostile_numbers(rng, n)
    record["value"] = repr(bad)[:60]
    calls = [0]

    def fn(t, *args):
        calls[0] += 1
        if mode == "good" or t < after_t or calls[0] % every:
            return good_fn(t, *args)
        if mode == "raise":
            return thunk()
        if mode == "flaky":
            return scalar_or(hostile_numbers(rng, n), n)
        return scalar_or(bad, n)
    return fn, record


def make_element(rng, inputs, outputs):
    """A stiction.Impedance subclass with hostile parts: (class, record)."""
    import numpy as np
    import stiction

    record = {"inputs": inputs, "outputs": outputs}
    state = rng.choice([0, 0, 1, 2])

    wrong = rng.choice(["input_size", "output_size", "state_size"]) if rng.random() < 0.15 else None

    def size(name, right):
        if name != wrong:
            return right
        value = rng.choice([0, -1, 10 ** 20, "2", None, 2.5, float("nan"), right + 1, True])
        record[name] = repr(value)
        return value

    attrs = {"input_size": size("input_size", inputs), "output_size": size("output_size", outputs),
             "state_size": size("state_size", state)}
    k = rng.uniform(1.0, 100.0)

    def good_evaluate(t, x_hat, y, tau):
        u = [k * x for x in list(x_hat)[:outputs]] + [0.0] * max(0, outputs - len(x_hat))
        y_dot = [-y[i] for i in range(len(y))] if state else None
        return u, y_dot

    evaluate, record["evaluate"] = behaviour(rng, good_evaluate, outputs, "evaluate")

    def evaluate_method(self, t, x_hat, y, tau):
        out = evaluate(t, x_hat, y, tau)
        if isinstance(out, tuple) and len(out) == 2:
            return out
        if rng.random() < 0.5:
            return out, None  # a hostile u with no y_dot
        return out  # not even a pair
    attrs["evaluate"] = evaluate_method

    if rng.random() < 0.4:
        pool = HOSTILE_NAMES if rng.random() < 0.4 else ["f", "g", "power", "e_1", "x-y"]
        names = [rng.choice(pool) for _ in range(rng.randrange(0, 4))]
        shape = rng.choice(["pair", "triple", "bare", "long"])
        if shape == "pair":
            sigs = [(nm, "N") for nm in names]
        elif shape == "triple":
            sigs = [(nm, "N", rng.choice(["desc", "\x1b[2J", None])) for nm in names]
        elif shape == "bare":
            sigs = names
        else:
            sigs = [(nm, "N", "d", "extra") for nm in names]
        record["signals"] = repr(sigs)[:80]
        attrs["signals"] = lambda self: sigs
        write, record["write_signals"] = behaviour(rng, lambda t, *a: [0.0] * len(sigs), len(sigs),
                                                   "write_signals")
        attrs["write_signals"] = lambda self, x_hat, y, u: write(1.0, x_hat, y, u)
    if rng.random() < 0.4:
        energy, record["stored_energy"] = behaviour(rng, lambda t, *a: 0.0, 1, "stored_energy")
        attrs["stored_energy"] = lambda self, x_hat, y: energy(1.0, x_hat, y)
    if rng.random() < 0.3:
        slip, record["slip_velocity"] = behaviour(rng, lambda t, x_hat: float(x_hat[-1]), 1,
                                                  "slip_velocity")
        attrs["slip_velocity"] = lambda self, x_hat: slip(1.0, x_hat)
    if rng.random() < 0.15:
        attrs["stiffness"] = rng.choice([float("nan"), float("inf"), -1.0, 0.0, 1e300, "1e3", None, 50.0])
        record["stiffness"] = repr(attrs["stiffness"])
    if rng.random() < 0.2:
        init = rng.choice([[float("nan")] * max(state, 1), [0.0] * (state + 1), "x", None, np.zeros(state)])
        attrs["initial_state"] = lambda self: init
        record["initial_state"] = repr(init)[:40]
    if rng.random() < 0.1:
        attrs["state_labels"] = [rng.choice(HOSTILE_NAMES) for _ in range(rng.randrange(0, 3))]
        record["state_labels"] = repr(attrs["state_labels"])[:60]
    cls = type("FuzzElement", (stiction.Impedance,), attrs)
    return cls, record


def make_case(seed, number):
    """(scene factory, run options, record) of case `number`."""
    import stiction

    rng = random.Random(f"{seed}:{number}")
    kind = rng.choice(["torque_law", "force_law", "arm_element", "point_element", "pair_element"])
    record = {"case": number, "kind": kind}
    if kind == "torque_law":
        law, record["law"] = behaviour(rng, lambda t, s: 0.1, 1, "law")
        signals = None
        if rng.random() < 0.3:
            signals = [rng.choice(["arm.theta.0", "arm.omega.0", "nope", "t"] + HOSTILE_NAMES)
                       for _ in range(rng.randrange(0, 3))]
            record["signals"] = repr(signals)[:80]

        def scene():
            return stiction.Scene("pd_arm").set_source("controller", law, signals=signals)
    elif kind == "force_law":
        law, record["law"] = behaviour(rng, lambda t, s: (0.1, 0.0, 0.0), 3, "law")

        def scene():
            return stiction.Scene.from_toml(FORCE, sources={"push": law})
    else:
        text, inputs, outputs = {"arm_element": (ARM, 2, 1), "point_element": (BOX, 6, 3),
                                 "pair_element": (PAIR, 6, 3)}[kind]
        cls, record["element"] = make_element(rng, inputs, outputs)
        as_instance = rng.random() < 0.5

        def scene():
            return stiction.Scene.from_toml(text, elements={"el": cls() if as_instance else cls})

    # Valid run options mostly (the elements are the subject), one hostile option at times.
    options = {"accuracy": False, "force_step": rng.random() < 0.7}
    if rng.random() < 0.3:
        options["integrator"] = rng.choice(["rk4", "euler", "heun", "symplectic_euler", "implicit"])
    if rng.random() < 0.2:
        options["dt"] = rng.choice([1e-4, 1e-3, 5e-3, 1e-5])
    if rng.random() < 0.2:
        hostile = rng.choice(["accuracy", "force_step", "integrator", "dt", "duration", "tolerance"])
        options[hostile] = rng.choice({
            "accuracy": [True, None, "yes", float("nan"), 2],
            "force_step": [False, "no", 2, None],
            "integrator": INTEGRATORS,
            "dt": [0.0, -1.0, float("nan"), float("inf"), "0.001", True, 1e300],
            "duration": [1e-9, 0.0, -1.0, float("nan"), True, 10 ** 400, 1e300],
            "tolerance": [1e-6, 1e-3, 0.0, float("nan"), 1e-300, -1.0],
        }[hostile])
        if hostile == "tolerance" and rng.random() < 0.7:
            options["integrator"] = rng.choice(["rk4_adaptive", "sdirk2", "sdirk4"])
    record["options"] = {k: repr(v) for k, v in options.items()}
    return scene, options, record


def finite_result(result):
    """Whether every row and every `final` value of a result is finite."""
    import numpy as np
    rows = np.asarray(result.rows)
    if rows.size and not np.isfinite(rows).all():
        return False
    for value in (result.summary.get("final") or {}).values():
        if isinstance(value, float) and not math.isfinite(value):
            return False
        if value is None:  # JSON null: a non-finite number written as null
            return False
    return True


def run_case(seed, number):
    """The outcome of one case: a dict with `outcome` and `detail`."""
    import warnings
    import stiction

    scene_of, options, record = make_case(seed, number)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            scene = scene_of()
            result = stiction.run(scene, **options)
    except stiction.Error as e:
        return {"outcome": "stiction_error", "detail": f"{type(e).__name__}: {str(e)[:200]}", "record": record}
    except (KeyboardInterrupt, SystemExit, MemoryError, RecursionError, ZeroDivisionError,
            HostileError, StopIteration, AssertionError) as e:
        return {"outcome": "propagated", "detail": f"{type(e).__name__}", "record": record}
    except (TypeError, ValueError, OverflowError, AttributeError, RuntimeError) as e:
        text = safe_str(e)
        fuzz_own = text.startswith("fuzz: ") or "str() of the exception argument failed" in text
        if fuzz_own:
            return {"outcome": "propagated", "detail": f"{type(e).__name__}: {text[:200]}", "record": record}
        if type(e) in (TypeError, ValueError, OverflowError) and text:
            return {"outcome": "clear_error", "detail": f"{type(e).__name__}: {text[:200]}", "record": record}
        return {"outcome": "unclear_error", "detail": f"{type(e).__name__}: {text[:300]}", "record": record}
    except BaseException as e:  # noqa: BLE001 - every other kind is counted, not a failure
        return {"outcome": "unclear_error", "detail": f"{type(e).__name__}: {safe_str(e)[:300]}",
                "record": record}
    if result.status == "ok" and not finite_result(result):
        return {"outcome": "nonfinite_ok", "detail": repr(result), "record": record}
    return {"outcome": "finished_" + str(result.status), "detail": repr(result)[:200], "record": record}


def safe_str(e):
    try:
        return str(e)
    except BaseException:  # noqa: BLE001
        return f"<str() of {type(e).__name__} raised>"


# --- the worker and the parent -------------------------------------------------------------

def worker(seed, numbers):
    """Runs the cases, one JSON line per case on stdout ("start" before, the outcome after)."""
    out = sys.stdout
    sys.stdout = sys.stderr  # anything a case prints goes to stderr, not into the protocol
    sys.setrecursionlimit(400)
    for number in numbers:
        out.write(json.dumps({"start": number}) + "\n")
        out.flush()
        outcome = run_case(seed, number)
        outcome["case"] = number
        out.write(json.dumps(outcome, default=repr) + "\n")
        out.flush()


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--cases", type=int, default=1000, help="cases to run (default 1000)")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--seconds", type=float, default=0.0,
                        help="stop starting new cases after this long (0: no bound)")
    parser.add_argument("--timeout", type=float, default=10.0, help="seconds one case may take")
    parser.add_argument("--only", type=int, help="run this case alone, in this process")
    parser.add_argument("--verbose", action="store_true", help="print every case's outcome")
    parser.add_argument("--worker", nargs="*", type=int, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.worker is not None:
        worker(args.seed, range(args.worker[0], args.worker[1]))
        return 0
    if args.only is not None:
        outcome = run_case(args.seed, args.only)
        print(json.dumps(outcome, indent=1, default=repr))
        return 1 if outcome["outcome"] == "nonfinite_ok" else 0

    started = time.monotonic()
    counts, findings, unclear = {}, [], []
    next_case, proc = 0, None
    stderr_log = open(os.devnull, "w") if not args.verbose else sys.stderr

    def start_worker(first):
        return subprocess.Popen([sys.executable, os.path.abspath(__file__), "--seed", str(args.seed),
                                 "--worker", str(first), str(args.cases)],
                                stdout=subprocess.PIPE, stderr=stderr_log, bufsize=0)

    current = None
    pending = b""  # bytes read from the worker, not yet a whole line
    deadline_hit = False
    while next_case < args.cases:
        if args.seconds and time.monotonic() - started > args.seconds:
            deadline_hit = True
            break
        if proc is None:
            proc = start_worker(next_case)
            current, pending = None, b""
        if b"\n" not in pending:
            ready, _, _ = select.select([proc.stdout], [], [], args.timeout)
        else:
            ready = True
        if not ready:  # one case took longer than the timeout: a hang
            proc.kill()
            proc.wait()
            number = current if current is not None else next_case
            counts["hang"] = counts.get("hang", 0) + 1
            findings.append(("hang", number, f"no outcome within {args.timeout:g} s"))
            next_case, proc, pending = number + 1, None, b""
            continue
        if b"\n" not in pending:
            chunk = os.read(proc.stdout.fileno(), 65536)
            pending += chunk
            if chunk:
                continue
        if b"\n" in pending:
            line, pending = pending.split(b"\n", 1)
        else:
            line = b""
        if not line:  # the worker died
            code = proc.wait()
            if current is None:  # died between cases: finished, or before the first
                if code != 0:
                    findings.append(("worker", next_case, f"worker exit {code} outside a case"))
                proc = None
                if code == 0:
                    break
                next_case += 1
                continue
            kind = f"signal {-code}" if code < 0 else f"exit {code}"
            counts["crash"] = counts.get("crash", 0) + 1
            findings.append(("crash", current, kind))
            next_case, proc, pending = current + 1, None, b""
            continue
        message = json.loads(line)
        if "start" in message:
            current = message["start"]
            continue
        current = None
        next_case = message["case"] + 1
        outcome = message["outcome"]
        counts[outcome] = counts.get(outcome, 0) + 1
        if args.verbose:
            print(json.dumps(message, default=repr))
        if outcome == "nonfinite_ok":
            findings.append((outcome, message["case"], message["detail"]))
        if outcome == "unclear_error":
            unclear.append((message["case"], message["detail"]))
    if proc is not None:
        proc.kill()
        proc.wait()

    done = sum(counts.values())
    elapsed = time.monotonic() - started
    print(f"fuzz_python: seed {args.seed}: {done} cases in {elapsed:.1f} s"
          + (" (time bound reached)" if deadline_hit else ""))
    for key in sorted(counts):
        print(f"  {key}: {counts[key]}")
    print(f"  crashes (signals): {counts.get('crash', 0)}, hangs: {counts.get('hang', 0)}, "
          f"ok with non-finite output: {counts.get('nonfinite_ok', 0)}")
    kinds = {}
    for number, detail in unclear:
        kinds.setdefault(detail.split(":")[0] + ": " + detail.split(":", 1)[-1][:70], []).append(number)
    for detail, numbers in sorted(kinds.items()):
        print(f"  unclear error x{len(numbers)} (cases {', '.join(map(str, numbers[:5]))}): {detail}")
    for kind, number, detail in findings:
        print(f"FINDING {kind}: case {number}: {detail}\n  replay: python3 {sys.argv[0]} --seed {args.seed} --only {number}")
    return 1 if findings else 0


if __name__ == "__main__":
    signal.signal(signal.SIGPIPE, signal.SIG_DFL)
    sys.exit(main())
