#!/usr/bin/python3
"""Example 10: notched three-point bending. Runs fdem, writes the load-displacement and load-CMOD
curves, prints P_max against LEFM and the work of fracture against G_I.

Usage (from the repository root, after building):
    /usr/bin/python3 examples/10_three_point_bending/run.py           # default: D/l_ch = 10
    /usr/bin/python3 examples/10_three_point_bending/run.py --full    # D/l_ch = 5, 10, 20 (20:
                                          # to just past the peak) and unstructured at 5
Options: --sizes 5,10,20 (D/l_ch of the aligned runs), --unaligned (no mesh line along the
ligament), --h H (mesh size at the ligament, m; default 1 mm = l_ch/5), --band B (mesh size h
in |x| <= B D; default 0.25), --contact (add the smooth
contact of examples 08/09: crack-face self-contact), --end-factor F (end time x F), --out DIR
(default out/10_three_point_bending[_full]), --fdem PATH (default build/release/fdem),
--threads N (default 1), --check (exit 1 when a spec V6 target is missed), --no-run
(post-process existing runs), --validate DIR (write DIR/checks_bending.csv for scripts/validate),
--fracture KEY=VALUE (override a key of the rock's [material.fracture], repeatable),
--mesh-algorithm N (Gmsh's 2-D algorithm for the beam, e.g. 1, 5; default Gmsh's 6: other meshes
of the same sizes, the "seeds" of the unstructured run), --quick (what scripts/validate --quick and the CTest `validation` test run: D/l_ch = 5 to just
past the peak, end time x 0.3: P_max/P_LEFM, crack path, quasi-static, energy; no tail, so no
work of fracture).

Every size is the scenario.toml beam scaled by D/D_0 (D_0 = 50 mm): depth, span, coarse mesh size,
times (ramp, end time, output interval) x D/D_0, load-point speed x (D/D_0)^(-1/2) (the peak
deflection of similar beams grows like P_max ~ sqrt(D), so the time to peak stays ~ D); the mesh
size at the ligament h is the same for all (h/l_ch fixed, so Gamma of eq. 9.13 is the same).

Load P = minus the load point's interval-average support reaction (bodies.csv
beam/load.reaction_avg_y, docs/output.md), load-point displacement delta = -beam/load.uy,
CMOD = mouth_right.x - mouth_left.x - 2e (probes.csv; the two points at x = -+e = -+h on the
bottom face beside the notch mouth). Writes OUT/<run>/curve.csv, OUT/curve.png (P against delta
and against CMOD, all runs), OUT/crack.png (the default-size run at its end, broken joints red).
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
import labtest  # noqa: E402  (scripts/labtest.py: shared helpers of the lab-test examples)

D0 = 0.050  # m: depth of scenario.toml's beam (beam.geo)
F_HALF = 2.66  # SENB K calibration f(a0/D = 0.5) for S/D = 4 (ASTM E399 / Srawley, spec V6)
WOF_TOL = {"aligned": 0.05, "unaligned": 0.15}  # spec V6: work of fracture = G_I +- 5 % / 15 %
PMAX_BAND = (0.6, 1.0)  # spec V6: P_max / P_LEFM
TAIL_DELTA = 10.0  # the work of fracture is checked when the run ends at delta >= 10 delta_peak
# (README: at 4 delta_peak the A/delta^2 tail is not yet asymptotic and overshoots by ~10 %)
SEPARATED = 0.01  # a run that ends with P <= 1 % of P_max and a break within 2 h of the top has
# separated the beam: its work of fracture is the P-delta area to the end, no tail (the A/delta^2
# tail assumes a load that never vanishes; README: at D/l_ch = 10 it added 4 % of G_I to a beam
# that then needed 0.1 % more to separate)


# the spec's joint law (the published codes' law; theory §9.3a): the unstructured beam again with it
# in --full, its work of fracture reported beside the default law's (theory §9.3b, eq. 9.30)
INDEPENDENT = ("mixed_mode", '"independent"')
DEFAULT_MIXED = "proportional"  # fdem's default mixed_mode (docs/scenario.md)


def sub1(pattern, repl, text, what):
    text, n = re.subn(pattern, repl, text)
    assert n == 1, f"{what} not found once ({n}), update run.py"
    return text


def make_run(out, ratio, h, aligned, contact, end_factor, band, algorithm=None, fracture=()):
    """Write OUT/beam.geo and OUT/scenario_used.toml for D = ratio * l_ch; returns the scenario
    path. Times x D/D0, speeds x (D/D0)^-1/2, coarse mesh size x D/D0."""
    text = open(os.path.join(HERE, "scenario.toml")).read()
    cfg = tomllib.loads(text)
    rock = next(m for m in cfg["material"] if m["name"] == "rock")
    fr = rock["fracture"]
    lch = rock["youngs_modulus"] * fr["fracture_energy_I"] / fr["tensile_strength"] ** 2
    D = ratio * lch
    k = D / D0
    geo = open(os.path.join(HERE, "beam.geo")).read()
    geo = sub1(r"(?m)^D = [0-9.e+-]+;", f"D = {D!r};", geo, "beam.geo: D")
    geo = sub1(r"(?m)^h = [0-9.e+-]+;", f"h = {h!r};", geo, "beam.geo: h")
    geo = sub1(r"(?m)^aligned = [01];", f"aligned = {1 if aligned else 0};", geo,
               "beam.geo: aligned")
    geo = sub1(r"(?m)^band = [0-9.e+-]+;", f"band = {band!r};", geo, "beam.geo: band")
    if algorithm is not None:  # another unstructured mesh of the same sizes (spec V7's "seeds")
        geo += f"Mesh.Algorithm = {algorithm:d};\n"
    open(os.path.join(out, "beam.geo"), "w").write(geo)
    text = sub1(r'mesh = "beam\.geo"', f'mesh = "{os.path.join(out, "beam.geo")}"', text,
                "scenario.toml: the beam's mesh")
    text = sub1(r"(?m)^end_time = [0-9.e+-]+",
                f"end_time = {cfg['simulation']['end_time'] * k * end_factor!r}", text, "end_time")
    text = sub1(r"(?m)^interval = [0-9.e+-]+", f"interval = {cfg['output']['interval'] * k!r}",
                text, "interval")
    text = sub1(r"(?m)^mesh_size = [0-9.e+-]+", f"mesh_size = {cfg['body'][0]['mesh_size'] * k!r}",
                text, "mesh_size")
    text = re.sub(r"(?m)^(start|end) = ([0-9.e+-]+)",
                  lambda m: f"{m.group(1)} = {float(m.group(2)) * k!r}", text)
    text = re.sub(r"(?m)^velocity = \[0\.0, (-[0-9.e+-]+)\]",
                  lambda m: f"velocity = [0.0, {float(m.group(1)) / math.sqrt(k)!r}]", text)
    for key, value in fracture:  # --fracture KEY=VALUE: a key of the rock's [material.fracture]
        text = sub1(rf"(?m)^{re.escape(key)} = [^#\n]*?(\s*#|$)", f"{key} = {value}\\1", text,
                    f"scenario.toml: [material.fracture] {key}")
    if contact:
        text += ("\n[contact]\nalgorithm = \"smooth\"\nedge_targets = false\n"
                 "friction = 0.577\n")
    path = os.path.join(out, "scenario_used.toml")
    open(path, "w").write(text)
    return path


def read_curve(d, e):
    """time, delta, CMOD, P and the work of P from bodies.csv and probes.csv of run folder d. P
    is an interval average, so delta and CMOD (instants at the row's time) are averaged over the
    interval too (labtest.platen_curve does the same); the work of P is exact for a prescribed
    velocity constant over an interval: sum of P_avg x (delta_i - delta_{i-1}) (eq. 8.4)."""
    rows = labtest.read_csv(os.path.join(d, "bodies.csv"))
    probes = labtest.read_csv(os.path.join(d, "probes.csv"))
    n = min(len(rows), len(probes))
    t, delta, cmod, load = [], [], [], []
    pd, pc = 0.0, 0.0
    work = 0.0
    for r, p in zip(rows[:n], probes[:n]):
        dl = -r["beam/load.uy"]
        cm = p["mouth_right.x"] - p["mouth_left.x"] - 2 * e
        t.append(r["time"])
        delta.append(0.5 * (pd + dl))
        cmod.append(0.5 * (pc + cm))
        load.append(-r["beam/load.reaction_avg_y"])
        work += load[-1] * (dl - pd)
        pd, pc = dl, cm
    return t, delta, cmod, load, work


def tail_work(delta, load, ipk):
    """The work beyond the last row from the fit P = A/delta^2 of the rows past the peak where P < P_max/5 (the far tail of a beam
    hinging about the load point: Elices, Guinea and Planas 1992, recalled): int_end^inf A/d^2 =
    A/delta_end. Returns (W tail estimate, A)."""
    pts = [(delta[i], load[i]) for i in range(ipk, len(delta))
           if 0 < load[i] < load[ipk] / 5 and delta[i] > 0]
    A = tail = float("nan")
    if len(pts) >= 3:
        # least squares of P = A x with x = 1/delta^2
        sxx = sum((1 / d ** 2) ** 2 for d, _ in pts)
        sxy = sum(p / d ** 2 for d, p in pts)
        A = sxy / sxx
        tail = A / delta[-1]
    return tail, A


def crack_stats(d, h, ligament):
    """Breaks of cracks.csv (pre-broken notch joints are not in it): how many, their length,
    the share of length within |x| <= h of the ligament x = 0, the largest |x|."""
    path = os.path.join(d, "cracks.csv")
    ev = labtest.read_csv(path) if os.path.exists(path) else []
    L = sum(e["h"] for e in ev)
    on = sum(e["h"] for e in ev if abs(e["x"]) <= h)
    mode = {}
    for e in ev:
        mode[int(e["mode"])] = mode.get(int(e["mode"]), 0) + 1
    gI = [e for e in ev if int(e["mode"]) == 1]
    return {"n": len(ev), "length": L, "on": on, "share": on / L if L else float("nan"),
            "max_x": max((abs(e["x"]) for e in ev), default=float("nan")),
            "ymax": max((e["y"] for e in ev if abs(e["x"]) <= h), default=float("nan")),
            "ytop": max((e["y"] for e in ev), default=float("nan")),
            "modes": mode, "ligament": ligament,
            "gamma_I": (sum(e["work"] for e in gI) / sum(e["h"] for e in gI)) if gI else
            float("nan")}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--full", action="store_true")
    ap.add_argument("--quick", action="store_true",
                    help="the default size (scripts/validate --quick)")
    ap.add_argument("--sizes")
    ap.add_argument("--unaligned", action="store_true")
    ap.add_argument("--h", type=float, default=1.0e-3)
    ap.add_argument("--contact", action="store_true")
    ap.add_argument("--band", type=float, default=0.25)
    ap.add_argument("--end-factor", type=float, default=1.0)
    ap.add_argument("--fracture", action="append", default=[], metavar="KEY=VALUE",
                    help="override a key of the rock's [material.fracture] (repeatable), e.g. "
                         "fracture_energy_II=25.0")
    ap.add_argument("--mesh-algorithm", type=int, choices=[1, 2, 5, 6, 8],
                    help="Gmsh's 2-D algorithm for beam.geo (default: Gmsh's, 6): another "
                         "mesh of the same sizes, e.g. for the unstructured run's scatter")
    ap.add_argument("--out")
    ap.add_argument("--fdem", default="build/release/fdem")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--no-run", action="store_true")
    ap.add_argument("--validate", metavar="DIR",
                    help="also write DIR/checks_bending.csv for scripts/validate's report")
    a = ap.parse_args()
    fracture = []
    for item in a.fracture:
        key, sep, value = item.partition("=")
        if not sep or not re.fullmatch(r"[a-z_I]+", key) or not value:
            ap.error(f"--fracture {item!r}: expected KEY=VALUE, e.g. fracture_energy_II=25.0")
        base = tomllib.load(open(os.path.join(HERE, "scenario.toml"), "rb"))
        keys = next(m for m in base["material"] if m["name"] == "rock")["fracture"]
        if key not in keys:
            ap.error(f"--fracture {item!r}: {key} is not a key of the rock's [material.fracture] "
                     f"in scenario.toml ({', '.join(keys)})")
        fracture.append((key, value))
    if a.quick:  # the CTest `validation` run: D/l_ch = 5 to just past the peak
        a.sizes = a.sizes or "5"
        a.end_factor = 0.3 if a.end_factor == 1.0 else a.end_factor
    sizes = [float(s) for s in (a.sizes or ("5,10,20" if a.full else "10")).split(",")]
    runs_spec = [(r, not a.unaligned, a.band, a.end_factor, []) for r in sizes]
    if a.full and not a.sizes:
        # D/l_ch = 20 to just past the peak only (the tail would cost 8 x the default run), with
        # the fine band |x| <= D/8 instead of D/4 (half the triangles; the band is >= 2.5 l_ch
        # wide either way); spec V6's unstructured run at the cheapest size
        # D/l_ch = 5 (aligned and unstructured) to delta ~ 13 delta_peak (end time x 3) and
        # D/l_ch = 10 to complete separation (end time x 6, ~25 delta_peak, ~28 min on one core):
        # the work-of-fracture checks
        # and the unstructured run again with the spec's law, mixed_mode = "independent" (theory
        # §9.3a: it makes the zigzag crack's inclined joints pay eq. 9.29's premium), reported
        runs_spec = [(5.0, True, a.band, 3 * a.end_factor, []),
                     (10.0, True, a.band, 6 * a.end_factor, []),
                     (20.0, True, 0.125, 0.35 * a.end_factor, []),
                     (5.0, False, a.band, 3 * a.end_factor, []),
                     (5.0, False, a.band, 3 * a.end_factor, [INDEPENDENT])]
    out = a.out or ("out/10_three_point_bending" + ("_full" if a.full else "") +
                    ("_quick" if a.quick else ""))
    os.makedirs(out, exist_ok=True)

    runs = []
    for ratio, aligned, band, end_factor, extra in runs_spec:
        overrides = fracture + extra
        name = f"D_lch_{ratio:g}" + ("" if aligned else "_unaligned") + (
            f"_alg{a.mesh_algorithm}" if a.mesh_algorithm is not None else "") + "".join(
            f"_{k}={v.strip(chr(34))}" for k, v in overrides)  # no quotes in a folder name
        d = os.path.join(out, name)
        os.makedirs(d, exist_ok=True)
        scen = make_run(d, ratio, a.h, aligned, a.contact, end_factor, band, a.mesh_algorithm,
                        overrides)
        wall = None
        if not a.no_run:
            wall = labtest.run_fdem(a.fdem, scen, d, a.threads, what=name + ": ")
        cfg = tomllib.load(open(scen, "rb"))
        rock = next(m for m in cfg["material"] if m["name"] == "rock")
        fr = rock["fracture"]
        E, nu = rock["youngs_modulus"], rock["poisson_ratio"]
        Ep = E / (1 - nu * nu) if rock.get("plane", "strain") == "strain" else E  # theory §2.3
        GI, ft = fr["fracture_energy_I"], fr["tensile_strength"]
        p = fr.get("penalty", "auto")
        p = 10.0 * E if p == "auto" else p
        lch = E * GI / ft ** 2
        D = ratio * lch
        S, a0 = 4 * D, D / 2
        KIc = math.sqrt(Ep * GI)
        P_lefm = KIc * D ** 1.5 / (S * F_HALF)  # spec V6, B = 1 m
        gamma = GI + 4.0 / 3.0 * a.h * ft ** 2 / p  # theory eq. 9.13 at the ligament's h
        t, delta, cmod, load, W = read_curve(d, a.h)
        ipk = max(range(len(load)), key=lambda i: load[i])
        tail, A = tail_work(delta, load, ipk)
        hist = labtest.read_csv(os.path.join(d, "history.csv"))
        q = labtest.quasi_static(hist, t[ipk], labtest.wave_speed(rock))
        cs = crack_stats(d, a.h, D - a0)
        last = hist[-1]
        with open(os.path.join(d, "curve.csv"), "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["time_s", "delta_m", "cmod_m", "load_N_per_m"])
            for row in zip(t, delta, cmod, load):
                w.writerow([f"{v:.9g}" for v in row])
        runs.append(dict(name=name, ratio=ratio, aligned=aligned, dir=d, cfg=cfg, rock=rock,
                         D=D, S=S, a0=a0, P_lefm=P_lefm, gamma=gamma, GI=GI, KIc=KIc, Ep=Ep,
                         t=t, delta=delta, cmod=cmod, load=load, ipk=ipk, W=W, tail=tail, A=A,
                         q=q, cs=cs, last=last, wall=wall, lch=lch))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axs = plt.subplots(1, 2, figsize=(10, 4.2))
    for r in runs:
        lab = f"D/l_ch = {r['ratio']:g}" + ("" if r["aligned"] else " unstructured") + (
            "" if r["rock"]["fracture"].get("mixed_mode", DEFAULT_MIXED) == DEFAULT_MIXED
            else ", " + r["rock"]["fracture"]["mixed_mode"])
        axs[0].plot([x * 1e6 for x in r["delta"]], [P / r["P_lefm"] for P in r["load"]], label=lab)
        axs[1].plot([x * 1e6 for x in r["cmod"]], [P / r["P_lefm"] for P in r["load"]], label=lab)
    for ax, xl in ((axs[0], "load-point displacement δ [µm]"), (axs[1], "CMOD [µm]")):
        ax.axhline(1.0, color="0.5", ls="--", lw=1)
        ax.set_xlabel(xl)
        ax.set_ylabel("P / P_LEFM")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("notched three-point bending, S/D = 4, a0/D = 0.5: P_LEFM = K_Ic D^1.5/(S f(0.5))",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "curve.png"), dpi=100)
    plt.close(fig)

    pic = next((r for r in runs if r["ratio"] == 10 and r["aligned"]), runs[0])
    fr_list = labtest.frames(pic["dir"])
    if fr_list:
        je = labtest.JointEdges(fr_list[0][1], "beam")
        o_r = labtest.break_opening(pic["rock"], a.h)
        labtest.plot_cracks(os.path.join(out, "crack.png"), (fr_list[-1][1], je), o_r, "beam",
                            title=f"{pic['name']}, t = {fr_list[-1][0] * 1e3:.2f} ms",
                            magnify=20.0)

    ok = True
    rows_v = []
    why = "spec fracture.md §11 V6"
    for r in runs:
        i = r["ipk"]
        cs, q = r["cs"], r["q"]
        lig = r["D"] - r["a0"]
        wof = r["W"] / lig
        wof_tail = (r["W"] + (r["tail"] if math.isfinite(r["tail"]) else 0.0)) / lig
        wfrac = r["last"].get("energy.fracture", float("nan")) / lig
        ratio_p = r["load"][i] / r["P_lefm"]
        tp_lcp = r["t"][i] / (r["S"] / q["c_p"])
        tol = WOF_TOL["aligned" if r["aligned"] else "unaligned"]
        print(f"{r['name']}: D = {r['D'] * 1e3:g} mm, S = {r['S'] * 1e3:g} mm, h = {a.h * 1e3:g} mm"
              + (f", run {r['wall']:.0f} s" if r["wall"] else ""))
        print(f"  P_max = {r['load'][i]:.1f} N/m at delta = {r['delta'][i] * 1e6:.2f} um, "
              f"CMOD = {r['cmod'][i] * 1e6:.2f} um, t = {r['t'][i] * 1e3:.3f} ms "
              f"({tp_lcp:.0f} S/c_p); P_LEFM = {r['P_lefm']:.1f} N/m "
              f"(K_Ic = sqrt(E' G_I) = {r['KIc'] / 1e6:.4f} MPa m^0.5, E' = {r['Ep'] / 1e9:.3f} GPa)"
              f"; P_max/P_LEFM = {ratio_p:.3f}")
        print(f"  work of fracture W/(B(D - a0)) = {wof:.2f} J/m^2 to the end "
              f"(delta = {r['delta'][-1] * 1e6:.1f} um, P = {r['load'][-1] / r['load'][i] * 100:.1f} % "
              f"of P_max), with the A/delta^2 tail {wof_tail:.2f} J/m^2; "
              f"G_I = {r['GI']:g}, Gamma (eq. 9.13) = {r['gamma']:.3f} J/m^2; "
              f"W_frac/(D - a0) (history) = {wfrac:.2f} J/m^2")
        print(f"  breaks: {cs['n']} joints, {cs['length'] * 1e3:.1f} mm "
              f"({cs['length'] / lig * 100:.0f} % of the ligament), {cs['share'] * 100:.1f} % of "
              f"it within |x| <= h, largest |x| = {cs['max_x'] * 1e3:.2f} mm, crack tip at "
              f"y = {cs['ymax'] * 1e3:.1f} mm (top {r['D'] * 1e3:g} mm); modes {cs['modes']}; "
              f"Gamma_I (eq. 9.20) = {cs['gamma_I']:.3f} J/m^2")
        print(f"  quasi-static: max KE/E_elastic before the peak {q['ke_ratio'] * 100:.3g} % "
              f"(peak row {q['ke_ratio_peak_row'] * 100:.3g} %); energy error {q['energy_error'] * 100:.3g} %"
              f"; KE at the end {r['last']['kinetic']:.3g} J/m")
        mixed = r["rock"]["fracture"].get("mixed_mode", DEFAULT_MIXED)
        tag = (f"3PB D/l_ch = {r['ratio']:g}" + (", aligned" if r["aligned"] else ", unstructured")
               + f", h = {a.h * 1e3:g} mm" + ("" if mixed == DEFAULT_MIXED else
                                              f", mixed_mode = {mixed}") + ": ")
        # the spec's law on an unstructured mesh: its work of fracture is information (theory
        # §9.3a: 1.19-1.25 G_I on three meshes at h = 1 mm, outside V6's ± 15 %), the default
        # law's is the check
        info = mixed == "independent" and not r["aligned"]
        rows_v.append(labtest.check("V6", tag + "P_max / P_LEFM", ratio_p, PMAX_BAND[0], "range",
                                    PMAX_BAND[1], "", why + ": [0.6, 1.0]"))
        # the jointed beam is softer than the rock (eq. 9.6: E_eff = E/(1 + 2E/p) on a structured
        # mesh), and G = K^2/E' of the jointed continuum: P_LEFM with E_eff for information
        p_pen = r["rock"]["fracture"].get("penalty", "auto")
        p_pen = 10.0 * r["rock"]["youngs_modulus"] if p_pen == "auto" else p_pen
        eff = 1.0 / (1.0 + 2.0 * r["rock"]["youngs_modulus"] / p_pen)
        rows_v.append(labtest.check("V6", tag + "P_max / P_LEFM with E_eff = E/(1 + 2E/p) of eq. "
                                    "9.6 in K_Ic", ratio_p / math.sqrt(eff), 1.0, "report", 0, "",
                                    "theory eq. 9.6 (information: the joints' compliance)"))
        reach = r["delta"][-1] / r["delta"][i]
        separated = (r["load"][-1] <= SEPARATED * r["load"][i]
                     and cs["ytop"] >= r["D"] - 2.0 * a.h)
        if separated:  # the whole ligament broke: the area to the end is the work of fracture
            wof_tail = wof
            print(f"  separated (P = {r['load'][-1] / r['load'][i] * 100:.1f} % of P_max, a break "
                  f"at y = {cs['ytop'] * 1e3:.1f} mm): work of fracture = the area to the end, "
                  f"{wof:.2f} J/m^2 = {wof / r['GI']:.4f} G_I")
        if r["load"][-1] <= 0.4 * r["load"][i]:  # past the steep drop: a tail to report
            long_ = reach >= TAIL_DELTA or separated
            how = (f"P-delta area to complete separation at delta = {reach:.1f} delta_peak"
                   if separated else
                   f"P-delta area to delta_end = {reach:.1f} delta_peak + A/delta^2 tail")
            rows_v.append(labtest.check("V6", tag + f"work of fracture W/(B(D - a0)) / G_I ({how})",
                                        wof_tail / r["GI"], 1.0, "rel" if long_ and not info else
                                        "report", tol, "",
                                        why + f": G_I ± {tol * 100:g} % (RILEM)" +
                                        ("; not checked: the spec's law, mixed_mode = "
                                         "\"independent\" (theory §9.3a), for comparison with "
                                         "the default law's row" if info else "") +
                                        ("" if long_ else f"; not checked: the run ends before "
                                         f"{TAIL_DELTA:g} delta_peak, the tail fit overshoots")))
            rows_v.append(labtest.check("V6", tag + "work of fracture / Gamma of eq. 9.13 (what "
                                        "a broken joint dissipates)", wof_tail / r["gamma"], 1.0,
                                        "report", 0, "", "theory eq. 9.13"))
            rows_v.append(labtest.check("V6", tag + "P-delta area to the end of the run (no tail) "
                                        "/ (B(D - a0)) / G_I", wof / r["GI"], 1.0, "report", 0,
                                        "", "the tail's share: the row above minus this one"))
            rows_v.append(labtest.check("V6", tag + "fracture dissipation at the end of the run "
                                        "(history.csv energy.fracture) / (D - a0) / Gamma",
                                        wfrac / r["gamma"], 1.0, "report", 0, "",
                                        "theory eqs. 9.13, 9.19"))
            if long_ and not info:
                ok &= abs(wof_tail / r["GI"] - 1) <= tol
            elif info:
                print("  (the spec's law, mixed_mode = \"independent\": work of fracture reported "
                      "for comparison, not checked)")
            else:
                print(f"  (run ends at delta = {reach:.1f} delta_peak < {TAIL_DELTA:g}: work of "
                      "fracture reported, not checked)")
        else:
            print(f"  (run ends at P = {r['load'][-1] / r['load'][i] * 100:.0f} % of P_max, before "
                  "the tail: no work of fracture)")
        rows_v.append(labtest.check("V6", tag + "share of the broken length within ±h of the "
                                    "ligament", cs["share"], 1.0 if r["aligned"] else 0.0,
                                    "report" if not r["aligned"] else "at_least", 0, "",
                                    why + ": crack within ±h of the ligament"))
        rows_v.append(labtest.check("V6", tag + "max KE / E_elastic before the peak",
                                    q["ke_ratio"], 0.01, "at_most", 0, "",
                                    "spec fracture.md §11: quasi-static, <= 1 %"))
        rows_v.append(labtest.check("V6", tag + "time to peak / (S/c_p)", tp_lcp, 50, "at_least",
                                    0, "", "spec fracture.md §11: >= 50 L/c_p"))
        rows_v.append(labtest.check("V6", tag + "energy error (largest energy) to the end",
                                    q["energy_error"], 0.01, "at_most", 0, "",
                                    why + ": energy balance <= 1 %"))
        ok &= PMAX_BAND[0] <= ratio_p <= PMAX_BAND[1] and q["ke_ratio"] <= 0.01
        ok &= q["energy_error"] <= 0.01 and (cs["share"] >= 1.0 or not r["aligned"])
    al = [r for r in runs if r["aligned"]]
    if len(al) >= 2:
        seq = [r["load"][r["ipk"]] / r["P_lefm"] for r in al]
        inc = all(b > a_ for a_, b in zip(seq, seq[1:]))
        print("  P_max/P_LEFM against D/l_ch: " + ", ".join(
            f"{r['ratio']:g}: {s:.3f}" for r, s in zip(al, seq)) +
            (" (increasing)" if inc else " (NOT increasing)"))
        rows_v.append(labtest.check("V6", "3PB: P_max/P_LEFM increases with D/l_ch (" +
                                    ", ".join(f"{r['ratio']:g}" for r in al) + ")",
                                    1.0 if inc else 0.0, 1.0, "bool", 0, "",
                                    why + ": size effect towards LEFM"))
        ok &= inc
    print("  V6 " + ("met" if ok else "NOT met"))
    failed = 0
    if a.validate:
        failed = labtest.write_checks(
            a.validate, "bending", rows_v,
            [(os.path.join(out, "curve.png"), "three-point bending: P/P_LEFM against δ and CMOD (V6)"),
             (os.path.join(out, "crack.png"), "three-point bending: broken joints (V6)")])
    if (a.check and not ok) or failed:
        sys.exit(1)


if __name__ == "__main__":
    main()
