"""The Python examples (examples/python/) run, meet their analytic references and write PNGs."""
import csv
import os
import re
import subprocess
import sys

import matplotlib.image as mpimg
import numpy as np

from conftest import ROOT


def run_script(name, *args):
    p = subprocess.run([sys.executable, str(ROOT / "examples" / "python" / name), *args],
                       capture_output=True, text=True, env=os.environ.copy())
    assert p.returncode == 0, p.stdout + p.stderr
    return p.stdout


def png_ok(path):
    img = mpimg.imread(str(path))
    assert img.ndim == 3 and img.shape[0] > 200 and img.shape[1] > 300
    assert len(np.unique(img.reshape(-1, img.shape[2])[:, :3], axis=0)) > 50


def test_friction_sweep_follows_the_analytic_line(tmp_path):
    png = tmp_path / "friction_sweep.png"
    run_script("friction_sweep.py", "--out", str(png))
    png_ok(png)
    with open(tmp_path / "friction_sweep.csv") as f:
        rows = list(csv.DictReader(f))
    assert [float(r["mu"]) for r in rows] == [0.2, 0.3, 0.5, 0.8]
    for r in rows:
        d, d_an = float(r["stop_distance_m"]), float(r["analytic_m"])
        assert abs(d / d_an - 1) < 0.01, r  # stop distance v0^2 / (2 mu g) within 1 %
        t, t_an = float(r["stop_time_s"]), float(r["analytic_time_s"])
        assert abs(t - t_an) < 0.01 * t_an + 0.005, r  # sampled every 200 steps


def test_drop_test_rebounds_and_draws_the_stress(tmp_path):
    png = tmp_path / "drop.png"
    out = run_script("drop_test.py", "--out", str(png))
    png_ok(png)
    ratio = float(re.search(r"momentum ratio ([0-9.]+)", out).group(1))
    assert 0.9 < ratio <= 1.0, out  # an elastic rebound, minus the vibration left in the bodies
    err = float(re.search(r"max \|total - total_0\| = ([0-9.e+-]+)", out).group(1))
    assert err < 0.05, out
