#!/usr/bin/env python3
"""Per-element stable steps of a quadratic tetrahedral mesh, and what subcycling could save.

Usage: scripts/step_classes.py MESH.msh [MESH.msh ...]   (gmsh 4.1 ASCII, as `snapjump mesh` writes)

An explicit element's stable step is proportional to its smallest node distance (the 3D body's
rule: dt = factor * spacing / p-wave speed). Each element is put in the power-of-two class of its
step against the mesh's smallest; a multi-time-step scheme that steps class c every 2^c fine
steps does sum(2^-c) element updates per fine step instead of one per element. The printed ratio
is that work over the single step's: the most such a scheme could save on the elements.
"""
import math
import statistics
import sys


def read_msh(path):
    lines = open(path).read().split("\n")
    i = lines.index("$Nodes")
    blocks = int(lines[i + 1].split()[0])
    i += 2
    nodes = {}
    for _ in range(blocks):
        n = int(lines[i].split()[3])
        tags = [int(lines[i + 1 + k]) for k in range(n)]
        for k in range(n):
            nodes[tags[k]] = [float(v) for v in lines[i + 1 + n + k].split()]
        i += 1 + 2 * n
    i = lines.index("$Elements")
    blocks = int(lines[i + 1].split()[0])
    i += 2
    tets = []
    for _ in range(blocks):
        _, _, kind, n = map(int, lines[i].split())
        if kind == 11:  # 10-node tetrahedron
            tets += [[int(v) for v in lines[i + 1 + k].split()[1:]] for k in range(n)]
        i += 1 + n
    return nodes, tets


def main(paths):
    for path in paths:
        nodes, tets = read_msh(path)
        spacing = []
        for t in tets:
            p = [nodes[a] for a in t]
            spacing.append(min(math.dist(p[a], p[b]) for a in range(10) for b in range(a)))
        smallest = min(spacing)
        cls = [int(math.floor(math.log2(s / smallest) + 1e-9)) for s in spacing]
        print(f"{path}: {len(spacing)} elements, smallest node spacing {1e3 * smallest:.3f} mm, "
              f"median {1e3 * statistics.median(spacing):.3f} mm")
        for c in range(max(cls) + 1):
            share = 100 * sum(1 for k in cls if k == c) / len(cls)
            print(f"  step {2 ** c} x the smallest: {share:.1f} % of the elements")
        ratio = sum(0.5**k for k in cls) / len(cls)
        print(f"  element work with power-of-two subcycling / with one step: {ratio:.3f}")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
