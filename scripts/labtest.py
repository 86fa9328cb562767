"""Shared post-processing of the lab-test examples (08 Brazilian disc, 09 UCS).

Reads what every fdem run writes (docs/output.md): bodies.csv (platen reactions and motion),
history.csv (energies), cracks.csv (the break events) and the VTU frames (node positions and
displacements). For the pictures and the process zone, broken and softening joints are found
geometrically from the frames: with fracture
every triangle owns its nodes, the copies of one mesh vertex share the reference position
X = x - displacement, and a joint is counted as broken when at least 2 of its 3 Simpson points
(the two ends and the mid-point, theory eqs. 9.2-9.3) have separated by more than the mode-I break
opening o_r = o_p + G_I/(I_z f_t) (theory eqs. 9.4, 9.12 `exact`; eq. 9.15 with 2 points). That is
the break rule for pure opening; a joint broken in shear separates by s_r instead, which for the
rock of these examples is larger, so shear breaks are counted once they have opened by o_r.
Needs numpy, python3-vtk9 and matplotlib (/usr/bin/python3 on the development machine).
"""
import csv
import math
import os
import re
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

import numpy as np

I_Z = 0.386307  # theory eq. 9.11 (Evans-Marathe softening)


def run_fdem(fdem, scen, out, threads, what=""):
    """Run `fdem run scen --out out`; the wall time [s]. Exit 1 (a run-time check stopped it,
    message printed by fdem) lets the caller evaluate the rows written; other failures exit."""
    t0 = time.time()
    rc = subprocess.run([fdem, "run", scen, "--out", out, "--quiet", "--threads",
                         str(threads)]).returncode
    if rc == 1:
        print(f"note: {what}fdem stopped early (exit 1); evaluating the rows written before")
    elif rc != 0:
        sys.exit(rc)
    with open(os.path.join(out, "run_status.txt"), "w") as f:
        f.write("completed\n" if rc == 0 else "stopped early (exit 1)\n")
    return time.time() - t0


def run_completed(out):
    """True if the last run_fdem into OUT reached its end time (OUT/run_status.txt)."""
    path = os.path.join(out, "run_status.txt")
    return os.path.exists(path) and open(path).read().startswith("completed")


def absolute_meshes(text, folder):
    """Scenario text with every `mesh = "file"` made absolute (the scenario is written elsewhere)."""
    return re.sub(r'mesh = "([^"/][^"]*)"',
                  lambda m: f'mesh = "{os.path.join(folder, m.group(1))}"', text)


def read_csv(path):
    """Rows of an fdem CSV as dicts of floats (an incomplete last line is skipped)."""
    rows = []
    with open(path, newline="") as f:
        r = csv.DictReader(f)
        for row in r:
            try:
                rows.append({k: float(v) for k, v in row.items()})
            except (TypeError, ValueError):
                break
    return rows


def platen_curve(rows, top, bottom):
    """Time, platen closure and load P from bodies.csv.

    P is the mean of the two platens' interval-average support reactions (theory eq. 8.4): the
    top support pushes its platen down with -P, the bottom one up with +P. The average over an
    interval belongs with the closure at the interval's middle, so the closure is averaged too.
    """
    t, closure, load = [], [], []
    prev_c = 0.0
    for r in rows:
        c = r[bottom + ".uy"] - r[top + ".uy"]
        t.append(r["time"])
        closure.append(0.5 * (prev_c + c))
        load.append(0.5 * (r[bottom + ".reaction_avg_y"] - r[top + ".reaction_avg_y"]))
        prev_c = c
    return t, closure, load


def wave_speed(mat):
    """P-wave speed c_p = sqrt((lambda + 2 mu)/rho) (theory eq. 2.5, 5.3), plane strain or stress."""
    E, nu, rho = mat["youngs_modulus"], mat["poisson_ratio"], mat["density"]
    if mat.get("plane", "strain") == "strain":
        m = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu))
    else:
        m = E / (1 - nu * nu)
    return math.sqrt(m / rho)


def quasi_static(hist, t_peak, c_p):
    """Kinetic/strain ratio before the peak and the energy balance of a platen-driven run.

    The platens move at constant speed from the first step on, so their kinetic energy is the
    first row's (the specimen has not moved yet); it is subtracted. The ratio (to the elastic
    energy of the elements and joints) is taken over the second half of the loading, rows
    t_peak/2 <= t < t_peak; the peak row's own value is returned too (its interval may already
    hold the start of the failure).
    """
    ke0 = hist[0]["kinetic"]
    ratios = [(h["kinetic"] - ke0) / (h["strain"] + h.get("energy.joint", 0.0)) for h in hist
              if 0.5 * t_peak <= h["time"] < t_peak and h["strain"] > 0]
    at_peak = [(h["kinetic"] - ke0) / (h["strain"] + h.get("energy.joint", 0.0)) for h in hist
               if h["time"] == t_peak]
    scale = max(max(abs(h["work_external"]), h["kinetic"] + h["strain"] + h["contact"] +
                    h.get("energy.joint", 0.0)) for h in hist)
    err = max(abs(h["energy_error"]) for h in hist)
    return {"ke_ratio": max(ratios) if ratios else float("nan"), "energy_error": err / scale,
            "ke_ratio_peak_row": at_peak[0] if at_peak else float("nan"),
            "c_p": c_p}


