#!/usr/bin/env python3
"""T6 of spec parallel-and-python.md: a .pvtu frame of a distributed run, read with VTK's own
parallel reader (python3-vtk9) and merged by its node_id / tri_id arrays, equals the serial
.vtu frame bit for bit: every point and cell array, the points, the connectivity and the time.

Usage: check_pvtu.py SERIAL.vtu PARALLEL.pvtu PROCESSES [OWNING]
OWNING: how many processes hold cells (default PROCESSES; fewer for a model of fewer node groups
than processes, tests/mpi/few_groups.sh).
Exit 0 and "OK: ..." when equal; 1 with the first difference otherwise; 2 when VTK is missing.
"""
import sys

try:
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import (vtkXMLPUnstructuredGridReader,
                                     vtkXMLUnstructuredGridReader)
except ImportError as e:  # pragma: no cover
    print(f"cannot import VTK/numpy ({e}): install python3-vtk9 python3-numpy")
    sys.exit(2)


def read(reader, path):
    reader.SetFileName(path)
    reader.Update()
    g = reader.GetOutput()
    if g is None or g.GetNumberOfCells() == 0:
        sys.exit(f"FAIL: {path}: VTK read no cells")
    return g


def arrays(data):
    return {data.GetArrayName(k): vtk_to_numpy(data.GetArray(k))
            for k in range(data.GetNumberOfArrays())}


def same_bits(a, b):
    a = np.ascontiguousarray(a)
    b = np.ascontiguousarray(b)
    return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()


def connectivity(g):
    cells = g.GetCells()
    conn = vtk_to_numpy(cells.GetConnectivityArray())
    offs = vtk_to_numpy(cells.GetOffsetsArray())
    if not np.all(np.diff(offs) == 3):
        sys.exit("FAIL: a cell is not a triangle")
    return conn.reshape(-1, 3)


def main():
    if len(sys.argv) not in (4, 5):
        sys.exit(__doc__)
    serial_path, pvtu_path, procs = sys.argv[1], sys.argv[2], int(sys.argv[3])
    owning = int(sys.argv[4]) if len(sys.argv) > 4 else procs
    s = read(vtkXMLUnstructuredGridReader(), serial_path)
    preader = vtkXMLPUnstructuredGridReader()
    p = read(preader, pvtu_path)
    if preader.GetNumberOfPieces() != procs:
        sys.exit(f"FAIL: {preader.GetNumberOfPieces()} pieces, expected {procs}")

    sp, pp = arrays(s.GetPointData()), arrays(p.GetPointData())
    sc, pc = arrays(s.GetCellData()), arrays(p.GetCellData())
    node = pp.pop("node_id")
    tri = pc.pop("tri_id")
    rank = pc.pop("rank")
    nn, nt = s.GetNumberOfPoints(), s.GetNumberOfCells()
    if sorted(pp) != sorted(sp) or sorted(pc) != sorted(sc):
        sys.exit(f"FAIL: arrays differ: points {sorted(pp)} vs {sorted(sp)}, "
                 f"cells {sorted(pc)} vs {sorted(sc)}")
    # every triangle in exactly one piece, every node in at least one
    if not same_bits(np.sort(tri), np.arange(nt, dtype=tri.dtype)):
        sys.exit("FAIL: the pieces' triangles are not each serial triangle exactly once")
    if len(np.unique(node)) != nn:
        sys.exit(f"FAIL: the pieces hold {len(np.unique(node))} distinct nodes, serial {nn}")
    if rank.min() < 0 or rank.max() >= procs or len(np.unique(rank)) != owning:
        sys.exit(f"FAIL: rank values {np.unique(rank)} for {procs} processes")
    for name, a in sp.items():
        if not same_bits(pp[name], a[node]):
            sys.exit(f"FAIL: point array {name} differs from the serial frame")
    for name, a in sc.items():
        if not same_bits(pc[name], a[tri]):
            sys.exit(f"FAIL: cell array {name} differs from the serial frame")
    if not same_bits(vtk_to_numpy(p.GetPoints().GetData()),
                     vtk_to_numpy(s.GetPoints().GetData())[node]):
        sys.exit("FAIL: the points differ from the serial frame")
    if not np.array_equal(node[connectivity(p)].astype(np.int64),
                          connectivity(s)[tri].astype(np.int64)):
        sys.exit("FAIL: the connectivity differs from the serial frame")
    for name in ("TIME", "CYCLE"):
        a = vtk_to_numpy(s.GetFieldData().GetArray(name))
        b = vtk_to_numpy(p.GetFieldData().GetArray(name))
        if not same_bits(a, b):
            sys.exit(f"FAIL: field {name} differs")
    print(f"OK: {pvtu_path} ({procs} pieces, {len(node)} points, {len(tri)} cells) merges to "
          f"{serial_path} bit for bit ({len(sp)} point and {len(sc)} cell arrays)")


if __name__ == "__main__":
    main()
