#!/usr/bin/python3
"""examples/12_particles_mpi/make_raster.py writes the particles of examples/04_particles/
particles.geo without Gmsh: check that it writes the same ones. Meshes particles.geo with the
gmsh CLI at N (default 5) and compares, group by group (p0..p7), the particle triangles as
sets of vertex coordinates: the same number of triangles, and every generator triangle equal
to a Gmsh triangle to TOL = 1e-12 m per coordinate (so the same vertices, centres, fans and
group assignment). The walls are meshed differently (structured here) and only checked to
cover the same area.

Usage: raster_matches_gmsh.py GMSH REPO_ROOT WORKDIR [N]
Exit 0 with "OK: ..." when equal, 1 otherwise.
"""
import os
import subprocess
import sys

TOL = 1e-12


def read_msh22(path):
    """{physical name: [triangle as 3 (x, y)]} of an ASCII MSH 2.2 file."""
    with open(path) as f:
        lines = f.read().split("\n")
    sec = {lines[i]: i for i in range(len(lines)) if lines[i].startswith("$")}
    names = {}
    i = sec["$PhysicalNames"]
    for ln in lines[i + 2:i + 2 + int(lines[i + 1])]:
        dim, tag, name = ln.split(maxsplit=2)
        names[int(tag)] = name.strip('"')
    nodes = {}
    i = sec["$Nodes"]
    for ln in lines[i + 2:i + 2 + int(lines[i + 1])]:
        v, x, y, _ = ln.split()
        nodes[int(v)] = (float(x), float(y))
    groups = {}
    i = sec["$Elements"]
    for ln in lines[i + 2:i + 2 + int(lines[i + 1])]:
        w = [int(a) for a in ln.split()]
        if w[1] != 2:
            continue  # points and lines of the geometry
        ntags = w[2]
        tri = tuple(nodes[v] for v in w[3 + ntags:])
        groups.setdefault(names[w[3]], []).append(tri)
    return groups


def key(tri):
    """A triangle's vertices rotated to start at the smallest (orientation kept)."""
    s = min(range(3), key=lambda q: tri[q])
    return tri[s:] + tri[:s]


def area(tri):
    (x0, y0), (x1, y1), (x2, y2) = tri
    return 0.5 * ((x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0))


def main():
    if len(sys.argv) not in (4, 5):
        sys.exit(__doc__)
    gmsh, root, work = sys.argv[1:4]
    n = int(sys.argv[4]) if len(sys.argv) > 4 else 5
    os.makedirs(work, exist_ok=True)
    ref, gen = os.path.join(work, "gmsh.msh"), os.path.join(work, "raster.msh")
    subprocess.run([gmsh, "-2", "-format", "msh22", "-setnumber", "N", str(n),
                    os.path.join(root, "examples/04_particles/particles.geo"), "-o", ref],
                   check=True, stdout=subprocess.DEVNULL)
    subprocess.run([sys.executable, os.path.join(root, "examples/12_particles_mpi/make_raster.py"),
                    str(n), gen], check=True, stdout=subprocess.DEVNULL)
    a, b = read_msh22(ref), read_msh22(gen)
    fail = []
    if sorted(a) != sorted(b):
        fail.append(f"groups differ: gmsh {sorted(a)}, generator {sorted(b)}")
    worst = 0.0
    count = 0
    for g in sorted(set(a) & set(b)):
        if g == "walls":
            continue
        ta = sorted(key(t) for t in a[g])
        tb = sorted(key(t) for t in b[g])
        if len(ta) != len(tb):
            fail.append(f"group {g}: gmsh {len(ta)} triangles, generator {len(tb)}")
            continue
        for t in tb:
            if area(t) <= 0:
                fail.append(f"group {g}: generator triangle {t} is not counter-clockwise")
                break
        # match each generator triangle to the nearest Gmsh one (Gmsh may orient either way:
        # compare as vertex sets)
        pool = [sorted(t) for t in ta]
        for t in tb:
            st = sorted(t)
            d, j = min((max(abs(p[c] - q[c]) for p, q in zip(st, u) for c in (0, 1)), j)
                       for j, u in enumerate(pool))
            worst = max(worst, d)
            if d > TOL:
                fail.append(f"group {g}: generator triangle {t} is {d:.3g} m from every Gmsh one")
                break
            pool.pop(j)
            count += 1
    wa = sum(abs(area(t)) for t in a.get("walls", []))
    wb = sum(area(t) for t in b.get("walls", []))
    if abs(wa - wb) > 1e-9 * wa:
        fail.append(f"walls: area gmsh {wa!r} m^2, generator {wb!r} m^2")
    if fail:
        print("FAIL: " + "\nFAIL: ".join(fail))
        sys.exit(1)
    print(f"OK: N = {n}: {count} particle triangles in {len(a) - 1} groups equal Gmsh's from "
          f"particles.geo to {worst:.3g} m (tolerance {TOL:g} m); walls area {wb:.6g} m^2")


if __name__ == "__main__":
    main()