def frames(out):
    """(time, path) of every frame listed in OUT/series.pvd."""
    pvd = os.path.join(out, "series.pvd")
    if not os.path.exists(pvd):
        return []
    res = []
    for ds in ET.parse(pvd).getroot().iter("DataSet"):
        res.append((float(ds.get("timestep")), os.path.join(out, ds.get("file"))))
    return sorted(res)


def elastic_opening_per_length(mat):
    """o_p / h = 2 f_t / p (theory eq. 9.4)."""
    fr = mat["fracture"]
    p = fr.get("penalty", "auto")
    p = 10.0 * mat["youngs_modulus"] if p == "auto" else p
    return 2.0 * fr["tensile_strength"] / p


def break_opening(mat, mesh_size):
    """Mode-I break opening o_r = 2 h f_t/p + G_I/(I_z f_t) (theory eqs. 9.4, 9.12 `exact`)."""
    fr = mat["fracture"]
    ft, GI = fr["tensile_strength"], fr["fracture_energy_I"]
    p = fr.get("penalty", "auto")
    p = 10.0 * mat["youngs_modulus"] if p == "auto" else p
    return 2.0 * mesh_size * ft / p + GI / (I_Z * ft)


def read_frame(path):
    from vtk import vtkXMLUnstructuredGridReader
    from vtk.util.numpy_support import vtk_to_numpy
    r = vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    g = r.GetOutput()
    x = vtk_to_numpy(g.GetPoints().GetData())[:, :2].copy()
    u = vtk_to_numpy(g.GetPointData().GetArray("displacement"))[:, :2].copy()
    conn = vtk_to_numpy(g.GetCells().GetConnectivityArray()).reshape(-1, 3).copy()
    body = vtk_to_numpy(g.GetCellData().GetArray("body")).copy()
    names_arr = g.GetFieldData().GetAbstractArray("body_name")
    names = [names_arr.GetValue(i) for i in range(names_arr.GetNumberOfValues())]
    return x, u, conn, body, names


class JointEdges:
    """Internal edges of one body entry, as pairs of node copies, built from a frame."""

    def __init__(self, path, body_name):
        x, u, conn, body, names = read_frame(path)
        ids = [i for i, n in enumerate(names) if n == body_name]
        tris = conn[np.isin(body, ids)]
        X = x - u
        self.tris = tris
        key = np.round(X / 1e-9).astype(np.int64)  # reference position on a 1 nm grid
        vkey = {}
        vid = np.empty(len(x), dtype=np.int64)
        for i, k in enumerate(map(tuple, key)):
            vid[i] = vkey.setdefault(k, len(vkey))
        edges = {}
        for tri in tris:
            for a, b in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])):
                ka, kb = vid[a], vid[b]
                e = (ka, kb) if ka < kb else (kb, ka)
                # store the copies in the order of the sorted vertex pair
                edges.setdefault(e, []).append((a, b) if ka < kb else (b, a))
        pairs = [v for v in edges.values() if len(v) == 2]
        self.a1 = np.array([p[0][0] for p in pairs])  # vertex 1, copy in triangle 1
        self.b1 = np.array([p[1][0] for p in pairs])  # vertex 1, copy in triangle 2
        self.a2 = np.array([p[0][1] for p in pairs])
        self.b2 = np.array([p[1][1] for p in pairs])
        # unit normal of every joint in the reference configuration, pointing from triangle 2's
        # side into triangle 1 (so n . (x_copy1 - x_copy2) > 0 is opening)
        tri_of = {}
        for tri in tris:
            for a in tri:
                tri_of[a] = tri
        e = X[self.a2] - X[self.a1]
        n = np.stack([-e[:, 1], e[:, 0]], axis=1) / np.linalg.norm(e, axis=1)[:, None]
        c1 = np.array([X[tri_of[a]].mean(axis=0) for a in self.a1])
        flip = np.einsum("ij,ij->i", n, c1 - 0.5 * (X[self.a1] + X[self.a2])) < 0
        n[flip] *= -1
        self.n = n
        self.X = X
        self.mid = 0.5 * (X[self.a1] + X[self.a2])
        self.length = np.linalg.norm(X[self.a1] - X[self.a2], axis=1)

    def past_elastic_limit(self, x, o_p_per_m):
        """Mask of joints opened beyond the elastic limit o_p = 2 h f_t/p (theory eq. 9.4) at
        an end or the mid-point, normal opening in the reference normal (small rotations):
        the joints in softening or broken (mode I)."""
        da = np.einsum("ij,ij->i", x[self.a1] - x[self.b1], self.n)
        db = np.einsum("ij,ij->i", x[self.a2] - x[self.b2], self.n)
        o_p = o_p_per_m * self.length
        return (da > o_p) | (db > o_p) | (0.5 * (da + db) > o_p)

    def broken(self, x, o_r):
        """Mask of joints with >= 2 of 3 Simpson points separated by more than o_r."""
        da = x[self.a1] - x[self.b1]
        db = x[self.a2] - x[self.b2]
        n = (np.linalg.norm(da, axis=1) > o_r).astype(int) + \
            (np.linalg.norm(db, axis=1) > o_r).astype(int) + \
            (np.linalg.norm(0.5 * (da + db), axis=1) > o_r).astype(int)
        return n >= 2


