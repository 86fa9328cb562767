#!/usr/bin/python3
"""Example 11: impact fragmentation (spec V8). Runs fdem for several impact velocities and mesh seeds, writes the fragment statistics.

Usage (from the repository root, after building):
    /usr/bin/python3 examples/11_impact_fragmentation/run.py           # default: mesh 5 mm, 5/10/20/40 m/s, seed 1
    /usr/bin/python3 examples/11_impact_fragmentation/run.py --full    # spec V8: mesh 5 mm, 5/10/20/40 m/s, seeds 1-3
    /usr/bin/python3 examples/11_impact_fragmentation/run.py --fine    # as --full with mesh 2.5 mm (~8x the cost)
    /usr/bin/python3 examples/11_impact_fragmentation/run.py --quick   # CTest `validation`: mesh 5 mm, 10/40 m/s, seed 1
Options: --ring (also the expanding ring), --velocities 5,40 and --seeds 1,2 override the sets, --after T (simulated time after the
contact starts, s), --out DIR (default out/11_impact_fragmentation[_full|_fine|_quick]), --fdem PATH
(default build/release/fdem), --threads N (default 1), --check (exit 1 when a spec V8 target is
missed), --no-run (post-process existing runs), --validate DIR (write DIR/checks_impact.csv).

A disc D = 0.1 m of rock, every internal edge a cohesive joint, falls at v onto a fixed plate
(undamped). Per run (OUT/v<V>_s<S>/): fdem's files. Writes:
  OUT/sizes.csv      every disc fragment at the end of every run: v, seed, fragment id,
                     triangles, mass, equivalent diameter, cumulative mass fraction (sorted by size)
  OUT/sizes.png      cumulative mass fraction against fragment size, one curve per velocity
  OUT/summary.csv    per run and per velocity (seed mean): fragment count, largest-fragment mass
                     fraction, single-triangle fragments (count fraction and mass fraction),
                     energy error / KE0, mass error, broken joints, fracture work, run time
  OUT/summary.png    fragment count and largest fraction against v
  OUT/fragments.png  the fragments at the end (seed 1 of every velocity), coloured by fragment
  OUT/ring/          with --ring, --full, --fine: the expanding ring of ring.toml at r = 30, 100,
                     300 1/s (OUT/ring/r<R>/), ring_study.csv and ring_study.png: mean fragment
                     length against r, with the cohesive-model fit and Grady's estimate
and prints the numbers. Targets (spec fracture.md §11 V8): sum of the fragment masses = the disc's
mass (rho x its mesh area, from the triangles of the first frame) to 1e-12 relative at every
output time; energy balance within 1 % of KE0; seed-mean fragment count non-decreasing and
largest-fragment fraction non-increasing with v. Needs python3-vtk9, numpy, matplotlib
(/usr/bin/python3).
"""
import argparse
import csv
import math
import os
import re
import sys
import tomllib

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(HERE)), "scripts"))
import labtest  # noqa: E402  (scripts/labtest.py: shared helpers of the lab-test examples)

D = 0.1  # m: disc diameter (disc.geo)
GAP = 2.0e-4  # m: initial gap between the disc and the plate (disc.geo)
MASS_TOL = 1e-12  # spec V8: sum of fragment masses = total, relative
ENERGY_TOL = 0.01  # spec V8: energy balance <= 1 % of KE0
SIZES = {  # mode: (mesh size [m], velocities [m/s], seeds, simulated time after contact [s])
    "default": (5.0e-3, [5.0, 10.0, 20.0, 40.0], [1], 6.0e-4),
    "full": (5.0e-3, [5.0, 10.0, 20.0, 40.0], [1, 2, 3], 6.0e-4),
    "fine": (2.5e-3, [5.0, 10.0, 20.0, 40.0], [1, 2, 3], 6.0e-4),
    "quick": (5.0e-3, [10.0, 40.0], [1], 2.0e-4),
}


def sub1(pattern, repl, text, what):
    text, n = re.subn(pattern, repl, text)
    assert n == 1, f"{what} not found once ({n}), update run.py"
    return text


