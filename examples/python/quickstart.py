#!/usr/bin/python3
"""snapjump from Python: predict a popper, simulate a short axisymmetric jump, plot it.

    make test        (or cmake --build build) builds the module into build/python
    PYTHONPATH=build/python /usr/bin/python3 examples/python/quickstart.py [OUT.png]

The plot needs matplotlib (Debian: apt-get install python3-matplotlib).
"""
import sys

import snapjump

# The theory for the paper's Fig. 2(a) popper, with units as on the command line.
p = snapjump.predict(R="30 mm", h="2 mm", net_weight="0.48 N")
q = p["quantities"]
print(f"predicted: {p['outcome_text']}; F* {q['F_star']['lower']:.3g} .. {q['F_star']['upper']:.3g} N,"
      f" H {1e3 * q['H']['lower']:.3g} .. {1e3 * q['H']['upper']:.3g} mm")

# The simulated jump: the axisymmetric model at its coarse preset takes about half a minute.
folder = snapjump.run(R="30 mm", h="2 mm", net_weight="0.48 N", model="axisymmetric",
                      resolution="coarse", progress=print)
run = snapjump.read_run(folder)
m = run["summary"]["measured"]
print("simulated:", m["outcome"], "F*", m["quantities"]["F_star"]["value"], "N")

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    sys.exit("no matplotlib: apt-get install python3-matplotlib to draw the figure")
s = run["series"]
fig, ax = plt.subplots(2, 1, sharex=True, figsize=(7, 6))
ax[0].plot(1e3 * s["t"], 1e3 * s["z"])
ax[0].set_ylabel("container height z [mm]")
ax[1].plot(1e3 * s["t"], s["F"])
ax[1].set_ylabel("plate force F [N]")
ax[1].set_xlabel("t after release [ms]")
out = sys.argv[1] if len(sys.argv) > 1 else "quickstart.png"
fig.savefig(out, dpi=120)
print("figure", out)
