#!/usr/bin/env python3
"""Cost of driving fdem from Python (issue #13 "Performance"; docs/python.md, docs/performance.md).

1. `sim.run(until=T)` from Python against `fdem run --end-time T` of the CLI on the demo scenario
   (examples/03_contact_slide), both writing their output, 1 OpenMP thread, alternated A/B/A/B.
2. The overhead of a per-step Python callback: run(steps=N, callback=f, every=1) against
   run(steps=N), per call.
3. The overhead of one Python call of sim.step(): N calls of step() against one step(N).

    PYTHONPATH=build/release/python FDEM_CLI=build/release/fdem \\
        /usr/bin/python3 bench/python_overhead.py [--end-time 0.2] [--repeats 5]
"""
import argparse
import os
import pathlib
import re
import statistics
import subprocess
import tempfile
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")

import fdem  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[1]
DEMO = str(ROOT / "examples" / "03_contact_slide" / "scenario.toml")


def time_cli(cli, end, out):
    """Wall time of the run loop as the CLI reports it ("done N steps in T s"), load excluded."""
    p = subprocess.run([cli, "run", DEMO, "--end-time", repr(end), "--threads", "1",
                        "--out", out], check=True, capture_output=True, text=True)
    m = re.search(r"^done\s+(\d+) steps in ([0-9.e+-]+) s", p.stdout + p.stderr, re.M)
    return float(m.group(2)), int(m.group(1))


def time_python(end, out):
    """Wall time of sim.run(until=end) with the same output as the CLI, load excluded."""
    sim = fdem.Simulation.from_toml(DEMO)
    sim.end_time = end
    sim.open_output(out)
    t0 = time.perf_counter()
    sim.run(until=end)
    return time.perf_counter() - t0, sim.step_count


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--end-time", type=float, default=0.2)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--steps", type=int, default=20000)
    args = ap.parse_args()
    cli = os.environ.get("FDEM_CLI", str(ROOT / "build" / "release" / "fdem"))
    tmp = tempfile.mkdtemp(prefix="fdem_pyov_")
    print(f"load average {os.getloadavg()[0]:.2f}")

    a, b = [], []
    for k in range(args.repeats):
        ta, na = time_cli(cli, args.end_time, f"{tmp}/cli{k}")
        tb, nb = time_python(args.end_time, f"{tmp}/py{k}")
        assert na == nb, (na, nb)
        a.append(ta)
        b.append(tb)
    ma, mb = statistics.median(a), statistics.median(b)
    print(f"demo to t = {args.end_time} s, 1 thread: CLI median {ma:.3f} s, Python run(until) "
          f"median {mb:.3f} s, Python / CLI = {mb / ma:.4f} "
          f"(CLI {[round(x, 3) for x in a]}, Python {[round(x, 3) for x in b]})")

    sim = fdem.Simulation.from_toml(DEMO)
    n = args.steps
    sim.run(steps=2000)  # past the first detection
    plain, cb = [], []
    for _ in range(args.repeats):
        t0 = time.perf_counter()
        sim.run(steps=n)
        plain.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        sim.run(steps=n, callback=lambda s: True, every=1)
        cb.append(time.perf_counter() - t0)
    p, c = statistics.median(plain), statistics.median(cb)
    print(f"run(steps={n}): {p / n * 1e6:.2f} us/step; with a Python callback every step "
          f"{c / n * 1e6:.2f} us/step: overhead {(c - p) / n * 1e6:.2f} us per callback")

    one, many = [], []
    m = n // 4
    for _ in range(args.repeats):
        t0 = time.perf_counter()
        sim.step(m)
        one.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        for _ in range(m):
            sim.step()
        many.append(time.perf_counter() - t0)
    o, mm = statistics.median(one), statistics.median(many)
    print(f"step({m}) once: {o / m * 1e6:.2f} us/step; step() {m} times: {mm / m * 1e6:.2f} "
          f"us/step: overhead {(mm - o) / m * 1e6:.2f} us per Python call")


if __name__ == "__main__":
    main()
