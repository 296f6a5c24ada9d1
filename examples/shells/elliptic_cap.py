#!/usr/bin/python3
"""A designer's own shell for snapjump: an elliptic (spheroidal) cap, made with gmsh's Python API
(Debian: apt-get install python3-gmsh; run it with Debian's /usr/bin/python3).

The mid-surface is the spheroid x^2/a^2 + y^2/a^2 + z^2/c^2 = 1 with a = 32 mm, c = 28 mm (flatter
at the apex than a sphere: its radius of curvature there is a^2/c = 36.6 mm, at the rim about
30 mm), the shell 2 mm thick (outer and inner spheroids 1 mm out and in along the axes), cut by the
plane 24 mm above the apex. The apex points down (-z); the rim face is the cut.

Physical groups, as snapjump reads them (docs/shells.md):
  shell   (volume)   the elastic body, quadratic tetrahedra
  inner   (surface)  the pressurised inner surface
  clamped (surface)  the rim face glued to the container
  outer   (surface)  the surface that meets the plate

    /usr/bin/python3 examples/shells/elliptic_cap.py examples/shells/elliptic.msh [SIZE_mm]
    build/snapjump run examples/shells/elliptic.toml --resolution coarse
"""
import sys

import gmsh

A, C, H = 32e-3, 28e-3, 2e-3  # mid-surface semi-axes, thickness [m]
DEPTH = 24e-3  # the cut, above the apex [m]


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "elliptic.msh"
    size = float(sys.argv[2]) * 1e-3 if len(sys.argv) > 2 else 4e-3
    # readConfigFiles=False: no ~/.gmshrc (a script) runs here either.
    gmsh.initialize(readConfigFiles=False)
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("elliptic_cap")
    occ = gmsh.model.occ

    def spheroid(da):
        s = occ.addSphere(0, 0, 0, 1.0)
        occ.dilate([(3, s)], 0, 0, 0, A + da, A + da, C + da)
        return s

    outer, inner = spheroid(H / 2), spheroid(-H / 2)
    shell, _ = occ.cut([(3, outer)], [(3, inner)])
    z_cut = -C + DEPTH
    big = 2 * (A + H)
    box = occ.addBox(-big, -big, -C - H, 2 * big, 2 * big, z_cut + C + H)
    cap, _ = occ.intersect(shell, [(3, box)])
    occ.synchronize()

    volumes = [tag for dim, tag in cap if dim == 3]
    groups = {"inner": [], "clamped": [], "outer": []}
    for _, surface in gmsh.model.getBoundary([(3, v) for v in volumes], oriented=False):
        x0, y0, z0, x1, y1, z1 = gmsh.model.getBoundingBox(2, surface)
        if abs(z1 - z0) < 1e-4 and abs(z0 - z_cut) < 1e-4:
            groups["clamped"].append(surface)  # the flat rim face
        elif z0 < -C - H / 4:
            groups["outer"].append(surface)  # reaches down to the outer apex, -(C + H/2)
        else:
            groups["inner"].append(surface)
    for name, tags in groups.items():
        if not tags:
            raise SystemExit(f"no surface found for the group '{name}'")
        gmsh.model.setPhysicalName(2, gmsh.model.addPhysicalGroup(2, tags), name)
    gmsh.model.setPhysicalName(3, gmsh.model.addPhysicalGroup(3, volumes), "shell")

    gmsh.option.setNumber("Mesh.MeshSizeMax", size)
    gmsh.option.setNumber("Mesh.MeshSizeMin", size / 4)
    gmsh.option.setNumber("Mesh.ElementOrder", 2)
    gmsh.option.setNumber("Mesh.HighOrderOptimize", 1)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.model.mesh.generate(3)
    gmsh.write(out)
    _, tets, _ = gmsh.model.mesh.getElements(3)
    print(f"wrote {out}: {sum(len(t) for t in tets)} quadratic tetrahedra; groups "
          + ", ".join(f"{k} ({len(v)} surfaces)" for k, v in groups.items()) + ", shell")
    gmsh.finalize()


if __name__ == "__main__":
    main()