def crack_report(out, frame_list, t_peak, o_p_per_m, D, body_name, interval=None):
    """Where joints softened and broke. Breaks from OUT/cracks.csv (one row per break: time,
    mid-point, mode; docs/output.md), the process zone at the peak from the peak row's frame
    (joints opened past the elastic limit). The loaded diameter is x = 0. Spec V4: broken joints
    at peak within +-D/10 of it (here: the breaks up to the peak row, whose interval holds the
    largest average load; if none broke by then and INTERVAL, the output interval, is given: the
    breaks of the next interval), first breaks within the central third |y| <= D/6 (here: the
    first five breaks)."""
    res = {"along_diameter": False, "final_frame": None, "summary": "no output"}
    parts = []
    if frame_list:
        je = JointEdges(frame_list[0][1], body_name)
        res["final_frame"] = (frame_list[-1][1], je)
        ipk = min(range(len(frame_list)), key=lambda i: abs(frame_list[i][0] - t_peak))
        x = read_frame(frame_list[ipk][1])[0]
        soft = je.past_elastic_limit(x, o_p_per_m)
        if soft.any():
            y = je.mid[soft, 1]
            near = np.abs(je.mid[soft, 0]) <= D / 10
            parts.append(f"at the peak row (t = {frame_list[ipk][0] * 1e3:.3f} ms) {soft.sum()} "
                         f"joints opened past the elastic limit, {near.sum()} of them within "
                         f"|x| <= D/10, y from {y.min() * 1e3:.1f} to {y.max() * 1e3:.1f} mm")
    path = os.path.join(out, "cracks.csv")
    ev = read_csv(path) if os.path.exists(path) else []
    ok = bool(ev)
    if ev:
        ev.sort(key=lambda e: (e["time"], e["joint"]))
        mode = {1: "I", 2: "II", 3: "mixed"}
        first = ev[:5]
        central = [abs(e["y"]) <= D / 6 for e in first]
        parts.append("first breaks: " + ", ".join(
            f"t = {e['time'] * 1e3:.4f} ms ({e['x'] * 1e3:.1f}, {e['y'] * 1e3:.1f}) mm "
            f"mode {mode.get(int(e['mode']), '?')}" for e in first) +
            f"; {sum(central)}/{len(first)} in the central third |y| <= D/6")
        ok &= all(central)
        upto = [e for e in ev if e["time"] <= t_peak]
        label = "up to the peak row"
        if not upto and interval:
            # the load can peak while the process zone softens, before any joint breaks: then
            # the breaks of the interval after the peak row (the load's first drop) stand for it
            upto = [e for e in ev if e["time"] <= t_peak + interval]
            label = "in the interval after the peak row (none before it)"
        if upto:
            near = [abs(e["x"]) <= D / 10 for e in upto]
            L = sum(e["h"] for e in upto)
            Ln = sum(e["h"] for e, n in zip(upto, near) if n)
            parts.append(f"breaks {label}: {len(upto)}, "
                         f"{L * 1e3:.1f} mm, {Ln / L * 100:.0f} % of the length within |x| <= D/10")
            ok &= all(near)
        else:
            parts.append("no break up to the peak row")
            ok = False
        near = [abs(e["x"]) <= D / 10 for e in ev]
        L = sum(e["h"] for e in ev)
        parts.append(f"all breaks: {len(ev)}, {L * 1e3:.1f} mm, "
                     f"{sum(e['h'] for e, n in zip(ev, near) if n) / L * 100:.0f} % within "
                     f"|x| <= D/10, last at t = {ev[-1]['time'] * 1e3:.3f} ms")
    else:
        parts.append("no joint broke (cracks.csv empty or missing)")
    res["along_diameter"] = ok
    res["summary"] = ";\n    ".join(parts)
    return res


