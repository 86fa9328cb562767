#!/usr/bin/python3
"""Check an fdem output series with the real VTK XML reader (python3-vtk9).

usage:
  check_vtu.py SERIES.pvd
      structure only: every frame listed in the .pvd opens without VTK errors or warnings, has the
      built-in arrays (docs/output.md) with the right number of tuples and components, only
      triangles, finite values, and TIME equal to the .pvd timestep.
  check_vtu.py SERIES.pvd --body x0,y0,w,h,nx,ny,E,nu,strain|stress ... \
                          --frame t,Fxx,Fxy,Fyx,Fyy,cx,cy ...
      additionally compares every value with the analytic one for the series written by
      fdem_write_known_state with the same arguments (tests/output/write_known_state.cpp):
      x = F X + c in every frame, stress from spec §3.1, Green-Lagrange strain, von Mises.

Exit code 0 on success, 1 with a message naming frame, array and tuple on the first mismatch,
2 if python3-vtk9 or numpy is missing.
"""
import argparse
import math
import os
import sys
import xml.etree.ElementTree as ET

try:
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
except ImportError as exc:  # pragma: no cover - depends on the machine
    sys.stderr.write(
        f"check_vtu.py: cannot import VTK/numpy ({exc}).\n"
        "Install the Debian packages python3-vtk9 and python3-numpy and run this script with "
        "/usr/bin/python3 (the python3 on PATH may be a different interpreter).\n")
    sys.exit(2)

# name -> (components, VTK data type name)
POINT_ARRAYS = {"displacement": 3, "velocity": 3, "force": 3, "contact_force": 3, "body": 1}
CELL_ARRAYS = {"stress": 9, "strain": 9, "von_mises": 1, "body": 1, "material": 1}
FIELD_ARRAYS = ("TIME", "TimeValue", "CYCLE")
VTK_TRIANGLE = 5


class CheckError(Exception):
    pass


def fail(msg):
    raise CheckError(msg)


def read_pvd(path):
    """(time, absolute file) of every DataSet of a .pvd collection."""
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as exc:
        fail(f"{path}: cannot read the series: {exc}")
    if root.get("type") != "Collection":
        fail(f"{path}: VTKFile type is {root.get('type')!r}, expected 'Collection'")
    base = os.path.dirname(os.path.abspath(path))
    frames = [(float(ds.get("timestep")), os.path.join(base, ds.get("file")))
              for ds in root.iter("DataSet")]
    if not frames:
        fail(f"{path}: no DataSet entries")
    return frames


def read_vtu(path):
    """Read one .vtu with vtkXMLUnstructuredGridReader; any VTK error or warning is a failure."""
    if not os.path.isfile(path):
        fail(f"{path}: listed in the .pvd but does not exist")
    messages = []
    reader = vtkXMLUnstructuredGridReader()
    for event in ("ErrorEvent", "WarningEvent"):
        reader.AddObserver(event, lambda obj, ev, m=messages: m.append(ev))
    reader.GetExecutive().AddObserver("ErrorEvent", lambda o, ev, m=messages: m.append(ev))
    reader.SetFileName(path)
    reader.Update()
    if messages or reader.GetErrorCode() != 0:
        fail(f"{path}: the VTK reader reported {messages or reader.GetErrorCode()}")
    return reader.GetOutput()


def get_array(data, name, components, tuples, where):
    arr = data.GetArray(name)
    if arr is None:
        names = [data.GetArrayName(i) for i in range(data.GetNumberOfArrays())]
        fail(f"{where}: array {name!r} missing (have {names})")
    if arr.GetNumberOfComponents() != components:
        fail(f"{where}: array {name!r} has {arr.GetNumberOfComponents()} components, "
             f"expected {components}")
    if arr.GetNumberOfTuples() != tuples:
        fail(f"{where}: array {name!r} has {arr.GetNumberOfTuples()} tuples, expected {tuples}")
    values = vtk_to_numpy(arr).reshape(tuples, components)
    if not np.all(np.isfinite(values)):
        fail(f"{where}: array {name!r} has non-finite values")
    return values


