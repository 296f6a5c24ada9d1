#!/usr/bin/python3
"""A design map: the theory's outcome and jump height over a grid of (h, net weight) poppers,
all of them in one call of the vectorised snapjump.predict.

    cmake --build build --target _snapjump snapjump_python_files    # the module, in build/python
    PYTHONPATH=build/python /usr/bin/python3 examples/python/design_grid.py [--n 100] [--out FILE]

With matplotlib (Debian: apt-get install python3-matplotlib) it draws FILE (design_grid.png);
without it, it writes the grid as a CSV table (design_grid.csv) and says so.
"""
import argparse
import csv
import sys

import numpy as np

import snapjump


def design_grid(n):
    """The theory over n x n designs: the paper's R = 30 mm cap, h from 1 to 3 mm, net weight from
    0.1 to 2 N. Returns (h [m], net weight [N], the prediction's dict of (n, n) arrays)."""
    h = np.linspace(1e-3, 3e-3, n)
    mg = np.linspace(0.1, 2.0, n)
    p = snapjump.predict(R="30 mm", h=h[None, :], net_weight=mg[:, None])
    return h, mg, p


def write_csv(path, h, mg, p):
    q = p["quantities"]
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["h [m]", "net_weight [N]", "outcome", "F_star_lower [N]", "F_star_upper [N]",
                    "H_lower [m]", "H_upper [m]"])
        for i in range(len(mg)):
            for j in range(len(h)):
                w.writerow([repr(h[j]), repr(mg[i]), p["outcome"][i, j],
                            *(repr(float(q[k][end][i, j])) for k in ("F_star", "H")
                              for end in ("lower", "upper"))])


def draw(path, h, mg, p, plt):
    outcomes = sorted(set(p["outcome"].ravel()))
    code = np.vectorize(outcomes.index)(p["outcome"])
    fig, ax = plt.subplots(figsize=(7, 5))
    extent = [1e3 * h[0], 1e3 * h[-1], mg[0], mg[-1]]
    image = ax.imshow(code, origin="lower", aspect="auto", extent=extent,
                      cmap=plt.get_cmap("Pastel1", len(outcomes)),
                      vmin=-0.5, vmax=len(outcomes) - 0.5)
    bar = fig.colorbar(image, ticks=range(len(outcomes)))
    bar.ax.set_yticklabels(outcomes)
    H = 1e3 * p["quantities"]["H"]["upper"]
    lines = ax.contour(1e3 * h, mg, np.where(np.isfinite(H), H, np.nan), colors="k",
                       linewidths=0.8)
    ax.clabel(lines, fmt="%.0f mm")
    ax.set_xlabel("shell thickness h [mm] (R = 30 mm)")
    ax.set_ylabel("net weight mg [N]")
    ax.set_title("predicted outcome; contours: upper bound of the height H")
    fig.savefig(path, dpi=120)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=100, help="designs along each axis (100)")
    parser.add_argument("--out", help="the figure (design_grid.png) or, without matplotlib, "
                                      "the table (design_grid.csv)")
    args = parser.parse_args(argv)
    h, mg, p = design_grid(args.n)
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        out = args.out or "design_grid.csv"
        write_csv(out, h, mg, p)
        print(f"no matplotlib (apt-get install python3-matplotlib for the figure): "
              f"wrote the {args.n} x {args.n} designs to {out}")
        return 0
    out = args.out or "design_grid.png"
    draw(out, h, mg, p, plt)
    print(f"figure {out}: {args.n} x {args.n} designs")
    return 0


if __name__ == "__main__":
    sys.exit(main())
