#!/usr/bin/env python3
"""Writes a synthetic force-plate record of a popper's jump, as a lab's software would log it:
each sensor on its own clock in one merged file (empty cells for the others), ';' separators
with decimal commas, quoted headers with units in parentheses, a laser dropout, plate noise and
the plate's 170 Hz ring-down after the launch and the landing. The truth it was made from is
printed, so that `snapjump analyze` can be checked against it.

    python3 examples/records/synthetic_lab_record.py record.csv
    build/snapjump analyze record.csv --R 30mm
"""
import math
import random
import sys

G = 9.80665
MG, F_STAR = 0.48, 1.6            # net weight, snap force [N]
T_ON, T_FALL, T_LAND = 0.500, 0.511, 0.700   # onset, launch (F reaches 0), landing [s]
V0, H_L = 0.8, 15e-3              # take-off speed [m/s], container height at the onset [m]
T_END = 0.9


def force(t):
    if t < T_ON - 1e-3:
        f = MG
    elif t < T_ON + 1e-3:
        f = MG + (F_STAR - MG) * (t - T_ON + 1e-3) / 2e-3
    elif t < T_FALL:
        f = F_STAR * (1.0 - (t - T_ON - 1e-3) / 10e-3)
    elif t < T_LAND:
        f = 0.0
    elif t < T_LAND + 1e-3:
        f = 3.0 * (t - T_LAND) / 1e-3
    elif t < T_LAND + 2e-3:
        f = 3.0 - (3.0 - MG) * (t - T_LAND - 1e-3) / 1e-3
    else:
        f = MG
    for start in (T_FALL, T_LAND + 2e-3):  # the plate rings at 170 Hz
        if t >= start:
            s = t - start
            f += 0.1 * math.exp(-s / 10e-3) * math.sin(2 * math.pi * 170 * s)
    return f


def height(t):
    if t < T_ON - 0.1:
        return 0.0
    if t < T_ON:
        return H_L * (t - T_ON + 0.1) / 0.1
    if T_FALL <= t < T_LAND:
        s = t - T_FALL
        return H_L + max(0.0, V0 * s - 0.5 * G * s * s)
    return H_L


def gap(t):
    return max(0.0, 0.9e-3 + 5e-3 * (T_ON - t) / 0.1)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "record.csv"
    rnd = random.Random(7)
    rows = {}  # time in ns -> [F, z, w, dp]

    def put(t, k, v):
        rows.setdefault(round(t * 1e9), [None] * 4)[k] = v

    i = 0
    while i * 2e-4 <= T_END:  # the plate at 5 kHz
        t = i * 2e-4
        put(t, 0, force(t) + rnd.gauss(0, 5e-3))
        i += 1
    i = 0
    while 1e-4 + i / 3000 <= T_END:  # the lasers at 3 kHz, another clock
        t = 1e-4 + i / 3000
        put(t, 1, 1e3 * (height(t) + rnd.gauss(0, 0.02e-3)))
        if not 0.400 < t < 0.403:  # a dropout of the apex laser
            put(t, 2, 1e3 * (gap(t) + rnd.gauss(0, 0.02e-3)))
        i += 1
    i = 0
    while i / 400 <= T_END:  # the pressure at 400 Hz
        t = i / 400
        put(t, 3, (2000.0 - 4000.0 * t) / 1e3)
        i += 1
    with open(out, "w") as f:
        f.write('"Time (s)";"Fz (N)";"z (mm)";"w (mm)";"dp (kPa)"\n')
        for ns in sorted(rows):
            cells = ["%.7f" % (ns * 1e-9)] + ["" if v is None else "%.6g" % v for v in rows[ns]]
            f.write(";".join(cells).replace(".", ",") + "\n")
    H = H_L + V0 * V0 / (2 * G)
    print(f"wrote {out}: onset {T_ON*1e3:.1f} ms, F* {F_STAR} N, launch {T_FALL*1e3:.1f} ms "
          f"(t* {1e3*(T_FALL-T_ON):.1f} ms), H {H*1e3:.2f} mm, H_l {H_L*1e3:.1f} mm, "
          f"landing {T_LAND*1e3:.0f} ms")


if __name__ == "__main__":
    main()