def make_run(out, h, v, seed, after):
    """The scenario of one run in OUT/v<V>_s<S>/: scenario.toml with the disc's mesh a copy of
    disc.geo with `seed`, mesh size h, velocity v, end time gap/v + after."""
    d = os.path.join(out, f"v{v:g}_s{seed}")
    os.makedirs(d, exist_ok=True)
    geo = open(os.path.join(HERE, "disc.geo")).read()
    geo = sub1(r"(?m)^seed = \d+;", f"seed = {seed};", geo, "disc.geo: seed")
    open(os.path.join(d, "disc.geo"), "w").write(geo)
    text = open(os.path.join(HERE, "scenario.toml")).read()
    text = sub1(r'mesh = "disc\.geo"', f'mesh = "{os.path.join(os.path.abspath(d), "disc.geo")}"',
                text, "scenario.toml: the disc's mesh")
    text = labtest.absolute_meshes(text, HERE)
    text = sub1(r"(mesh_size = )5\.0e-3(\s+# m: ~ l_ch)", rf"\g<1>{h!r}\2", text,
                "scenario.toml: the disc's mesh_size")
    text = sub1(r"velocity = \[0\.0, -10\.0\]", f"velocity = [0.0, {-v!r}]", text,
                "scenario.toml: the disc's velocity")
    text = sub1(r"(?m)^end_time = [0-9.e+-]+", f"end_time = {GAP / v + after!r}", text,
                "scenario.toml: end_time")
    path = os.path.join(d, "scenario_used.toml")
    open(path, "w").write(text)
    return d, path


def read_fragments(path):
    """fragments.csv as {time: [rows]} without the summary rows (docs/output.md)."""
    blocks = {}
    for r in labtest.read_csv(path):
        if r["fragment"] >= 0:
            blocks.setdefault(r["time"], []).append(r)
    return blocks


def disc_reference(frame, rho, body_name="disc"):
    """Number of disc triangles and the disc's mass rho x sum of its triangle areas, from the
    reference positions X = x - u of a frame (shoelace formula; independent of fdem's masses)."""
    x, u, conn, body, names = labtest.read_frame(frame)
    ids = [i for i, n in enumerate(names) if n == body_name]
    tris = conn[np.isin(body, ids)]
    X = x - u
    a, b, c = X[tris[:, 0]], X[tris[:, 1]], X[tris[:, 2]]
    area = 0.5 * np.abs((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) -
                        (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))
    return len(tris), rho * float(np.sum(area)), tris


def evaluate(d, rho, v):
    """Numbers of one finished run in folder d."""
    frames = labtest.frames(d)
    if not frames or not os.path.exists(os.path.join(d, "fragments.csv")):
        sys.exit(f"error: {d} holds no finished run (no frames or fragments.csv); run without "
                 "--no-run")
    ntri, mass_ref, _ = disc_reference(frames[0][1], rho)
    # the disc's triangles come first (first [[body]]), so its fragments are those with an id
    # (= smallest triangle id) below ntri; the plate is the fragment with id ntri
    blocks = read_fragments(os.path.join(d, "fragments.csv"))
    mass_err = 0.0
    for t, rows in blocks.items():
        m = math.fsum(r["mass"] for r in rows if r["fragment"] < ntri)
        mass_err = max(mass_err, abs(m / mass_ref - 1.0))
    t_end = max(blocks)
    frag = [r for r in blocks[t_end] if r["fragment"] < ntri]
    total = math.fsum(r["mass"] for r in frag)
    single = [r for r in frag if r["triangles"] == 1]
    hist = labtest.read_csv(os.path.join(d, "history.csv"))
    ke0 = 0.5 * mass_ref * v * v  # KE0 = m v^2 / 2 (the plate is fixed)
    err = max(abs(h["energy_error"]) for h in hist)
    contact = [h["time"] for h in hist if h["active_contacts"] > 0]
    # history.csv's largest_fragment_mass_fraction (bodies with fracture only: the disc) at the
    # last row, against the same number from fragments.csv (a consistency check of the column)
    hist_largest = hist[-1].get("largest_fragment_mass_fraction", float("nan"))
    return {"hist_largest": hist_largest, "ntri": ntri, "mass": mass_ref, "mass_err": mass_err, "t_end": t_end,
            "t_hist_end": hist[-1]["time"],
            "count": len(frag), "largest": max(r["mass"] for r in frag) / total,
            "single_count": len(single) / len(frag),
            "single_mass": math.fsum(r["mass"] for r in single) / total,
            "energy_err": err / ke0, "energy_end": hist[-1]["energy_error"] / ke0, "ke0": ke0,
            "ke0_fdem": hist[0]["kinetic"], "broken": hist[-1].get("joints.broken", 0),
            "w_frac": hist[-1].get("energy.fracture", 0.0),
            "first_contact": contact[0] if contact else float("nan"), "fragments": frag,
            "history": hist, "final_frame": frames[-1][1]}


