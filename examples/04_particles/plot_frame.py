#!/usr/bin/python3
"""Render one frame of example 04 or 12 (a .vtu, or the .pvtu of a distributed run) to a PNG:
particles coloured by speed, walls grey. Only the triangles in the window are drawn (example 12
has 10^5 particles).

Usage: /usr/bin/python3 plot_frame.py out/04_particles/frame_000020.vtu particles.png [x0,x1,y0,y1]
       /usr/bin/python3 plot_frame.py out/12_particles_mpi/frame_000012.pvtu particles.png \
           [x0,x1,y0,y1]
The optional window [m] zooms in (default: the whole box).
Needs python3-vtk9 and python3-matplotlib (Debian packages), hence /usr/bin/python3.
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.collections import PolyCollection
from vtk import vtkXMLPUnstructuredGridReader, vtkXMLUnstructuredGridReader
from vtk.util.numpy_support import vtk_to_numpy


def main(vtu, png, window=None):
    # a .pvtu: VTK reads every piece (one per process) into one grid; nodes on the cuts appear
    # once per piece that uses them, which changes nothing in the picture
    r = (vtkXMLPUnstructuredGridReader() if vtu.endswith(".pvtu")
         else vtkXMLUnstructuredGridReader())
    r.SetFileName(vtu)
    r.Update()
    g = r.GetOutput()
    x = vtk_to_numpy(g.GetPoints().GetData())[:, :2]
    conn = vtk_to_numpy(g.GetCells().GetConnectivityArray()).reshape(-1, 3)
    pd = g.GetPointData()
    names = [pd.GetArrayName(i) for i in range(pd.GetNumberOfArrays())]
    v = vtk_to_numpy(pd.GetArray("velocity"))[:, :2] if "velocity" in names else np.zeros_like(x)
    speed = np.linalg.norm(v, axis=1)[conn].mean(axis=1)
    x0, x1, y0, y1 = window or (x[:, 0].min(), x[:, 0].max(), x[:, 1].min(), x[:, 1].max())
    c = x[conn].mean(axis=1)  # draw only the triangles near the window
    near = ((c[:, 0] > x0 - 0.01) & (c[:, 0] < x1 + 0.01) & (c[:, 1] > y0 - 0.01)
            & (c[:, 1] < y1 + 0.01))
    conn, speed = conn[near], speed[near]
    moving = speed > 0  # the fixed walls have v = 0
    fig, ax = plt.subplots(figsize=(7, 6.2))
    ax.add_collection(PolyCollection(x[conn[~moving]], facecolor="0.75", edgecolor="none"))
    pc = PolyCollection(x[conn[moving]], array=speed[moving], cmap="viridis", edgecolor="k",
                        linewidths=0.2)
    ax.add_collection(pc)
    fig.colorbar(pc, ax=ax, label="speed [m/s]")
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    t = g.GetFieldData().GetArray("TimeValue")
    ax.set_title(f"{vtu.split('/')[-1]}" + (f", t = {t.GetValue(0) * 1e3:.2f} ms" if t else ""))
    fig.tight_layout()
    fig.savefig(png, dpi=80)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2],
         [float(c) for c in sys.argv[3].split(",")] if len(sys.argv) > 3 else None)
