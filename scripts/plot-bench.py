#!/usr/bin/env python3
"""Plots `preskin bench` JSON: median frame time against light count, clustered against brute
force (both axes logarithmic), one curve per light loop the run measured.

    scripts/plot-bench.py docs/bench-lavapipe.json docs/bench-lavapipe.png

Reads the `light_loop` rows (lights, clustered.wall_ms, brute_force.wall_ms); rows with 0 lights
have no place on a log axis and are left out. Bad input ends with one line
`plot-bench: error: <file>: <problem>` and exit status 1; the PNG is written atomically.
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")  # headless: no display needed
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import ScalarFormatter  # noqa: E402


def fail(path, problem):
    print(f"plot-bench: error: {path}: {problem}", file=sys.stderr)
    sys.exit(1)


def curves(bench, path):
    rows = bench.get("light_loop")
    if not isinstance(rows, list) or not rows:
        fail(path, "light_loop: no rows (was the bench run with --counts?)")
    series = {"clustered": [], "brute_force": []}
    for i, row in enumerate(rows):
        try:
            lights = float(row["lights"])
            if lights <= 0:
                continue
            for loop, points in series.items():
                if isinstance(row.get(loop), dict) and row[loop].get("wall_ms") is not None:
                    points.append((lights, float(row[loop]["wall_ms"])))
        except (KeyError, TypeError, ValueError) as e:
            fail(path, f"light_loop[{i}]: {e}")
    return {loop: sorted(points) for loop, points in series.items() if points}


def main():
    if len(sys.argv) != 3:
        print("usage: plot-bench.py BENCH.json OUT.png", file=sys.stderr)
        sys.exit(1)
    source, out = sys.argv[1], sys.argv[2]
    try:
        with open(source, encoding="utf-8") as f:
            bench = json.load(f)
    except (OSError, ValueError) as e:
        fail(source, e)
    data = curves(bench, source)
    if not data:
        fail(source, "light_loop: no row with lights > 0 and a wall_ms")

    labels = {"clustered": "clustered", "brute_force": "brute force (every light)"}
    fig, ax = plt.subplots(figsize=(8, 5), dpi=125)
    for loop, points in data.items():
        ax.plot([p[0] for p in points], [p[1] for p in points], marker="o", label=labels[loop])
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    for axis in (ax.xaxis, ax.yaxis):
        axis.set_major_formatter(ScalarFormatter())
    ax.set_xticks(sorted({p[0] for points in data.values() for p in points}))
    ax.set_xlabel("lights")
    ax.set_ylabel("frame time, ms (median wall clock)")
    ax.set_title(f"preskin bench: {bench.get('width', '?')}x{bench.get('height', '?')}, {bench.get('device', '?')}")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    tmp = out + ".tmp.png"
    try:
        fig.savefig(tmp)
        os.replace(tmp, out)
    except OSError as e:
        if os.path.exists(tmp):
            os.remove(tmp)
        fail(out, e)


if __name__ == "__main__":
    main()
