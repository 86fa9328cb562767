#!/usr/bin/python3
"""Write a brick-bond pack of N two-triangle blocks as a scenario (issue #16 item 4: loading).

    make_pack_scenario.py DIR N [--mode groups|separate] [--gap G] [--closing V] [--end-time T]

DIR/pack.msh (MSH 2.2 ASCII) holds N rectangular blocks of two triangles each, in rows of
ceil(sqrt(N)) blocks laid in brick bond (every other row shifted by half a block), 1 mm apart.
DIR/scenario.toml loads them:
  groups   (default): one surface physical group "b<i>" per block and one [[body]] entry per
           block, each with its own velocity (N entries);
  separate: one physical group "pack" and one [[body]] entry with pieces = "separate"
           (N pieces of one entry).
Velocities are deterministic (no randomness): entry i moves at (0.1 sin i, 0.1 cos i) m/s.
--gap G: G m between blocks instead of 1 mm (0: touching). --closing V (groups only): the pack
converges on its centre instead, neighbours closing at V m/s (a block at c moves at
-V (c - centre) / spacing per axis), so that every block soon presses on all its neighbours
(the contact-saturated pack of issue #16, as a scenario). --end-time T: instead of 1 ms.
"""
import math
import os
import sys

W, H = 0.2, 0.1  # block width and height [m]


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    out, n = argv[1], int(argv[2])
    mode, gap, closing, end_time = "groups", 1e-3, None, 1e-3  # gap between blocks [m]
    rest = argv[3:]
    while rest:
        if len(rest) < 2:
            sys.exit(__doc__)
        key, val = rest[0], rest[1]
        rest = rest[2:]
        if key == "--mode" and val in ("groups", "separate"):
            mode = val
        elif key == "--gap":
            gap = float(val)
        elif key == "--closing":
            closing = float(val)
        elif key == "--end-time":
            end_time = float(val)
        else:
            sys.exit(__doc__)
    if closing is not None and mode != "groups":
        sys.exit("--closing needs --mode groups (one velocity per block)")
    GAP = gap
    os.makedirs(out, exist_ok=True)
    per_row = max(1, math.ceil(math.sqrt(n)))
    rows = math.ceil(n / per_row)
    # the pack's centre (of the block centres, rows shifted alike on average)
    cx = 0.5 * ((per_row - 1) * (W + GAP) + 0.25 * (W + GAP) * (rows > 1)) + 0.5 * W
    cy = 0.5 * (rows - 1) * (H + GAP) + 0.5 * H
    centres = []
    nodes, tris = [], []
    for i in range(n):
        row, col = divmod(i, per_row)
        x0 = col * (W + GAP) + (0.5 * (W + GAP) if row % 2 else 0.0)
        y0 = row * (H + GAP)
        b = len(nodes)
        centres.append((x0 + 0.5 * W, y0 + 0.5 * H))
        nodes += [(x0, y0), (x0 + W, y0), (x0 + W, y0 + H), (x0, y0 + H)]
        # two counter-clockwise triangles per block, corners as 1-based node ids
        tris += [(i, b + 1, b + 2, b + 3), (i, b + 1, b + 3, b + 4)]
    with open(os.path.join(out, "pack.msh"), "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n")
        if mode == "groups":
            f.write(f"{n}\n")
            for i in range(n):
                f.write(f'2 {i + 1} "b{i}"\n')
        else:
            f.write('1\n2 1 "pack"\n')
        f.write(f"$EndPhysicalNames\n$Nodes\n{len(nodes)}\n")
        for k, (x, y) in enumerate(nodes):
            f.write(f"{k + 1} {x!r} {y!r} 0\n")
        f.write(f"$EndNodes\n$Elements\n{len(tris)}\n")
        for k, (i, a, b, c) in enumerate(tris):
            phys = i + 1 if mode == "groups" else 1
            # type 2 (3-node triangle), 2 tags: physical, elementary (one entity per block)
            f.write(f"{k + 1} 2 2 {phys} {i + 1} {a} {b} {c}\n")
        f.write("$EndElements\n")
    with open(os.path.join(out, "scenario.toml"), "w") as f:
        f.write(f"# {n} two-triangle blocks in brick bond, written by "
                f"tests/loading/make_pack_scenario.py ({mode})\n")
        f.write(f'[simulation]\nend_time = {end_time!r}\ndt = "auto"\n\n')
        f.write('[output]\nvtu = false\nbodies = false\n\n')
        f.write('[[material]]\nname = "rock"\ndensity = 2500\nyoungs_modulus = 1e9\n'
                'poisson_ratio = 0.25\n\n')
        if mode == "groups":
            for i in range(n):
                vx, vy = 0.1 * math.sin(i), 0.1 * math.cos(i)
                if closing is not None:
                    vx = -closing * (centres[i][0] - cx) / (W + GAP)
                    vy = -closing * (centres[i][1] - cy) / (H + GAP)
                f.write(f'[[body]]\nname = "b{i}"\nmesh = "pack.msh"\ngroup = "b{i}"\n'
                        f'material = "rock"\nvelocity = [{vx!r}, {vy!r}]\n\n')
        else:
            f.write('[[body]]\nname = "pack"\nmesh = "pack.msh"\ngroup = "pack"\n'
                    'material = "rock"\npieces = "separate"\nvelocity = [0.1, 0.0]\n')


if __name__ == "__main__":
    main(sys.argv)
