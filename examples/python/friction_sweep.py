#!/usr/bin/env python3
"""Friction sweep: a block kicked along a fixed platform stops after d = v0^2 / (2 mu g).

A 0.4 m x 0.2 m block (E = 1 GPa) rests on a 4 m long fixed platform under gravity. Mass damping settles it
on its contact layer for 0.05 s; then a [[kick]] gives it v0 = 2 m/s along the platform and it
slides to rest under Coulomb friction mu. For each mu the script builds the model in Python
(fdem.ModelBuilder with meshes from fdem.Mesh.rectangle), runs it, measures the distance the block
travels after the kick, and plots it against the analytic line v0^2 / (2 mu g).

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/friction_sweep.py
        [--mu 0.2 0.3 0.5 0.8] [--out out/python/friction_sweep.png] [--csv ...]

Units: SI (m, s, kg, Pa). Prints one line per mu and writes the PNG and a CSV of the points.
"""
import argparse
import csv
import os

import numpy as np

import fdem

G = 9.81  # m/s^2
V0 = 2.0  # m/s
T_KICK = 0.05  # s: end of the settling window


def build(mu, cells=0.05):
    """The sliding-block model for friction coefficient mu (cells: element size [m])."""
    b = fdem.ModelBuilder(name=f"friction_sweep(mu={mu})")
    t_stop = V0 / (mu * G)
    b.simulation(end_time=T_KICK + 1.15 * t_stop, dt="auto", gravity=(0.0, -G))
    b.output(vtu=False)
    # xi = 1 (theory §2.3) damps the block's elastic ringing that the onset of friction excites
    # (as the sliding-block validation T16 does); the platform is fixed, its material only gives
    # it mass
    rock = b.material("rock", density=2500.0, youngs_modulus=1.0e9, poisson_ratio=0.25,
                      damping_ratio=1.0)
    platform = fdem.Mesh.rectangle(0.0, 0.0, 4.0, 0.2, round(4.0 / cells), round(0.2 / cells))
    block = fdem.Mesh.rectangle(0.2, 0.2, 0.4, 0.2, round(0.4 / cells), round(0.2 / cells))
    b.body("platform", mesh=platform, material=rock, fixed=True)
    b.body("block", mesh=block, material=rock)
    b.damping(mass_proportional=1000.0, until=T_KICK)  # settle on the contact layer, then off
    b.kick("block", time=T_KICK, velocity=(V0, 0.0))
    b.contact("smooth", friction=mu)
    return b.build()


def stop_distance(mu, cells=0.05):
    """Distance [m] the block's mass centre travels from the kick until it stops."""
    sim = build(mu, cells)
    sim.run(until=T_KICK)
    x_kick = sim.resultants()["block"]["u"][0]
    state = {"stopped_at": None}

    def watch(s):
        r = s.resultants()["block"]
        if s.time > T_KICK + 0.01 and abs(r["v"][0]) < 1e-3 * V0:
            state["stopped_at"] = s.time
            return False  # at rest: stop the run
        return True

    sim.run(callback=watch, every=200)
    if state["stopped_at"] is None:
        raise RuntimeError(f"mu = {mu}: the block did not stop by t = {sim.time:.3f} s")
    return sim.resultants()["block"]["u"][0] - x_kick, state["stopped_at"] - T_KICK


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mu", type=float, nargs="+", default=[0.2, 0.3, 0.5, 0.8])
    ap.add_argument("--cells", type=float, default=0.05, help="element size [m]")
    ap.add_argument("--out", default="out/python/friction_sweep.png")
    ap.add_argument("--csv", default=None, help="CSV of the points (default: next to --out)")
    args = ap.parse_args()

    rows = []
    for mu in args.mu:
        d, t = stop_distance(mu, args.cells)
        d_an = V0**2 / (2 * mu * G)
        rows.append((mu, d, d_an, t, V0 / (mu * G)))
        print(f"mu = {mu:5.3f}: stop distance {d:.4f} m, analytic {d_an:.4f} m "
              f"({100 * (d / d_an - 1):+.2f} %), stop time {t:.4f} s")

    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    csv_path = args.csv or os.path.splitext(args.out)[0] + ".csv"
    with open(csv_path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["mu", "stop_distance_m", "analytic_m", "stop_time_s", "analytic_time_s"])
        w.writerows(rows)

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    mus = np.linspace(min(args.mu) * 0.8, max(args.mu) * 1.1, 200)
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(mus, V0**2 / (2 * mus * G), "k-", label=r"analytic $v_0^2/(2\mu g)$")
    ax.plot([r[0] for r in rows], [r[1] for r in rows], "o", color="C3", label="fdem")
    ax.set_xlabel(r"friction coefficient $\mu$ [-]")
    ax.set_ylabel("stop distance [m]")
    ax.set_title(f"block kicked at {V0} m/s along a fixed platform")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)
    print(f"plot {args.out}\ncsv  {csv_path}")


if __name__ == "__main__":
    main()