def ring_radii():
    """Inner and outer radius [m] as ring.geo defines them (`Ri = ...;`, `Ro = ...;`), so the
    study's thickness and KE0 follow the geometry file instead of a copy of its numbers."""
    text = open(os.path.join(HERE, "ring.geo")).read()
    radii = []
    for name in ("Ri", "Ro"):
        m = re.search(rf"(?m)^{name} = ([0-9.eE+-]+);", text)
        if not m:
            sys.exit(f"error: ring.geo: no line '{name} = <value>;'")
        radii.append(float(m.group(1)))
    return radii


RING_RI, RING_RO = ring_radii()  # m: ring.geo (inner, outer radius)
RING_R = 0.5 * (RING_RI + RING_RO)  # m: mean radius
RING_RATES = [30.0, 100.0, 300.0]  # 1/s: hoop strain rates of the ring study (--ring, --full)
# --quick --ring (CTest validation.impact_ring_quick, label full): the two lower rates on ring.toml's 0.625 mm mesh,
# ~95 s on one core (1.25 mm, two elements through the thickness, would take 15 s but resolves
# neither the cohesive zone nor the thickness: README)
RING_RATES_QUICK = [30.0, 100.0]
RING_ZMR_BAND = 1.5  # mean fragment length within x1.5 of the cohesive-model fit (README, theory)


def ring_scales(rock):
    """Zhou, Molinari & Ramesh's scales of cohesive fragmentation (recalled; theory §9.8): length
    L0 = E' G / f_t^2 and strain rate r0 = c f_t^3 / (E'^2 G), with the hoop (plane-strain bar)
    modulus E' = E / (1 - nu^2) and c = sqrt(E' / rho)."""
    e = rock["youngs_modulus"] / (1.0 - rock["poisson_ratio"] ** 2)
    fr = rock["fracture"]
    g, ft = fr["fracture_energy_I"], fr["tensile_strength"]
    c = math.sqrt(e / rock["density"])
    return e * g / ft**2, c * ft**3 / (e * e * g)


def zmr_size(rock, rate):
    """Mean fragment length of the cohesive-model fit s / L0 = 4.5 / (1 + 4.5 (r / r0)^(2/3))
    (Zhou, Molinari & Ramesh, Appl. Phys. Lett. 88, 261918 (2006); recalled, theory §9.8)."""
    l0, r0 = ring_scales(rock)
    return l0 * 4.5 / (1.0 + 4.5 * (rate / r0) ** (2.0 / 3.0))


def grady_size(rock, rate):
    """Grady's energy-balance size s = (24 G / (rho r^2))^(1/3) (Grady 1982, recalled)."""
    return (24.0 * rock["fracture"]["fracture_energy_I"] / (rock["density"] * rate**2)) ** (1 / 3)


def run_ring(out, fdem, threads, no_run, rate):
    """The expanding ring of ring.toml at hoop strain rate `rate` (optional part of spec V8):
    fragments at the end against Grady's size and the cohesive-model fit (zmr_size), energy
    balance against the initial kinetic energy of the exact annulus, KE0 = rho r^2 pi (Ro^4 -
    Ri^4)/4."""
    d = os.path.join(out, "ring", f"r{rate:g}")
    os.makedirs(d, exist_ok=True)
    text = labtest.absolute_meshes(open(os.path.join(HERE, "ring.toml")).read(), HERE)
    text = sub1(r"(?m)^velocity_gradient = .*$",
                f"velocity_gradient = [[{rate!r}, 0.0], [0.0, {rate!r}]]", text,
                "ring.toml: velocity_gradient")
    scen = os.path.join(d, "scenario_used.toml")
    open(scen, "w").write(text)
    cfg = tomllib.loads(text)
    wall = float("nan")
    if not no_run:
        wall = labtest.run_fdem(fdem, scen, d, threads, f"ring r = {rate:g} 1/s: ")
    rock = next(m for m in cfg["material"] if m["name"] == "rock")
    rho = rock["density"]
    frames = labtest.frames(d)
    if not frames or not os.path.exists(os.path.join(d, "fragments.csv")):
        sys.exit(f"error: {d} holds no finished run; run without --no-run")
    ntri, mass_ref, _ = disc_reference(frames[0][1], rho, "ring")
    blocks = read_fragments(os.path.join(d, "fragments.csv"))
    mass_err = max(abs(math.fsum(r["mass"] for r in rows) / mass_ref - 1.0)
                   for rows in blocks.values())
    frag = blocks[max(blocks)]
    multi = [r for r in frag if r["triangles"] > 1]
    total = math.fsum(r["mass"] for r in frag)
    # fragment length along the ring: its area / thickness
    arc = [r["area"] / (RING_RO - RING_RI) for r in frag]
    hist = labtest.read_csv(os.path.join(d, "history.csv"))
    ke0 = rho * rate**2 * math.pi * (RING_RO**4 - RING_RI**4) / 4.0
    grady = grady_size(rock, rate)
    l0, r0 = ring_scales(rock)
    return {"count": len(frag), "multi": len(multi), "grady": grady,
            "zmr": zmr_size(rock, rate),
            "l0": l0, "rate0": r0, "h": cfg["body"][0]["mesh_size"],
            "mean": 2 * math.pi * RING_R / len(frag),
            "mean_multi": 2 * math.pi * RING_R / len(multi) if multi else float("nan"),
            "mass_mean": math.fsum(a * r["mass"] for a, r in zip(arc, frag)) / total,
            "largest": max(arc), "single_mass": math.fsum(r["mass"] for r in frag
                                                          if r["triangles"] == 1) / total,
            "energy_err": max(abs(h["energy_error"]) for h in hist) / ke0, "ke0": ke0,
            "mass_err": mass_err, "ntri": ntri, "rate": rate,
            "broken": hist[-1].get("joints.broken", 0), "w_frac": hist[-1].get("energy.fracture", 0),
            "wall": wall, "rock": rock}


