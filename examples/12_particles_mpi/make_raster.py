#!/usr/bin/python3
"""Write the N x N particle raster of examples/04_particles/particles.geo as an MSH 2.2 file.

Usage: /usr/bin/python3 make_raster.py N OUT.msh [--order morton|rows]

Gmsh needs minutes and gigabytes to read particles.geo at N = 316 (~10^5 particles), although
every particle is only k = 5..8 triangles fanned from its centre: this script computes the same
points with the same formulas and writes the triangles directly (N = 316 in a few seconds).
The particle vertices are those of particles.geo: the hash fract(|sin(x)| * c) of the particle
index gives the vertex count k, the start angle, and per vertex the angle jitter and the radius,
evaluated in the same double arithmetic, in the same order, with the C library's sin/cos as Gmsh
does (math.sin, not numpy.sin, whose vectorised kernels may differ in the last bit; the hash
multiplies that bit by ~4e4). Test: tests/example/raster_matches_gmsh.py (N = 5, to 1e-12 m).

Order: the particles (their nodes and triangles) are written along a Z-order (Morton) curve of
their raster cells by default, so that consecutive ids are near in space: fdem numbers nodes and
triangles in file order within each [[body]] entry (group), and a distributed run owns nodes
in groups of 64 consecutive ids and runs element chunks of 256 consecutive triangles
(docs/parallel.md). At N = 316 on 4 parts `fdem decompose` counts 11.8 % redundant element work
and 22 060 ghost nodes per part at t = 0 in Morton order, 100.8 % and 188 690 in row order
(`--order rows`, particles.geo's order). The particles are the same either way.

Groups: physical surfaces "p0".."p7" (a particle's group by hash, as particles.geo) and "walls":
a ring of thickness T = 0.02 m around [0, N s]^2, meshed here on a structured 5 mm grid (each
square cut into two triangles). particles.geo meshes the ring with Gmsh's unstructured mesher,
so only the walls differ from example 04. All triangles are counter-clockwise. Element tags are
(physical, elementary) = (group tag, group tag): one elementary entity per group, so that the
Gmsh library that fdem reads the file with does not create 10^5 entities.
"""
import math
import sys

S = 0.01  # raster pitch [m]
R = 0.0045  # largest vertex distance from the raster point [m]
T = 0.02  # wall thickness [m]
LW = 0.005  # wall mesh size [m]
PI = 3.1415926535897932  # Gmsh's Pi


def fract_hash(x, c):
    h = abs(math.sin(x) * c)
    return h - math.floor(h)


def particle(n, i, j):
    """Centre, vertices (counter-clockwise) and group of particle (i, j) of an n x n raster,
    each expression as particles.geo writes it (Gmsh evaluates left to right in doubles)."""
    pid = j * n + i
    cx = (i + 0.5) * S
    cy = (j + 0.5) * S
    k = 5 + math.floor(fract_hash(pid * 12.9898 + 78.233, 43758.5453) * 4)
    a0 = 2 * PI * fract_hash(pid * 39.3468 + 11.135, 24634.6345)
    verts = []
    for q in range(k):
        u = fract_hash(pid * 7.233 + q * 91.17 + 3.1, 15731.743)
        a = a0 + 2 * PI * (q + 0.4 * (u - 0.5)) / k
        u = fract_hash(pid * 5.977 + q * 63.71 + 9.4, 31337.113)
        r = R * (0.6 + 0.4 * u)
        verts.append((cx + r * math.cos(a), cy + r * math.sin(a)))
    g = math.floor(fract_hash(pid * 3.7719 + 45.21, 12345.678) * 8)
    return (cx, cy), verts, g


