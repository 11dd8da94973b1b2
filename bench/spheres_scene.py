#!/usr/bin/env python3
"""Writes bench_peers' N-sphere problem as a scene file, for `stiction check` and `run`.

Usage: bench/spheres_scene.py N [--integrator implicit] [--dt 1/60] > spheres.toml

The same spheres as `bench_peers --problems spheres` (bench/peers/stiction_peer.cpp's
spheres_scene, bench/peers/problems.hpp's SphereParams): N spheres (m = 0.3 kg, R = 0.2 m,
mu = 0.1, K = 1e7 N/m, B = 10 N s/m) in lanes 0.5 m apart on one plane, launched sliding at
v0 = 1 + 2 i / (N - 1) m/s, each sticking (rolling without slip) at 2 v0 / (7 mu g), spread
over 0.29-0.87 s. Every sphere is its own island (docs/limits.md).
"""
import argparse
import sys
from fractions import Fraction

MASS, RADIUS, MU, STIFFNESS, DAMPING, V0 = 0.3, 0.2, 0.1, 1e7, 10.0, 2.0
LANE = 0.5


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("count", type=int, help="number of spheres (>= 1)")
    parser.add_argument("--integrator", default="implicit")
    parser.add_argument("--dt", default="1/60", help="step, a number or a fraction such as 1/60")
    parser.add_argument("--duration", type=float, default=1.0)
    parser.add_argument("--output-rate", type=float, default=60.0,
                        help="rows per second (the bench reads every 1/60 s)")
    args = parser.parse_args()
    if args.count < 1:
        parser.error("count must be >= 1")
    dt = float(Fraction(args.dt))
    out = [
        f'name = "spheres_{args.count}"',
        f'description = "{args.count} spheres sliding to rolling on one plane, stick times '
        f'spread over 0.29-0.87 s"',
        "gravity = [0.0, 0.0, -9.81]",
        "",
        "[simulation]",
        f'integrator = "{args.integrator}"',
        f"dt = {dt!r}",
        f"duration = {args.duration!r}",
        f"output_rate = {args.output_rate!r}",
    ]
    n = args.count
    for i in range(n):
        v0 = V0 if n == 1 else 1.0 + 2.0 * i / (n - 1)
        name = f"s{i:04d}"
        out += [
            "",
            f"[bodies.{name}]",
            'type = "rigid_body"',
            f"mass = {MASS!r}",
            'shape = "sphere"',
            f"radius = {RADIUS!r}",
            f"position = [0.0, {LANE * i!r}, {RADIUS!r}]",
            f"velocity = [{v0!r}, 0.0, 0.0]",
            f"[impedances.{name}_ground]",
            'type = "kikuuwe_contact"',
            f'body = "{name}"',
            f"stiffness = {STIFFNESS!r}",
            f"damping = {DAMPING!r}",
            f"mu = {MU!r}",
            "settle = true",
        ]
    sys.stdout.write("\n".join(out) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