def plot_ring(png, rings):
    """Mean fragment length against the hoop strain rate: fdem, the cohesive-model fit and
    Grady's estimate."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rock = rings[0]["rock"]
    rates = [r["rate"] for r in rings]
    rr = np.geomspace(min(rates) / 2, max(rates) * 2, 100)
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    ax.loglog(rr, [grady_size(rock, x) * 1e3 for x in rr], "k--",
              label="Grady (24 G/(rho r^2))^(1/3)")
    ax.loglog(rr, [zmr_size(rock, x) * 1e3 for x in rr], "b-",
              label="cohesive-model fit (Zhou, Molinari, Ramesh)")
    ax.fill_between(rr, [zmr_size(rock, x) * 1e3 / RING_ZMR_BAND for x in rr],
                    [zmr_size(rock, x) * 1e3 * RING_ZMR_BAND for x in rr], color="b", alpha=0.12,
                    label=f"x{RING_ZMR_BAND:g} band")
    ax.loglog(rates, [r["mean"] * 1e3 for r in rings], "ro", label="fdem: 2 pi R / N")
    ax.loglog(rates, [r["mean_multi"] * 1e3 for r in rings], "r^", mfc="none",
              label="fdem: multi-triangle fragments only")
    ax.set_xlabel("hoop strain rate r [1/s]")
    ax.set_ylabel("mean fragment length [mm]")
    ax.set_title(f"expanding ring R = {RING_R * 1e3:g} mm, h = {rings[0]['h'] * 1e3:g} mm")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=120)
    plt.close(fig)


def plot_sizes(png, runs, velocities, seeds):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for k, v in enumerate(velocities):
        for s in seeds:
            r = runs[(v, s)]
            dia = np.sort(np.array([f["diameter"] for f in r["fragments"]]))
            order = np.argsort([f["diameter"] for f in r["fragments"]])
            m = np.array([r["fragments"][i]["mass"] for i in order])
            cum = np.cumsum(m) / m.sum()
            ax.step(dia * 1e3, cum, where="post", color=f"C{k}", alpha=1.0 if s == seeds[0] else 0.5,
                    label=f"v = {v:g} m/s" if s == seeds[0] else None)
    ax.set_xscale("log")
    ax.set_xlabel("fragment size (equivalent diameter sqrt(4A/pi)) [mm]")
    ax.set_ylabel("cumulative mass fraction")
    ax.set_title(f"Impact of a D = {D * 1e3:g} mm disc: fragment sizes at the end"
                 + (f" (seeds {','.join(map(str, seeds))})" if len(seeds) > 1 else ""), fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=100)
    plt.close(fig)


def plot_summary(png, mean, velocities, runs, seeds):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker
    fig, axs = plt.subplots(1, 3, figsize=(11, 3.8))
    for ax, key, lab in ((axs[0], "count", "fragments (disc)"),
                         (axs[1], "largest", "largest fragment mass / disc mass"),
                         (axs[2], "energy_err", "max |energy error| / KE0")):
        for s in seeds:
            ax.plot(velocities, [runs[(v, s)][key] for v in velocities], "o", color="0.6", ms=4,
                    label="one seed" if s == seeds[0] else None)
        ax.plot(velocities, [mean[v][key] for v in velocities], "-s", color="C0", label="seed mean")
        ax.set_xscale("log")
        ax.set_xticks(velocities)
        ax.set_xticklabels([f"{v:g}" for v in velocities])
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.set_xlabel("impact velocity v [m/s]")
        ax.set_ylabel(lab)
        ax.grid(alpha=0.3)
    axs[2].axhline(ENERGY_TOL, color="r", ls="--", lw=1, label="spec V8: 1 %")
    axs[2].set_yscale("log")
    axs[0].legend(fontsize=8)
    axs[2].legend(fontsize=8)
    fig.suptitle("Impact fragmentation (spec V8)", fontsize=10)
    fig.tight_layout()
    fig.savefig(png, dpi=100)
    plt.close(fig)


def plot_fragments(png, runs, velocities, seed):
    """The disc's triangles at the end, current positions, coloured by fragment (VTU `fragment`);
    single-triangle fragments grey."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
    from vtk import vtkXMLUnstructuredGridReader
    from vtk.util.numpy_support import vtk_to_numpy
    fig, axs = plt.subplots(1, len(velocities), figsize=(3.2 * len(velocities), 3.4), squeeze=False)
    for ax, v in zip(axs[0], velocities):
        r = runs[(v, seed)]
        rd = vtkXMLUnstructuredGridReader()
        rd.SetFileName(r["final_frame"])
        rd.Update()
        g = rd.GetOutput()
        x = vtk_to_numpy(g.GetPoints().GetData())[:, :2]
        conn = vtk_to_numpy(g.GetCells().GetConnectivityArray()).reshape(-1, 3)
        frag = vtk_to_numpy(g.GetCellData().GetArray("fragment"))
        disc = frag < r["ntri"]
        ids, counts = np.unique(frag[disc], return_counts=True)
        size = dict(zip(ids, counts))
        rng = np.random.default_rng(1)
        colour = {f: rng.random(3) * 0.8 + 0.1 for f in ids}
        fc = [colour[f] if size[f] > 1 else (0.75, 0.75, 0.75) for f in frag[disc]]
        ax.add_collection(PolyCollection(x[conn[disc]], facecolors=fc, edgecolors="k",
                                         linewidths=0.1))
        ax.axhline(0.0, color="k", lw=1.5)
        ax.set_xlim(-0.09, 0.09)
        ax.set_ylim(-0.01, 0.12)
        ax.set_aspect("equal")
        ax.set_title(f"v = {v:g} m/s: {r['count']} fragments,\nlargest {r['largest']:.2f}, "
                     f"t = {r['t_end'] * 1e3:.2f} ms", fontsize=9)
        ax.set_xticks([])
        ax.set_yticks([])
    fig.suptitle("fragments at the end (colour: fragment; grey: single triangles)", fontsize=10)
    fig.tight_layout()
    fig.savefig(png, dpi=80)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--full", action="store_true")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--fine", action="store_true")
    ap.add_argument("--ring", action="store_true",
                    help="also run the expanding ring (ring.toml) at 30, 100, 300 1/s; --full and "
                         "--fine do")
    ap.add_argument("--velocities")
    ap.add_argument("--seeds")
    ap.add_argument("--after", type=float)
    ap.add_argument("--out")
    ap.add_argument("--fdem", default="build/release/fdem")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--no-run", action="store_true")
    ap.add_argument("--validate", metavar="DIR",
                    help="also write DIR/checks_impact.csv for scripts/validate's report")
    a = ap.parse_args()
    mode = "fine" if a.fine else ("full" if a.full else ("quick" if a.quick else "default"))
    h, velocities, seeds, after = SIZES[mode]
    if a.velocities:
        velocities = [float(x) for x in a.velocities.split(",")]
    if a.seeds:
        seeds = [int(x) for x in a.seeds.split(",")]
    if a.after:
        after = a.after
    out = a.out or ("out/11_impact_fragmentation" + ("" if mode == "default" else "_" + mode))
    os.makedirs(out, exist_ok=True)
    cfg = tomllib.load(open(os.path.join(HERE, "scenario.toml"), "rb"))
    rock = next(m for m in cfg["material"] if m["name"] == "rock")
    rho = rock["density"]
    c_p = labtest.wave_speed(rock)

    runs, walls = {}, {}
    for v in velocities:
        for s in seeds:
            d, scen = make_run(out, h, v, s, after)
            if not a.no_run:
                walls[(v, s)] = labtest.run_fdem(a.fdem, scen, d, a.threads, f"v = {v:g}, seed {s}: ")
            runs[(v, s)] = evaluate(d, rho, v)
            runs[(v, s)]["wall"] = walls.get((v, s), float("nan"))
    mean = {v: {k: float(np.mean([runs[(v, s)][k] for s in seeds]))
                for k in ("count", "largest", "single_count", "single_mass", "energy_err",
                          "energy_end", "broken", "w_frac", "ntri")} for v in velocities}

    with open(os.path.join(out, "sizes.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["velocity_m_s", "seed", "fragment", "triangles", "mass_kg_per_m", "diameter_m",
                    "cumulative_mass_fraction"])
        for v in velocities:
            for s in seeds:
                fr = sorted(runs[(v, s)]["fragments"], key=lambda r: (r["diameter"], r["fragment"]))
                tot, cum = math.fsum(r["mass"] for r in fr), 0.0
                for r in fr:
                    cum += r["mass"]
                    w.writerow([f"{v:g}", s, int(r["fragment"]), int(r["triangles"]),
                                f"{r['mass']:.9g}", f"{r['diameter']:.9g}", f"{cum / tot:.9g}"])
    cols = ["count", "largest", "single_count", "single_mass", "energy_err", "energy_end",
            "broken", "w_frac"]
    with open(os.path.join(out, "summary.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["velocity_m_s", "seed", "triangles", "fragments", "largest_fraction",
                    "single_triangle_count_fraction", "single_triangle_mass_fraction",
                    "max_abs_energy_error_over_KE0", "end_energy_error_over_KE0", "broken_joints",
                    "fracture_work_J_per_m", "KE0_J_per_m", "max_mass_error_rel", "run_s"])
        for v in velocities:
            for s in seeds:
                r = runs[(v, s)]
                w.writerow([f"{v:g}", s, r["ntri"]] + [f"{r[k]:.6g}" for k in cols] +
                           [f"{r['ke0']:.6g}", f"{r['mass_err']:.3g}", f"{r['wall']:.1f}"])
            if len(seeds) > 1:
                w.writerow([f"{v:g}", "mean", f"{mean[v]['ntri']:.6g}"] +
                           [f"{mean[v][k]:.6g}" for k in cols] + ["", "", ""])

    plot_sizes(os.path.join(out, "sizes.png"), runs, velocities, seeds)
    plot_summary(os.path.join(out, "summary.png"), mean, velocities, runs, seeds)
    plot_fragments(os.path.join(out, "fragments.png"), runs, velocities, seeds[0])

    fr = rock["fracture"]
    lch = rock["youngs_modulus"] * fr["fracture_energy_I"] / fr["tensile_strength"] ** 2
    print(f"Impact fragmentation: disc D = {D * 1e3:g} mm, mesh {h * 1e3:g} mm, D/l_ch = "
          f"{D / lch:.3g}, c_p = {c_p:.0f} m/s, rho c_p v / f_t = "
          + ", ".join(f"{rho * c_p * v / fr['tensile_strength']:.3g}" for v in velocities)
          + f" at v = {', '.join(f'{v:g}' for v in velocities)} m/s")
    for v in velocities:
        for s in seeds:
            r = runs[(v, s)]
            print(f"  v = {v:4g} m/s seed {s}: {r['ntri']} triangles, {r['count']} fragments, "
                  f"largest {r['largest']:.4f}, single triangles {r['single_count'] * 100:.1f} % "
                  f"of the fragments / {r['single_mass'] * 100:.1f} % of the mass, broken "
                  f"{r['broken']:.0f}, W_frac {r['w_frac']:.1f} J/m, KE0 {r['ke0']:.1f} J/m, "
                  f"energy error max {r['energy_err'] * 100:.3g} % / end "
                  f"{r['energy_end'] * 100:.3g} % of KE0, mass error {r['mass_err']:.2g}, "
                  f"t_end {r['t_end'] * 1e3:.3f} ms, history.csv largest_fragment_mass_fraction "
                  f"{r['hist_largest']:.6g}" +
                  ("" if r["t_hist_end"] == r["t_end"] else
                   f" (history to {r['t_hist_end'] * 1e3:.3f} ms)") +
                  (f", run {r['wall']:.1f} s" if math.isfinite(r["wall"]) else ""))
        if len(seeds) > 1:
            m = mean[v]
            print(f"  v = {v:4g} m/s seed mean: {m['count']:.1f} fragments, largest "
                  f"{m['largest']:.4f}, single triangles {m['single_count'] * 100:.1f} %, "
                  f"energy error {m['energy_err'] * 100:.3g} % of KE0")
    rings = []
    if a.ring or mode in ("full", "fine"):
        rates = RING_RATES_QUICK if mode == "quick" else RING_RATES
        rings = [run_ring(out, a.fdem, a.threads, a.no_run, rate) for rate in rates]
        with open(os.path.join(out, "ring", "ring_study.csv"), "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["rate_1_s", "rate_over_r0", "mesh_m", "triangles", "fragments",
                        "multi_triangle_fragments", "mean_length_m", "mean_length_multi_m",
                        "mass_weighted_length_m", "largest_length_m", "single_triangle_mass_fraction",
                        "zmr_m", "grady_m", "mean_over_zmr", "mean_over_grady",
                        "max_abs_energy_error_over_KE0", "max_mass_error_rel", "run_s"])
            for r in rings:
                w.writerow([f"{r['rate']:g}", f"{r['rate'] / r['rate0']:.4g}", f"{r['h']:g}",
                            r["ntri"], r["count"], r["multi"]] +
                           [f"{r[k]:.6g}" for k in ("mean", "mean_multi", "mass_mean", "largest",
                                                    "single_mass", "zmr", "grady")] +
                           [f"{r['mean'] / r['zmr']:.4g}", f"{r['mean'] / r['grady']:.4g}",
                            f"{r['energy_err']:.3g}", f"{r['mass_err']:.3g}", f"{r['wall']:.1f}"])
        plot_ring(os.path.join(out, "ring", "ring_study.png"), rings)
        print(f"  expanding ring (ring.toml, h = {rings[0]['h'] * 1e3:g} mm, {rings[0]['ntri']} "
              f"triangles; L0 = E' G/f_t^2 = {rings[0]['l0'] * 1e3:.2f} mm, r0 = "
              f"{rings[0]['rate0']:.0f} 1/s):")
        for ring in rings:
            print(f"    r = {ring['rate']:g} 1/s (r/r0 = {ring['rate'] / ring['rate0']:.2f}): "
                  f"{ring['count']} fragments ({ring['multi']} of more than one triangle, single "
                  f"triangles {ring['single_mass'] * 100:.1f} % of the mass), mean length 2 pi R / "
                  f"N = {ring['mean'] * 1e3:.2f} mm (multi-triangle fragments only "
                  f"{ring['mean_multi'] * 1e3:.2f} mm, mass-weighted {ring['mass_mean'] * 1e3:.2f} "
                  f"mm, largest {ring['largest'] * 1e3:.2f} mm); cohesive-model fit "
                  f"{ring['zmr'] * 1e3:.2f} mm: ratio {ring['mean'] / ring['zmr']:.3f}; Grady "
                  f"{ring['grady'] * 1e3:.2f} mm: ratio {ring['mean'] / ring['grady']:.3f}; broken "
                  f"{ring['broken']:.0f}, W_frac {ring['w_frac']:.1f} J/m; energy error max "
                  f"{ring['energy_err'] * 100:.3g} % of KE0 = {ring['ke0']:.1f} J/m; mass error "
                  f"{ring['mass_err']:.2g}" + (f", run {ring['wall']:.1f} s"
                                              if math.isfinite(ring["wall"]) else ""))
    counts = [mean[v]["count"] for v in velocities]
    largest = [mean[v]["largest"] for v in velocities]
    count_ok = all(b >= a_ for a_, b in zip(counts, counts[1:]))
    largest_ok = all(b <= a_ for a_, b in zip(largest, largest[1:]))
    mass_err = max(r["mass_err"] for r in runs.values())
    energy_err = max(r["energy_err"] for r in runs.values())
    complete = all(r["t_end"] >= r["t_hist_end"] - 1e-12 and r["t_end"] >= GAP / v + 0.99 * after
                   for (v, _), r in runs.items())
    print(f"  mass: max |sum of fragment masses / (rho A) - 1| = {mass_err:.3g} (target "
          f"{MASS_TOL:g}); energy: max |error| / KE0 = {energy_err * 100:.3g} % (target "
          f"{ENERGY_TOL * 100:g} %); count non-decreasing in v: {count_ok}; largest fraction "
          f"non-increasing in v: {largest_ok}; all runs reached the end: {complete}")
    ok = mass_err <= MASS_TOL and energy_err <= ENERGY_TOL and count_ok and largest_ok and complete
    print("  V8 " + ("met" if ok else "NOT met"))

    failed = 0
    if a.validate:
        why = "spec fracture.md §11 V8"
        tag = (f"impact D = {D * 1e3:g} mm, h = {h * 1e3:g} mm, v = "
               f"{'/'.join(f'{v:g}' for v in velocities)} m/s, {len(seeds)} seed(s): ")
        rows = [labtest.check("V8", tag + "max |sum of fragment masses / (rho x disc area) - 1| "
                              "over all output times", mass_err, MASS_TOL, "at_most", 0, "", why +
                              "; mass conservation (disc area from the frame's triangles)"),
                labtest.check("V8", tag + "all runs reached their end time", complete, 1, "bool",
                              0, "", "fdem stops when its energy check (10 %) fails"),
                labtest.check("V8", tag + "seed-mean fragment count non-decreasing with v",
                              count_ok, 1, "bool", 0, "",
                              why + "; counts " + ", ".join(f"{c:.1f}" for c in counts)),
                labtest.check("V8", tag + "seed-mean largest-fragment mass fraction "
                              "non-increasing with v", largest_ok, 1, "bool", 0, "",
                              why + "; fractions " + ", ".join(f"{x:.3f}" for x in largest))]
        for v in velocities:
            # energy balance: the spec's target at every size, --quick (the default CTest suite)
            # included since the contact fixes of theory §9.7 (c)
            rows.append(labtest.check("V8", tag + f"v = {v:g} m/s: max |energy error| / KE0 "
                                      "(seed max)", max(runs[(v, s)]["energy_err"] for s in seeds),
                                      ENERGY_TOL, "at_most", 0, "", why + "; undamped"))
            rows.append(labtest.check("V8", tag + f"v = {v:g} m/s: single-triangle fragments / "
                                      "fragments (seed mean, pulverisation)",
                                      mean[v]["single_count"], float("nan"), "report", 0, "", why))
        for ring in rings:
            rtag = (f"expanding ring R = {RING_R * 1e3:g} mm, r = {ring['rate']:g} 1/s, h = "
                    f"{ring['h'] * 1e3:g} mm: ")
            zmr_why = ("cohesive-model fit s/L0 = 4.5/(1 + 4.5 (r/r0)^(2/3)), Zhou, Molinari & "
                       "Ramesh 2006 (recalled); within x1.5: theory §9.8")
            rows += [labtest.check("V8", rtag + "mean fragment length 2 pi R / N over the "
                                   "cohesive-model fit", ring["mean"] / ring["zmr"],
                                   1 / RING_ZMR_BAND, "range", RING_ZMR_BAND, "", zmr_why),
                     labtest.check("V8", rtag + "mean fragment length 2 pi R / N over Grady's "
                                   "(24 G_I/(rho r^2))^(1/3)", ring["mean"] / ring["grady"],
                                   float("nan"), "report", 0, "",
                                   why + " (optional; Grady 1982, recalled) asks for x3; the fit "
                                   f"above is {ring['zmr'] / ring['grady']:.2f} x Grady here, "
                                   "below the band for any cohesive model: reported, theory §9.8"),
                     labtest.check("V8", rtag + "max |energy error| / KE0", ring["energy_err"],
                                   ENERGY_TOL, "at_most", 0, "", why + "; undamped"),
                     labtest.check("V8", rtag + "max |sum of fragment masses / (rho x ring area) "
                                   "- 1|", ring["mass_err"], MASS_TOL, "at_most", 0, "", why)]
        failed = labtest.write_checks(
            a.validate, "impact", rows,
            [(os.path.join(out, "summary.png"), tag + "fragment count, largest fraction and "
              "energy error against v (V8)"),
             (os.path.join(out, "sizes.png"), tag + "cumulative mass against fragment size (V8)"),
             (os.path.join(out, "fragments.png"), tag + "fragments at the end (V8)")] +
            ([(os.path.join(out, "ring", "ring_study.png"), "expanding ring: mean fragment "
               "length against the strain rate, cohesive-model fit and Grady (V8)")]
             if rings else []))
    if (a.check and not ok) or failed:
        sys.exit(1)


if __name__ == "__main__":
    main()
