#!/usr/bin/env python3
"""The largest running mean of a run's plate force F around its snap.

For each run folder given, reads series.csv and summary.json (t_onset, t_launch) and prints F*
and the largest running mean of F over 1 ms and 2 ms windows, from 10 ms before the onset to the
launch (docs/axisymmetric.md, where the axisymmetric and the 3D F* are compared).

    scripts/running_mean_peak.py RUN_DIR [RUN_DIR ...]
"""
import csv
import json
import sys


def peak_means(run_dir, windows=(1e-3, 2e-3)):
    with open(f"{run_dir}/series.csv") as f:
        rows = list(csv.reader(line for line in f if not line.startswith("#")))
    head, data = rows[0], rows[1:]
    t = [float(r[head.index("t")]) for r in data]
    F = [float(r[head.index("F")]) for r in data]
    with open(f"{run_dir}/summary.json") as f:
        q = json.load(f)["measured"]["quantities"]
    if "t_onset" not in q:
        raise SystemExit(f"{run_dir}: no onset in summary.json")
    t0 = q["t_onset"]["value"]
    t1 = q.get("t_launch", {}).get("value", t0 + 0.05)
    dt = (t[-1] - t[0]) / (len(t) - 1)
    out = []
    for w in windows:
        n = max(1, round(w / dt))
        best = 0.0
        for i, ti in enumerate(t):
            if t0 - 0.01 <= ti <= t1:
                lo = max(0, i - n // 2)
                hi = min(len(F), lo + n)
                best = max(best, sum(F[lo:hi]) / (hi - lo))
        out.append(best)
    return q["F_star"]["value"], out


if __name__ == "__main__":
    if len(sys.argv) < 2:
        raise SystemExit(__doc__)
    for d in sys.argv[1:]:
        f_star, means = peak_means(d)
        print(f"{d}: F* {f_star:.3f} N, largest 1 ms mean {means[0]:.3f} N, 2 ms mean {means[1]:.3f} N")
