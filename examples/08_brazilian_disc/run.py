#!/usr/bin/python3
"""Example 08: Brazilian disc. Runs fdem, writes the load-displacement curve and prints the numbers.

Usage (from the repository root, after building):
    /usr/bin/python3 examples/08_brazilian_disc/run.py            # mesh 2 mm
    /usr/bin/python3 examples/08_brazilian_disc/run.py --quick    # mesh 4 mm (the CTest check)
    /usr/bin/python3 examples/08_brazilian_disc/run.py --fine     # reference: mesh 1 mm
    /usr/bin/python3 examples/08_brazilian_disc/run.py --full     # spec V4: D/l_ch = 10, 20, 40
Options: --dlch 10,20,40 (D/l_ch values: G_I scaled; D, E, f_t, G_II and the mesh fixed; more
than one writes OUT/dlch_<v>/ per value and OUT/size_effect.csv/png), --validate DIR (write
DIR/checks_brazilian.csv and figures for scripts/validate; implies the D/l_ch sweep unless
--quick), --unaligned (disc_unaligned.geo: no mesh line along the loaded diameter),
--out DIR (default out/08_brazilian_disc[_unaligned][_full]), --fdem PATH (default
build/release/fdem), --threads N (default 1), --check (exit 1 when a spec V4 target is missed),
--no-run (post-process an existing OUT).

Writes OUT/curve.csv (time, platen closure, load P, nominal stress 2P/(pi D t)), OUT/curve.png
(load-displacement) and OUT/crack.png (the disc after the split, broken joints in red), and prints
the peak load, sigma_BTS = 2 P_max/(pi D t) against f_t (spec V4 band [0.9, 1.2]) and where the
joints broke. Needs python3-vtk9 and python3-matplotlib (Debian packages), hence /usr/bin/python3.
"""
import argparse
import csv
import math
import os
import re
import sys
import tomllib

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(HERE)), "scripts"))
import labtest  # noqa: E402  (scripts/labtest.py: shared helpers of examples 08 and 09)

D = 0.050  # m: disc diameter (disc.geo)
THICKNESS = 1.0  # m: 2-D, per unit thickness
BAND = (0.9, 1.2)  # spec V4: sigma_BTS / f_t (Rocco et al. 1999)


