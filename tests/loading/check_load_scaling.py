#!/usr/bin/python3
"""Loading scales linearly in the [[body]] entries (issue #16 item 4).

    check_load_scaling.py FDEM GENERATOR WORKDIR

Writes the brick-bond packs of 10^3 and 10^4 blocks with one [[body]] entry per block
(make_pack_scenario.py), runs `fdem check` on each three times (interleaved) and compares the
fastest wall time and the smallest peak RSS of each:
  time(10^4) / time(10^3) < 15: linear loading gives at most 10 (less, as process start-up
      and the Gmsh library load are a constant); the quadratic loading of issue #16 gave 120
      (51.6 s against 0.43 s). No absolute wall-clock threshold: the machine is shared.
  RSS(10^4) - RSS(10^3) < 100 MB: the model of 10^4 blocks is 6 MB; the per-entry node maps
      of issue #16 made it 1.6 GB.
Exit 0 if both hold, 1 otherwise; the numbers are printed either way.
"""
import os
import subprocess
import sys
import time

N_SMALL, N_LARGE = 1000, 10000
MAX_TIME_RATIO = 15.0
MAX_RSS_GROWTH_MB = 100.0


def timed(fdem, scenario, n):
    """Wall time [s] and peak RSS [MB] of one `fdem check` (its own rusage, from wait4);
    fails on a non-zero exit or a wrong summary."""
    t0 = time.perf_counter()
    pid = os.fork()
    if pid == 0:
        fd = os.open(os.devnull, os.O_WRONLY)
        out = os.open(scenario + ".out", os.O_WRONLY | os.O_CREAT | os.O_TRUNC)
        os.dup2(out, 1)
        os.dup2(fd, 2)
        os.execv(fdem, [fdem, "check", scenario])
    _, status, usage = os.wait4(pid, 0)
    wall = time.perf_counter() - t0
    if not os.WIFEXITED(status) or os.WEXITSTATUS(status) != 0:
        sys.exit(f"FAIL: fdem check {scenario} failed (status {status}); run it by hand")
    with open(scenario + ".out") as f:
        text = f.read()
    want = f"bodies     {n} (0 fixed) from {n} body entries"
    if want not in text:
        sys.exit(f"FAIL: fdem check {scenario}: no line '{want}' in\n{text[:2000]}")
    return wall, usage.ru_maxrss / 1024.0  # ru_maxrss is in KB on Linux


def main(argv):
    if len(argv) != 4:
        sys.exit(__doc__)
    fdem, gen, work = argv[1], argv[2], argv[3]
    scen = {}
    for n in (N_SMALL, N_LARGE):
        d = os.path.join(work, f"pack_{n}")
        subprocess.run([sys.executable, gen, d, str(n)], check=True)
        scen[n] = os.path.join(d, "scenario.toml")
    best = {n: (float("inf"), float("inf")) for n in scen}
    for _ in range(3):
        for n in (N_SMALL, N_LARGE):
            wall, rss = timed(fdem, scen[n], n)
            best[n] = (min(best[n][0], wall), min(best[n][1], rss))
    (t1, r1), (t2, r2) = best[N_SMALL], best[N_LARGE]
    ratio, growth = t2 / t1, r2 - r1
    print(f"fdem check, {N_SMALL} entries: {t1:.3f} s, {r1:.1f} MB peak RSS")
    print(f"fdem check, {N_LARGE} entries: {t2:.3f} s, {r2:.1f} MB peak RSS")
    print(f"time ratio {ratio:.2f} (limit {MAX_TIME_RATIO}), RSS growth {growth:.1f} MB "
          f"(limit {MAX_RSS_GROWTH_MB})")
    ok = ratio < MAX_TIME_RATIO and growth < MAX_RSS_GROWTH_MB
    print("OK: loading is linear in the entries" if ok else "FAIL: loading grows faster "
          "than linearly in the [[body]] entries")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
