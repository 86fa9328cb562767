#!/usr/bin/python3
"""Check the VTU frame of tests/composite_output/write_composite_state.cpp with the real VTK
reader (python3-vtk9): the cells are the sub-triangles, the `composite` cell field names the
composite of each (four consecutive cells per composite, -1 for CST triangles), the four cells of
a composite span six points whose hull area is the composite's, and the stress is the split law
of docs/theory.md eq. 3.8 on composite cells and eq. 2.2 on CST cells, computed here from F.

usage: check_composite_vtu.py FRAME.vtu Fxx,Fxy,Fyx,Fyy
Exit 0 on success, 1 with a message on the first mismatch, 2 if VTK/numpy are missing.
"""
import sys

try:
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
except ImportError as exc:  # pragma: no cover
    sys.stderr.write(f"check_composite_vtu.py: cannot import VTK/numpy ({exc}); install "
                     "python3-vtk9 and run with /usr/bin/python3\n")
    sys.exit(2)

E, NU = 1e9, 0.45  # as write_composite_state.cpp
N_COMPOSITES, N_CST = 4, 2


def fail(msg):
    print("FAILED: " + msg)
    sys.exit(1)


def main():
    path, ftext = sys.argv[1], sys.argv[2]
    F = np.array([float(v) for v in ftext.split(",")]).reshape(2, 2)
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    if reader.GetErrorCode() != 0:
        fail(f"{path}: VTK reader error {reader.GetErrorCode()}")
    g = reader.GetOutput()
    nc = g.GetNumberOfCells()
    if nc != 4 * N_COMPOSITES + N_CST:
        fail(f"{nc} cells, expected {4 * N_COMPOSITES + N_CST}")
    arr = g.GetCellData().GetArray("composite")
    if arr is None:
        fail("no cell array 'composite'")
    comp = vtk_to_numpy(arr)
    expect = [c for c in range(N_COMPOSITES) for _ in range(4)] + [-1] * N_CST
    if comp.tolist() != expect:
        fail(f"composite ids {comp.tolist()}, expected {expect}")
    pts = vtk_to_numpy(g.GetPoints().GetData())[:, :2]
    conn = vtk_to_numpy(g.GetCells().GetConnectivityArray()).reshape(nc, 3)

    # analytic stresses (plane strain Lame constants, theory eq. 2.5)
    mu = E / (2 * (1 + NU))
    lam = E * NU / ((1 + NU) * (1 - 2 * NU))
    kappa = lam + mu
    J = np.linalg.det(F)
    B = F @ F.T
    split = mu / J**2 * (B - 0.5 * np.trace(B) * np.eye(2)) + 0.5 * kappa * (J - 1 / J) * np.eye(2)
    cst = mu / J * (B - np.eye(2)) + 0.5 * lam * (J - 1 / J) * np.eye(2)
    stress = vtk_to_numpy(g.GetCellData().GetArray("stress")).reshape(nc, 3, 3)[:, :2, :2]
    scale = np.abs(split).max()
    for t in range(nc):
        want = split if comp[t] >= 0 else cst
        # 1e-12 relative: a few rounded products (values written as Float64)
        if np.abs(stress[t] - want).max() > 1e-12 * scale:
            fail(f"cell {t}: stress {stress[t].tolist()}, expected {want.tolist()}")

    def area(p):
        return 0.5 * ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) -
                      (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]))

    # reference area of one composite: the 2 x 1 rectangle in 2 x 1 cells, 2 triangles per cell
    a_ref = 0.5 * J
    for c in range(N_COMPOSITES):
        cells = conn[4 * c:4 * c + 4]
        if len(set(cells.flatten().tolist())) != 6:
            fail(f"composite {c}: its four cells use {len(set(cells.flatten().tolist()))} "
                 "points, expected 6")
        sub = [area(pts[cell]) for cell in cells]
        if min(sub) <= 0:
            fail(f"composite {c}: a sub-triangle is not counter-clockwise ({sub})")
        if abs(sum(sub) - a_ref) > 1e-12:
            fail(f"composite {c}: area {sum(sub)}, expected {a_ref}")
    print(f"OK: {nc} cells, {N_COMPOSITES} composites, split-law stress on composite cells")


if __name__ == "__main__":
    main()
