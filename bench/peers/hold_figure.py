#!/usr/bin/env python3
"""Figures of the hold benchmark (issue 38) from bench_peers' CSV.

    build/bench/peers/bench_peers --problems ramp_grid,pinch --csv hold.csv
    python3 bench/peers/hold_figure.py hold.csv docs/hold_ramp_grid.png [docs/hold_pinch.png]

The ramp grid: one panel per engine and setting, the creep after settling (m/s, log scale)
against tan a / mu, one line per mu. The pinch (optional second PNG): creep against the
squeeze's holding margin, one line per engine and setting. A creep below FLOOR (stiction's
rounding-level or exactly zero creep) is drawn on the floor line, with its label saying so.
"""
import csv
import math
import sys
from collections import OrderedDict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

FLOOR = 1e-20  # m/s: creeps below this are drawn on it


def step_text(dt):
    n = 1.0 / dt
    p = math.log10(dt)
    if abs(p - round(p)) < 1e-9:
        return "1e%d s" % round(p)
    if abs(n - round(n)) < 1e-6 and abs(1e3 * dt - round(1e3 * dt)) > 1e-9:
        return "1/%d s" % round(n)
    return "%g s" % dt


def label(row):
    engine = row["engine"].replace(" (double)", "")
    settings = row["settings"]
    for long, short in (
        ("dWorldStep, soft contact", "dWorldStep"),
        ("defaults, sleeping off", "sleeping off"),
        (", default contact", ""),
        ("Dantzig LCP, DART collision", "Dantzig"),
    ):
        settings = settings.replace(long, short)
    return "%s %s, %s" % (engine, settings, step_text(float(row["dt"])))


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def ramp_figure(rows, out):
    panels = OrderedDict()  # label -> {mu: [(ratio, creep)]}
    for row in rows:
        if row["problem"] != "ramp_grid" or row["breakaway"] != "0":
            continue
        mu = float(row["mu"])
        ratio = math.tan(math.radians(float(row["angle_deg"]))) / mu
        creep = float(row["error1"])
        panels.setdefault(label(row), OrderedDict()).setdefault(mu, []).append((ratio, creep))
    if not panels:
        sys.exit("no ramp_grid rows in the CSV")
    columns = 4
    rows_n = math.ceil((len(panels) + 1) / columns)
    fig, axes = plt.subplots(rows_n, columns, figsize=(3.2 * columns, 2.7 * rows_n),
                             sharex=True, sharey=True, squeeze=False)
    mus = sorted({mu for series in panels.values() for mu in series})
    colours = plt.cm.viridis([i / max(1, len(mus) - 1) for i in range(len(mus))])
    top = max(c for s in panels.values() for pts in s.values() for _, c in pts if math.isfinite(c))
    for ax, (name, series) in zip(axes.flat, panels.items()):
        below = False
        for mu, points in series.items():
            points.sort()
            xs = [r for r, _ in points]
            ys = [max(c, FLOOR) if math.isfinite(c) else float("nan") for _, c in points]
            below |= any(c < FLOOR for _, c in points)
            ax.plot(xs, ys, "o-", ms=3, lw=1.2, color=colours[mus.index(mu)],
                    label="mu = %g" % mu)
        ax.set_yscale("log")
        ax.set_title(name, fontsize=8.5)
        ax.grid(True, which="major", lw=0.4, alpha=0.5)
        ax.axhline(FLOOR, color="0.6", lw=0.6, ls=":")
        if below:
            ax.text(0.04, 0.92, "dotted line: creep < %g m/s" % FLOOR, transform=ax.transAxes,
                    fontsize=7, color="0.3")
    ax_empty = list(axes.flat)[len(panels):]
    for ax in ax_empty:
        ax.axis("off")
    handles, labels = list(axes.flat)[0].get_legend_handles_labels()
    if ax_empty:
        ax_empty[0].legend(handles, labels, loc="center", fontsize=9,
                           title="ramp grid: box on a ramp", title_fontsize=9, frameon=False)
    else:
        fig.legend(handles, labels, loc="lower center", ncol=len(labels), fontsize=8)
    for ax in axes[-1]:
        ax.set_xlabel("tan a / mu (utilization)", fontsize=8)
    for ax in axes[:, 0]:
        ax.set_ylabel("creep after settling, m/s", fontsize=8)
    for ax in axes.flat:
        ax.tick_params(labelsize=7)
        ax.xaxis.set_tick_params(labelbottom=True)
    axes[0, 0].set_ylim(FLOOR / 10, max(top, 1e-3) * 10)
    fig.suptitle("Hold benchmark, ramp grid: creep of a box held by friction "
                 "(bench/peers, issue 38)", fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.97))
    fig.savefig(out, dpi=130)
    print("wrote", out)


def pinch_figure(rows, out):
    series = OrderedDict()
    for row in rows:
        if row["problem"] != "pinch":
            continue
        series.setdefault(label(row), []).append((float(row["margin"]), float(row["error1"])))
    if not series:
        sys.exit("no pinch rows in the CSV")
    fig, ax = plt.subplots(figsize=(8.5, 4.2))
    markers = "osD^v<>ph*X"
    below = False
    for k, (name, points) in enumerate(series.items()):
        points.sort()
        ys = [max(c, FLOOR) if math.isfinite(c) else float("nan") for _, c in points]
        below |= any(c < FLOOR for _, c in points)
        ax.plot([m for m, _ in points], ys, marker=markers[k % len(markers)], ms=4, lw=1.2,
                label=name, color=plt.cm.tab20((2 * k) % 20 + (2 * k) // 20))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xticks([1.1, 1.5, 2, 5, 20])
    ax.set_xticklabels(["1.1x", "1.5x", "2x", "5x", "20x"])
    ax.axhline(FLOOR, color="0.6", lw=0.6, ls=":")
    if below:
        ax.text(1.12, FLOOR * 3, "floor: creep < %g m/s" % FLOOR, fontsize=7, color="0.3")
    ax.set_ylim(FLOOR / 10, None)
    ax.set_xlabel("squeeze / the force that just holds (holding margin)")
    ax.set_ylabel("creep after settling, m/s")
    ax.set_title("Hold benchmark, pinch: a block between two fingers under gravity", fontsize=10)
    ax.grid(True, which="major", lw=0.4, alpha=0.5)
    ax.legend(fontsize=7.5, loc="center left", bbox_to_anchor=(1.01, 0.5), frameon=False)
    fig.tight_layout()
    fig.savefig(out, dpi=130)
    print("wrote", out)


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    rows = read(sys.argv[1])
    ramp_figure(rows, sys.argv[2])
    if len(sys.argv) == 4:
        pinch_figure(rows, sys.argv[3])


if __name__ == "__main__":
    main()
