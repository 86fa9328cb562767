#!/usr/bin/python3
"""Example 07 (validation V1 of spec fracture.md §11): grip force against grip displacement of the
pull-apart run, as a CSV and a PNG, and the two checks of V1.

Usage: /usr/bin/python3 examples/07_pull_apart/plot.py [OUT_DIR]   (default out/07_pull_apart)
Writes OUT_DIR/pull_apart.csv (time, u, force, stress) and OUT_DIR/pull_apart.png; prints the
checks and exits 1 if one fails:
  peak grip stress = f_t                                  +-1 %   (docs/theory.md eq. 9.5)
  Gamma_I = work to break / joint length = G_I + (4/3) h f_t^2/p  +-1 %   (eq. 9.13)
Gamma_I is measured at the grip, independently of the joints' own bookkeeping: the work the grip
did (v x the sum of its reaction impulses, bodies.csv) minus the energy still stored at the end
(kinetic + strain + joint, history.csv), per unit joint length. The joints' own audit,
energy.fracture / length (eq. 9.19), is printed next to it.
Needs python3-matplotlib (Debian), hence /usr/bin/python3.
"""
import csv
import os
import sys
import tomllib

HERE = os.path.dirname(os.path.abspath(__file__))
WIDTH = 0.02  # m: joint line length = block width (blocks.geo W)
H_JOINT = WIDTH / 5  # m: 5 joints along it (blocks.geo Transfinite Curve {3} = 6 nodes)
GRIP = "blocks/top"


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def column(rs, *names):
    """First of names present in the rows (history column names of the fracture wiring)."""
    for n in names:
        if rs and n in rs[0]:
            return [float(r[n]) for r in rs]
    raise KeyError(f"none of {names} in the file")


def main(out):
    with open(os.path.join(HERE, "scenario.toml"), "rb") as f:
        sc = tomllib.load(f)
    mat = sc["material"][0]
    frac = mat["fracture"]
    E = mat["youngs_modulus"]
    ft = frac["tensile_strength"]
    GI = frac["fracture_energy_I"]
    p = 10 * E if frac.get("penalty", "auto") == "auto" else frac["penalty"]
    v = sc["boundary"][1]["velocity"][1]
    gamma_expected = GI + 4.0 / 3.0 * H_JOINT * ft * ft / p  # theory eq. 9.13

    b = rows(os.path.join(out, "bodies.csv"))
    h = rows(os.path.join(out, "history.csv"))
    t = column(b, "time")
    u = column(b, GRIP + ".uy")
    force = column(b, GRIP + ".reaction_avg_y")  # interval average (eq. 8.4), N/m
    stress = [F / WIDTH for F in force]
    with open(os.path.join(out, "pull_apart.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["time", "u", "force", "stress"])
        for r in zip(t, u, force, stress):
            w.writerow([f"{x:.10g}" for x in r])

    # work of the grip: v x impulse (the reaction averages times their intervals)
    work = 0.0
    for k in range(1, len(t)):
        work += v * force[k] * (t[k] - t[k - 1])
    work += v * force[0] * t[0]
    stored = (column(h, "kinetic")[-1] + column(h, "strain")[-1] +
              column(h, "joint", "energy.joint")[-1])
    gamma_grip = (work - stored) / WIDTH
    gamma_audit = column(h, "fracture", "energy.fracture")[-1] / WIDTH
    peak = max(stress)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    ax.plot([x * 1e6 for x in u], [s / 1e6 for s in stress], "-", lw=1.5, label="fdem (grip)")
    ax.axhline(ft / 1e6, color="0.5", ls="--", lw=1, label="f_t")
    ax.set_xlabel("grip displacement [µm]")
    ax.set_ylabel("grip stress F / W [MPa]")
    ax.set_title(f"V1 pull-apart: peak {peak / 1e6:.4g} MPa, "
                 f"Γ_I {gamma_grip:.4g} J/m² (expected {gamma_expected:.4g})", fontsize=9)
    ax.legend()
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "pull_apart.png"), dpi=120)

    ok = True
    for name, got, want in (("peak grip stress [Pa]", peak, ft),
                            ("Gamma_I at the grip [J/m^2]", gamma_grip, gamma_expected)):
        err = got / want - 1
        good = abs(err) <= 0.01
        ok = ok and good
        print(f"{name:30s} {got:12.8g}  expected {want:12.8g}  relative error {err:+.2e}  "
              f"{'pass' if good else 'FAIL'} (±1 %)")
    print(f"{'Gamma_I, joint audit [J/m^2]':30s} {gamma_audit:12.8g}  (energy.fracture / W, "
          f"eq. 9.19)")
    print(f"wrote {os.path.join(out, 'pull_apart.csv')} and pull_apart.png")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "out/07_pull_apart"))