def plot_curve(png, xs, ys, labels, xlabel, ylabel, xscale, yscale, title, hline=None):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for x, y, lab in zip(xs, ys, labels):
        ax.plot(np.array(x) * xscale, np.array(y) * yscale, label=lab)
    if hline:
        ax.axhline(hline[0] * yscale, color="0.5", ls="--", lw=1, label=hline[1])
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=100)
    plt.close(fig)


def plot_cracks(png, final, o_r, body_name, title, magnify=20.0):
    """Left: reference mesh with the broken joints in red; right: displacements x magnify."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection, PolyCollection
    path, je = final
    x = read_frame(path)[0]
    m = je.broken(x, o_r)
    X = je.X
    fig, axs = plt.subplots(1, 2, figsize=(9, 4.6))
    for ax, pos, sub in ((axs[0], X, "reference mesh"),
                         (axs[1], X + magnify * (x - X), f"displacement x {magnify:g}")):
        ax.add_collection(PolyCollection(pos[je.tris], facecolor="0.85", edgecolor="0.6",
                                         linewidths=0.2))
        segs = np.stack([X[je.a1[m]], X[je.a2[m]]], axis=1) if ax is axs[0] else \
            np.stack([pos[je.a1[m]], pos[je.a2[m]]], axis=1)
        ax.add_collection(LineCollection(segs, colors="r", linewidths=1.5))
        ax.autoscale()
        ax.set_aspect("equal")
        ax.set_title(sub, fontsize=9)
        ax.set_xlabel("x [m]")
    fig.suptitle(f"{title}: {m.sum()} broken joints", fontsize=10)
    fig.tight_layout()
    fig.savefig(png, dpi=70)
    plt.close(fig)


# ---- validation report rows (spec fracture.md §11): the lab-test examples that are validation
# cases (V4 Brazilian, V5 UCS, V6 three-point bending, V8 impact) write, with `run.py --validate
# DIR`, DIR/checks_<case>.csv in the format tools/validate/fdem_validate.cpp writes, so
# scripts/validate_report.py merges them into docs/validation/README.md.

def check(id, name, measured, expected, relation, tol=0.0, unit="", why=""):
    """One report row. relation: "rel" (|m/e - 1| <= tol), "abs" (|m - e| <= tol), "range"
    (expected <= m <= tol, i.e. tol is the upper bound), "at_most" (m <= e), "at_least" (m >= e),
    "report" (no pass/fail), "bool" (measured 1 = pass; expected ignored)."""
    m, e = float(measured), float(expected)
    if relation == "rel":
        ok, text = math.isfinite(m) and abs(m / e - 1.0) <= tol, f"± {100 * tol:.3g} %"
    elif relation == "abs":
        ok, text = math.isfinite(m) and abs(m - e) <= tol, f"± {tol:.3g} {unit}".strip()
    elif relation == "range":
        ok, text = math.isfinite(m) and e <= m <= tol, f"[{e:.3g}, {tol:.3g}]"
    elif relation == "at_most":
        ok, text = math.isfinite(m) and m <= e, "≤ expected"
    elif relation == "at_least":
        ok, text = math.isfinite(m) and m >= e, "≥ expected"
    elif relation == "bool":
        ok, text = m == 1.0, "yes"
    elif relation == "report":
        ok, text = True, "—"
    else:
        raise ValueError(f"unknown relation {relation!r}")
    return {"id": id, "name": name, "measured": f"{m:.8g}", "expected": f"{e:.8g}",
            "relation": relation, "tolerance": f"{float(tol):.8g}", "tolerance_text": text,
            "unit": unit, "pass": "report" if relation == "report" else ("pass" if ok else "FAIL"),
            "why": why}


def write_checks(folder, case, rows, figures=()):
    """Write folder/checks_<case>.csv (rows from check()) and copy each (png_path, title) of
    figures to folder/fig_<case>_<k>.png with its title in fig_<case>_<k>.title (the report shows
    them). Returns the number of failed rows."""
    import shutil
    os.makedirs(folder, exist_ok=True)
    cols = ["id", "name", "measured", "expected", "relation", "tolerance", "tolerance_text", "unit",
            "pass", "why"]
    with open(os.path.join(folder, f"checks_{case}.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols)
        w.writeheader()
        for r in rows:
            w.writerow(r)
    for k, (png, title) in enumerate(figures):
        if png and os.path.exists(png):
            shutil.copyfile(png, os.path.join(folder, f"fig_{case}_{k}.png"))
            with open(os.path.join(folder, f"fig_{case}_{k}.title"), "w") as f:
                f.write(title)
    failed = [r for r in rows if r["pass"] == "FAIL"]
    for r in rows:
        print(f"  [{r['pass']}] {r['id']} {r['name']}: {r['measured']} {r['unit']} "
              f"(expected {r['expected']} {r['tolerance_text']})")
    return len(failed)