def check_structure(grid, time, where):
    """Arrays, counts and cell types every fdem frame must have. Returns a dict of arrays."""
    n, c = grid.GetNumberOfPoints(), grid.GetNumberOfCells()
    if n == 0 or c == 0:
        fail(f"{where}: empty grid ({n} points, {c} cells)")
    out = {"points": vtk_to_numpy(grid.GetPoints().GetData()).reshape(n, 3)}
    types = vtk_to_numpy(grid.GetCellTypesArray())
    if not np.all(types == VTK_TRIANGLE):
        fail(f"{where}: cell types {sorted(set(types.tolist()))}, expected only {VTK_TRIANGLE}")
    if not np.all(out["points"][:, 2] == 0.0):
        fail(f"{where}: points have non-zero z")
    for name, nc in POINT_ARRAYS.items():
        out["point:" + name] = get_array(grid.GetPointData(), name, nc, n, where + " point data")
    for name, nc in CELL_ARRAYS.items():
        out["cell:" + name] = get_array(grid.GetCellData(), name, nc, c, where + " cell data")
    for name in FIELD_ARRAYS:
        out["field:" + name] = get_array(grid.GetFieldData(), name, 1, 1, where + " field data")
    # time must match the .pvd exactly: both are written with 17 significant digits
    if out["field:TIME"][0, 0] != time:
        fail(f"{where}: field TIME = {out['field:TIME'][0, 0]!r}, .pvd timestep = {time!r}")
    for name in ("displacement", "velocity", "force", "contact_force"):
        if not np.all(out["point:" + name][:, 2] == 0.0):
            fail(f"{where}: point array {name!r} has non-zero z component")
    stress = grid.GetCellData().GetArray("stress")
    if stress.GetComponentName(0) != "xx" or stress.GetComponentName(4) != "yy":
        fail(f"{where}: stress component names {stress.GetComponentName(0)!r}, ... "
             "expected xx, xy, xz, yx, yy, ...")
    return out


# ---- analytic values of the known series -------------------------------------------------------

def parse_floats(text, n, what):
    vals = text.split(",")
    if len(vals) != n:
        fail(f"{what} {text!r}: expected {n} comma-separated values")
    return vals


def lame(E, nu, mode):
    """Effective 2-D Lame constants (docs/theory.md eq. 2.5)."""
    mu = E / (2.0 * (1.0 + nu))
    lam = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu))
    if mode == "stress":
        lam = 2.0 * lam * mu / (lam + 2.0 * mu)
    return lam, mu


def analytic_cell(F, lam, mu):
    """Cauchy stress (spec §3.1 without eta D), Green-Lagrange strain, von Mises; 3x3 arrays."""
    F = np.array(F, dtype=float).reshape(2, 2)
    J = F[0, 0] * F[1, 1] - F[0, 1] * F[1, 0]
    B = F @ F.T
    sig2 = (mu / J) * (B - np.eye(2)) + 0.5 * lam * (J - 1.0 / J) * np.eye(2)
    E2 = 0.5 * (F.T @ F - np.eye(2))
    sig = np.zeros((3, 3))
    sig[:2, :2] = sig2
    eps = np.zeros((3, 3))
    eps[:2, :2] = E2
    sxx, syy, sxy = sig2[0, 0], sig2[1, 1], sig2[0, 1]
    vm = math.sqrt(sxx * sxx - sxx * syy + syy * syy + 3.0 * sxy * sxy)
    return sig.reshape(9), eps.reshape(9), vm


def compare(where, name, got, expected, atol):
    err = np.abs(np.asarray(got, dtype=float) - np.asarray(expected, dtype=float))
    if np.any(err > atol):
        i = np.unravel_index(np.argmax(err), err.shape)
        fail(f"{where}: {name}{list(i)} = {np.asarray(got).reshape(err.shape)[i]!r}, expected "
             f"{np.asarray(expected).reshape(err.shape)[i]!r} (|error| {err[i]:.3e} > {atol:.3e})")


