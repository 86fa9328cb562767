#!/usr/bin/env python3
"""Drop test: an elastic disk falls onto a slab; a picture of the stress field at peak impact.

A disk of radius R = 0.1 m (meshed by Gmsh from disk.geo through fdem.Mesh.read) hits a slab
0.6 m x 0.1 m held at its base at v0 = 2 m/s (given as its initial velocity, 0.5 mm above the
slab). The script follows the contact force on the disk with a run() callback, keeps the state of
the largest force (a checkpoint), restores it and draws the von Mises stress on the deformed mesh
with fdem.plot.tripcolor, plus the force history and the energy balance.

Reference: the rebound of an undamped elastic disk is elastic: the disk leaves the slab with
nearly all of its impact momentum (part goes into vibration); the script prints the momentum
ratio and the energy balance error.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/drop_test.py
        [--out out/python/drop_test.png] [--mesh-size 0.01]
"""
import argparse
import os
import pathlib
import tempfile

import numpy as np

import fdem
import fdem.plot

HERE = pathlib.Path(__file__).resolve().parent
V0 = 2.0  # m/s, downwards


def build(mesh_size):
    b = fdem.ModelBuilder(name="drop_test")
    b.simulation(end_time=0.006, dt="auto", gravity=(0.0, -9.81))
    b.output(vtu=False)
    steel = b.material("soft_steel", density=7800.0, youngs_modulus=2.0e9, poisson_ratio=0.3)
    slab = fdem.Mesh.rectangle(-0.3, -0.1, 0.6, 0.1, 60, 10)
    disk = fdem.Mesh.read(str(HERE / "disk.geo"), mesh_size=mesh_size)
    b.body("slab", mesh=slab, material=steel)
    b.boundary("slab", "bottom", fix=["x", "y"])
    b.body("disk", mesh=disk, group="disk", material=steel, velocity=(0.0, -V0))
    b.contact("smooth")
    return b.build()


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mesh-size", type=float, default=0.01, help="disk element size [m]")
    ap.add_argument("--out", default="out/python/drop_test.png")
    args = ap.parse_args()

    sim = build(args.mesh_size)
    rec = fdem.EnergyRecorder()
    hist = {"t": [], "fy": []}
    best = {"f": 0.0}
    ckpt = os.path.join(tempfile.mkdtemp(prefix="fdem_drop_"), "peak.fdck")

    def watch(s):
        fy = s.resultants()["disk"]["contact"][1]
        hist["t"].append(s.time)
        hist["fy"].append(fy)
        rec(s)
        if fy > best["f"]:
            best["f"] = fy
            s.save_checkpoint(ckpt)  # the state at the largest force so far
        return True

    sim.run(callback=watch, every=10)
    m_disk = sim.model.node_mass[sim.model.node_body == 1].sum()
    vy_end = sim.resultants()["disk"]["v"][1]
    e = rec.arrays()
    scale = max(e["kinetic"].max(), 1e-300)
    print(f"disk mass {m_disk:.3f} kg/m, impact velocity {V0} m/s")
    print(f"peak contact force {best['f']:.4g} N/m; rebound velocity {vy_end:.4f} m/s "
          f"(momentum ratio {vy_end / V0:.3f})")
    print(f"energy balance: max |total - total_0| = "
          f"{np.abs(e['total'] - e['total'][0]).max() / scale:.2e} of the kinetic energy")

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt


    peak = build(args.mesh_size)
    peak.restore_checkpoint(ckpt)
    fig = plt.figure(figsize=(11, 4.2))
    ax0 = fig.add_subplot(1, 2, 1)
    fdem.plot.tripcolor(peak, field="von_mises", ax=ax0, cmap="inferno",
                        title=f"von Mises stress at peak force, t = {peak.time * 1e3:.3f} ms")
    ax0.set_xlim(-0.15, 0.15)
    ax0.set_ylim(-0.1, 0.21)
    ax1 = fig.add_subplot(2, 2, 2)
    ax1.plot(np.array(hist["t"]) * 1e3, np.array(hist["fy"]) / 1e3, color="C3")
    ax1.set_ylabel("contact force on disk [kN/m]")
    ax1.grid(alpha=0.3)
    ax2 = fig.add_subplot(2, 2, 4, sharex=ax1)
    ax2.plot(e["time"] * 1e3, e["kinetic"], label="kinetic")
    ax2.plot(e["time"] * 1e3, e["strain"] + e["contact"], label="strain + contact")
    ax2.plot(e["time"] * 1e3, e["total"], "k", label="total")
    ax2.set_xlabel("time [ms]")
    ax2.set_ylabel("energy [J/m]")
    ax2.legend(fontsize=8)
    ax2.grid(alpha=0.3)
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    fig.savefig(args.out, dpi=120)
    print(f"plot {args.out}")


if __name__ == "__main__":
    main()