def wall_ring(n):
    """Structured triangles of the ring [-T, W + T]^2 minus [0, W]^2 (W = n S), size LW.
    Returns the grid points it uses (dict (ix, iy) -> (x, y)) and the triangles as index pairs.
    The squares' diagonals point to the corners of the box in each quadrant: an inner corner
    node is then in 4 triangles (mass 2/3 rho LW^2) instead of 5 with one diagonal direction
    everywhere; the heaviest wall node facing the grains enters the contact time step bound
    (contact_stable_dt: heaviest target over lightest contactor node)."""
    m_t = round(T / LW)  # cells across the wall
    m_w = round(n * S / LW)  # cells along the inner side
    m = m_w + 2 * m_t
    tris = []
    for iy in range(m):
        for ix in range(m):
            if m_t <= ix < m_t + m_w and m_t <= iy < m_t + m_w:
                continue  # inside the box
            a, b, c, d = (ix, iy), (ix + 1, iy), (ix + 1, iy + 1), (ix, iy + 1)
            if (2 * ix + 1 - m) * (2 * iy + 1 - m) > 0:  # lower-left, upper-right quadrant
                tris += [(a, b, c), (a, c, d)]
            else:
                tris += [(a, b, d), (b, c, d)]
    used = sorted({p for t in tris for p in t}, key=lambda p: (p[1], p[0]))
    # grid line l lies at (l - m_t) * LW; the inner sides at exactly 0 and n S
    def coord(l):
        return 0.0 if l == m_t else (n * S if l == m_t + m_w else (l - m_t) * LW)
    return {p: (coord(p[0]), coord(p[1])) for p in used}, tris


def morton(i, j):
    """Z-order index of raster cell (i, j): the bits of i and j interleaved."""
    z = 0
    for b in range(16):
        z |= ((i >> b) & 1) << (2 * b) | ((j >> b) & 1) << (2 * b + 1)
    return z


def write_msh(n, path, order="morton"):
    names = ["walls"] + [f"p{g}" for g in range(8)]  # physical tags 1..9
    nodes = []  # (x, y)
    elems = []  # (tag, n1, n2, n3), node ids 1-based
    cells = [(i, j) for j in range(n) for i in range(n)]
    if order == "morton":
        cells.sort(key=lambda c: morton(*c))
    for i, j in cells:
        (cx, cy), verts, g = particle(n, i, j)
        c = len(nodes) + 1
        nodes.append((cx, cy))
        nodes.extend(verts)
        k = len(verts)
        for q in range(k):
            elems.append((g + 2, c, c + 1 + q, c + 1 + (q + 1) % k))
    pts, tris = wall_ring(n)
    ids = {}
    for p, xy in pts.items():
        nodes.append(xy)
        ids[p] = len(nodes)
    for a, b, c in tris:
        elems.append((1, ids[a], ids[b], ids[c]))
    with open(path, "w") as f:  # repr(float): the shortest string that reads back the same
        f.write(f"$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n{len(names)}\n")
        f.writelines(f'2 {t + 1} "{name}"\n' for t, name in enumerate(names))
        f.write(f"$EndPhysicalNames\n$Nodes\n{len(nodes)}\n")
        f.writelines(f"{v} {x!r} {y!r} 0\n" for v, (x, y) in enumerate(nodes, 1))
        f.write(f"$EndNodes\n$Elements\n{len(elems)}\n")
        f.writelines(f"{e} 2 2 {t} {t} {a} {b} {c}\n" for e, (t, a, b, c) in enumerate(elems, 1))
        f.write("$EndElements\n")
    return n * n, len(nodes), len(elems)


def main():
    args = sys.argv[1:]
    order = "morton"
    if len(args) == 4 and args[2] == "--order" and args[3] in ("morton", "rows"):
        order = args[3]
        args = args[:2]
    if len(args) != 2:
        sys.exit(__doc__)
    n = int(args[0])
    if n < 1:
        sys.exit("N must be >= 1")
    particles, nodes, tris = write_msh(n, args[1], order)
    print(f"{sys.argv[2]}: {particles} particles, {nodes} nodes, {tris} triangles")


if __name__ == "__main__":
    main()