def make_scenario(out, mesh, unaligned, dlch=10.0):
    """The scenario actually run: scenario.toml with absolute mesh paths (and the 1 mm mesh, the
    disc without the diameter line); D/l_ch other than the file's 10 by scaling G_I (l_ch =
    E G_I / f_t^2 at fixed E, f_t, D: the same mesh, a more brittle disc; G_II stays: scaled with
    G_I, D/l_ch = 40 failed first in shear at the strips' edges, README)."""
    text = open(os.path.join(HERE, "scenario.toml")).read()
    if dlch != 10.0:
        for key in ("fracture_energy_I",):
            m = re.search(rf"(?m)^{key} = ([0-9.e+-]+)", text)
            assert m, f"scenario.toml: {key} not found, update run.py"
            g = float(m.group(1)) * 10.0 / dlch
            text = text[:m.start(1)] + repr(g) + text[m.end(1):]
    if unaligned:
        text, n = re.subn(r'mesh = "disc\.geo"', 'mesh = "disc_unaligned.geo"', text)
        assert n == 1, "scenario.toml: the disc's mesh line changed, update run.py"
    text = labtest.absolute_meshes(text, HERE)
    if mesh != 2.0e-3:
        text, n = re.subn(r'(mesh_size = )2\.0e-3(\s+# m: h_max)', rf"\g<1>{mesh!r}\2", text)
        assert n == 1, "scenario.toml: the disc's mesh_size line changed, update run.py"
    path = os.path.join(out, "scenario_used.toml")
    open(path, "w").write(text)
    return path


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--full", action="store_true", help="the spec V4 sweep D/l_ch = 10, 20, 40")
    ap.add_argument("--fine", action="store_true", help="mesh 1 mm instead of 2 mm")
    ap.add_argument("--unaligned", action="store_true")
    ap.add_argument("--out")
    ap.add_argument("--fdem", default="build/release/fdem")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--no-run", action="store_true")
    ap.add_argument("--validate", metavar="DIR",
                    help="also write DIR/checks_brazilian.csv for scripts/validate's report")
    ap.add_argument("--quick", action="store_true",
                    help="mesh 4 mm, D/l_ch = 10 (scripts/validate --quick, CTest validation.brazilian)")
    ap.add_argument("--dlch", help="D/l_ch values, comma-separated (default 10; --full and "
                    "--validate without --quick: 10,20,40, spec V4)")
    a = ap.parse_args()
    base = a.out or ("out/08_brazilian_disc" + ("_unaligned" if a.unaligned else "") +
                     ("_fine" if a.fine else "") + ("_quick" if a.quick else "") +
                     ("_full" if a.full else ""))
    sweep = a.dlch or ("10,20,40" if (a.full or a.validate) and not a.quick else "10")
    dlchs = [float(x) for x in sweep.split(",")]
    results = []
    for dlch in dlchs:
        out = base if len(dlchs) == 1 else os.path.join(base, f"dlch_{dlch:g}")
        results.append(run_one(a, out, dlch))
    ok = all(r["ok"] for r in results)
    rows = []
    why = "spec fracture.md §11 V4 (ISRM 1978; Rocco et al. 1999)"
    for r in results:
        tag = f"Brazilian D/l_ch = {r['dlch']:.3g}, h = {r['h'] * 1e3:g} mm: "
        rows += [labtest.check("V4", tag + "sigma_BTS / f_t = 2 P_max/(pi D t f_t)", r["ratio"],
                               BAND[0], "range", BAND[1], "", why),
                 labtest.check("V4", tag + "broken joints at the peak within D/10 of the loaded "
                               "diameter, first breaks in the central third",
                               r["along_diameter"], 1, "bool", 0, "", why + "; labtest.crack_report"),
                 labtest.check("V4", tag + "max KE / E_elastic before the peak", r["ke_ratio"],
                               0.01, "at_most", 0, "", "spec fracture.md §11: quasi-static, <= 1 %"),
                 labtest.check("V4", tag + "the run reached its end time (no run-time check "
                               "stopped it)", r["completed"], 1, "bool", 0, "",
                               "theory §9.7 (b): contact energy born at breaks stops brittle runs"),
                 labtest.check("V4", tag + "energy error (largest energy) in the rows written",
                               r["energy_error"], 0, "report", 0, "",
                               "reported: theory §9.7 (contact energy born at breaks)")]
    if len(results) > 1:
        by = sorted(results, key=lambda r: r["dlch"])
        dec = all(by[i + 1]["ratio"] <= by[i]["ratio"] for i in range(len(by) - 1))
        print("  sigma_BTS/f_t against D/l_ch: " +
              ", ".join(f"{r['dlch']:g}: {r['ratio']:.3f}" for r in by) +
              (" (decreasing)" if dec else " (NOT decreasing)"))
        rows.append(labtest.check("V4", "Brazilian: sigma_BTS/f_t decreasing as D/l_ch grows ("
                                  + ", ".join(f"{r['dlch']:g}" for r in by) + ")", dec, 1, "bool",
                                  0, "", why))
        ok &= dec
        with open(os.path.join(base, "size_effect.csv"), "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["D_over_lch", "lch_m", "P_max_N_per_m", "sigma_BTS_over_ft"])
            for r in by:
                w.writerow([f"{r['dlch']:g}", f"{r['lch']:.6g}", f"{r['pmax']:.6g}", f"{r['ratio']:.6g}"])
        labtest.plot_curve(os.path.join(base, "size_effect.png"), [[r["dlch"] for r in by]],
                           [[r["ratio"] for r in by]], ["fdem"], xlabel="D / l_ch",
                           ylabel="sigma_BTS / f_t", xscale=1, yscale=1,
                           title="Brazilian disc: size effect (spec V4)", hline=(1.0, "f_t"))
    failed = 0
    if a.validate:
        figs = []
        for r in results:
            tag = f"Brazilian D/l_ch = {r['dlch']:.3g}, h = {r['h'] * 1e3:g} mm: "
            figs += [(os.path.join(r["out"], "curve.png"), tag + "load against platen closure (V4)"),
                     (os.path.join(r["out"], "crack.png"), tag + "broken joints (V4)")]
        if len(results) > 1:
            figs.append((os.path.join(base, "size_effect.png"), "Brazilian disc: sigma_BTS/f_t "
                         "against D/l_ch (V4)"))
        failed = labtest.write_checks(a.validate, "brazilian", rows, figs)
    if (a.check and not ok) or failed:
        sys.exit(1)


def run_one(a, out, dlch):
    """One Brazilian run at D/l_ch = dlch into OUT: curve.csv/png, crack.png, the printed numbers."""
    os.makedirs(out, exist_ok=True)
    mesh = 1.0e-3 if a.fine else 4.0e-3 if a.quick else 2.0e-3
    scen = make_scenario(out, mesh, a.unaligned, dlch)
    cfg = tomllib.load(open(scen, "rb"))
    rock = next(m for m in cfg["material"] if m["name"] == "rock")
    ft = rock["fracture"]["tensile_strength"]
    E, GI = rock["youngs_modulus"], rock["fracture"]["fracture_energy_I"]
    lch = E * GI / ft**2  # characteristic length (spec §11)

    wall = None
    if not a.no_run:
        wall = labtest.run_fdem(a.fdem, scen, out, a.threads)

    # Load from the platens' support reactions (interval averages, docs/output.md bodies.csv):
    # the force on the top platen from its support is -P (down), on the bottom one +P.
    rows = labtest.read_csv(os.path.join(out, "bodies.csv"))
    t, closure, load = labtest.platen_curve(rows, "platen_top/platen_top",
                                            "platen_bottom/platen_bottom")
    sig = [2 * p / (math.pi * D * THICKNESS) for p in load]  # ISRM 1978: sigma = 2P/(pi D t)
    ipk = max(range(len(load)), key=lambda i: load[i])
    pmax, sbts = load[ipk], sig[ipk]
    ratio = sbts / ft

    with open(os.path.join(out, "curve.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["time_s", "closure_m", "load_N_per_m", "sigma_nominal_Pa"])
        for row in zip(t, closure, load, sig):
            w.writerow([f"{x:.9g}" for x in row])

    # Elastic check before any damage: the stress at the centre against the load. Hondros (1959):
    # for a pressure over an arc 2a, sigma_xx(0) = 2P/(pi D t) (sin 2a - a)/a; sin a = b/D.
    probes = labtest.read_csv(os.path.join(out, "probes.csv"))
    alpha = math.asin(0.08)
    hondros = (math.sin(2 * alpha) - alpha) / alpha
    half = [i for i in range(len(t)) if 0.4 * pmax <= load[i] <= 0.6 * pmax and i < ipk]
    centre = [probes[i]["centre.sxx"] / (2 * load[i] / (math.pi * D * THICKNESS)) for i in half]

    hist = labtest.read_csv(os.path.join(out, "history.csv"))
    q = labtest.quasi_static(hist, t[ipk], labtest.wave_speed(rock))

    # Where the joints broke: from the frames (node copies that separated, labtest.open_edges).
    frames = labtest.frames(out)
    disc = next(b for b in cfg["body"] if b["name"] == "disc")
    o_r = labtest.break_opening(rock, disc["mesh_size"])
    crack = labtest.crack_report(out, frames, t[ipk], labtest.elastic_opening_per_length(rock), D,
                                 "disc", interval=cfg["output"]["interval"])

    labtest.plot_curve(
        os.path.join(out, "curve.png"), [closure], [load], ["fdem"],
        xlabel="platen closure [mm]", ylabel="load P [kN/m]", xscale=1e3, yscale=1e-3,
        title=f"Brazilian disc D = {D * 1e3:.0f} mm, b/D = 0.08, D/l_ch = {D / lch:.0f}",
        hline=(math.pi * D * THICKNESS * ft / 2, "P at $\\sigma_{BTS} = f_t$"))
    # picture: the first frame after the peak at which the load has fallen below half the peak
    after = [i for i in range(ipk, len(t)) if load[i] < 0.5 * pmax]
    if crack["final_frame"] and after:
        tf = t[after[0]]
        path = min(frames, key=lambda f: abs(f[0] - tf))
        labtest.plot_cracks(os.path.join(out, "crack.png"), (path[1], crack["final_frame"][1]),
                            o_r, "disc", title=f"t = {path[0] * 1e3:.2f} ms (load < P_max/2), "
                            "broken joints red", magnify=10.0)

    print(f"Brazilian disc D = {D * 1e3:.0f} mm, f_t = {ft / 1e6:g} MPa, l_ch = {lch * 1e3:.3g} mm, "
          f"D/l_ch = {D / lch:.3g}" + (f", run {wall:.1f} s" if wall else ""))
    print(f"  peak load P_max = {pmax / 1e3:.1f} kN/m at closure {closure[ipk] * 1e3:.4f} mm, "
          f"t = {t[ipk] * 1e3:.3f} ms ({t[ipk] / (D / q['c_p']):.0f} D/c_p)")
    print(f"  sigma_BTS = 2 P/(pi D t) = {sbts / 1e6:.2f} MPa, sigma_BTS/f_t = {ratio:.3f} "
          f"(spec V4: [{BAND[0]}, {BAND[1]}])")
    if centre:
        print(f"  elastic check (P = 0.4-0.6 P_max): sigma_xx(centre)/(2P/(pi D t)) = "
              f"{sum(centre) / len(centre):.3f} (mean of {len(centre)} rows; Hondros "
              f"{hondros:.4f}; one triangle, instant stress against interval-average load)")
    print(f"  before peak: max KE/E_elastic = {q['ke_ratio'] * 100:.3g} % (spec: <= 1 %; peak row "
          f"{q['ke_ratio_peak_row'] * 100:.3g} %), energy error {q['energy_error'] * 100:.3g} % of the largest energy")
    print(f"  cracks: {crack['summary']}")
    if "joints.broken" in hist[-1]:
        h = hist[-1]
        print(f"  history.csv at the end: {h['joints.broken']:.0f} joints broken, crack length "
              f"{h['crack_length'] * 1e3:.1f} mm, {h['fragments']:.0f} fragments, W_frac "
              f"{h['energy.fracture']:.3g} J/m")
    ok = BAND[0] <= ratio <= BAND[1] and crack["along_diameter"] and q["ke_ratio"] <= 0.01
    print("  V4 " + ("met" if ok else "NOT met"))
    return dict(dlch=dlch, out=out, h=disc["mesh_size"], completed=labtest.run_completed(out), lch=lch, pmax=pmax, ratio=ratio,
                along_diameter=bool(crack["along_diameter"]), ke_ratio=q["ke_ratio"],
                energy_error=q["energy_error"], ok=ok)


if __name__ == "__main__":
    main()