def check_known(arrays, k, frame, bodies, where):
    t, Fxx, Fxy, Fyx, Fyy, cx, cy = frame
    F = np.array([[Fxx, Fxy], [Fyx, Fyy]])
    c = np.array([cx, cy])

    # reference nodes, triangles' body and material, as write_known_state.cpp builds them
    X, node_body, tri_body, tri_mat, tri_lame = [], [], [], [], []
    for b, (x0, y0, w, h, nx, ny, E, nu, mode) in enumerate(bodies):
        for j in range(ny + 1):
            for i in range(nx + 1):
                X.append((x0 + w * i / nx, y0 + h * j / ny))
                node_body.append(b)
        tri_body += [b] * (2 * nx * ny)
        tri_mat += [b] * (2 * nx * ny)
        tri_lame += [(*lame(E, nu, mode), E)] * (2 * nx * ny)
    X = np.array(X)
    n = len(X)
    if arrays["points"].shape[0] != n or arrays["cell:stress"].shape[0] != len(tri_body):
        fail(f"{where}: {arrays['points'].shape[0]} points / {arrays['cell:stress'].shape[0]} "
             f"cells, expected {n} / {len(tri_body)}")
    idx = np.arange(n, dtype=float)
    zeros = np.zeros(n)

    # positions and displacement: x = F X + c is computed in both programs with a few roundings
    # of the largest coordinate (~1e-16 relative each); 1e-12 of it is a wide margin that is
    # still far below any ordering or indexing mistake (>= a mesh spacing, 0.25 m here)
    x = X @ F.T + c
    scale = max(1.0, float(np.max(np.abs(x))))
    compare(where, "points", arrays["points"][:, :2], x, 1e-12 * scale)
    compare(where, "displacement", arrays["point:displacement"][:, :2], x - X, 1e-12 * scale)

    # fields set from node index and frame number: small integers times exact binary fractions,
    # exactly representable, so compared exactly
    compare(where, "velocity", arrays["point:velocity"],
            np.column_stack([k + 0.5 * idx, -0.25 * idx, zeros]), 0.0)
    compare(where, "force", arrays["point:force"],
            np.column_stack([1000.0 * idx, k - 2000.0 * idx, zeros]), 0.0)
    compare(where, "contact_force", arrays["point:contact_force"],
            np.column_stack([-idx, 3.0 * k + zeros, zeros]), 0.0)
    compare(where, "point body", arrays["point:body"][:, 0], node_body, 0.0)
    compare(where, "cell body", arrays["cell:body"][:, 0], tri_body, 0.0)
    compare(where, "cell material", arrays["cell:material"][:, 0], tri_mat, 0.0)

    # stress/strain: F is recomputed from rounded positions, F = Ds Dm^-1, so it carries an
    # error of a few ulp (~1e-15); sigma and E are O(1) functions of F with coefficients ~E, so
    # the error is ~1e-15 E (measured: at most 1.8e-15 E and 1.7e-15 for the strain). 1e-12 E
    # leaves a 500x margin and still catches any formula error (a wrong or missing term is
    # ~1e-3 E or larger for the deformations used). Strain: the same argument with E -> 1.
    for tri, (lam, mu, E_scale) in enumerate(tri_lame):
        sig, eps, vm = analytic_cell(F, lam, mu)
        compare(where + f" cell {tri}", "stress", arrays["cell:stress"][tri], sig, 1e-12 * E_scale)
        compare(where + f" cell {tri}", "strain", arrays["cell:strain"][tri], eps, 1e-12)
        compare(where + f" cell {tri}", "von_mises", arrays["cell:von_mises"][tri], [vm],
                1e-12 * E_scale)


def check_extras(grid, arrays, where):
    """Extra fields written by write_known_state through the ExtraField interface."""
    n, c = grid.GetNumberOfPoints(), grid.GetNumberOfCells()
    idx = np.arange(n, dtype=float)
    d = get_array(grid.GetPointData(), "distance", 1, n, where + " point data")
    compare(where, "distance", d[:, 0], 0.1 * idx, 0.0)
    nrm = get_array(grid.GetPointData(), "normal", 3, n, where + " point data")
    compare(where, "normal", nrm, np.column_stack([idx, -idx, np.zeros(n)]), 0.0)
    cid = get_array(grid.GetCellData(), "cell_id", 1, c, where + " cell data")
    compare(where, "cell_id", cid[:, 0], np.arange(c, dtype=float), 0.0)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("pvd")
    ap.add_argument("--body", action="append", default=[])
    ap.add_argument("--frame", action="append", default=[])
    ap.add_argument("--min-frames", type=int, default=1)
    args = ap.parse_args()
    try:
        bodies = []
        for text in args.body:
            v = parse_floats(text, 9, "--body")
            bodies.append((*map(float, v[:4]), int(v[4]), int(v[5]), float(v[6]), float(v[7]),
                           v[8]))
        frames = [tuple(map(float, parse_floats(t, 7, "--frame"))) for t in args.frame]

        series = read_pvd(args.pvd)
        if len(series) < args.min_frames:
            fail(f"{args.pvd}: {len(series)} frames, expected at least {args.min_frames}")
        if frames and len(series) != len(frames):
            fail(f"{args.pvd}: {len(series)} frames, expected {len(frames)}")
        for k, (time, path) in enumerate(series):
            where = os.path.basename(path)
            grid = read_vtu(path)
            arrays = check_structure(grid, time, where)
            if frames:
                if time != frames[k][0]:
                    fail(f"{where}: .pvd timestep {time!r}, expected {frames[k][0]!r}")
                if arrays["field:CYCLE"][0, 0] != 10 * k:
                    fail(f"{where}: CYCLE {arrays['field:CYCLE'][0, 0]}, expected {10 * k}")
                check_known(arrays, k, frames[k], bodies, where)
                check_extras(grid, arrays, where)
        print(f"check_vtu.py: {args.pvd}: {len(series)} frames OK")
    except CheckError as exc:
        sys.stderr.write(f"check_vtu.py: FAILED: {exc}\n")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
