#!/usr/bin/env bash
# Usage: scaling_split.sh SCALING FDEM MPIEXEC OUT
# scripts/scaling --split at toy sizes, two rounds: every round also runs the 2N scene on one
# process (kind serial_weak in scaling.csv), and the weak efficiency T1(N)/T2(2N) is printed as
# the product of the size factor 2 T1(N)/T1(2N) and the parallel efficiency T1(2N)/(2 T2(2N)).
# The check recomputes the three figures of every round from the CSV's seconds and compares them
# with the printed ones (rounded to 2 digits), and checks that the medians line names them.
set -euo pipefail
scaling=$1 fdem=$2 mpiexec=$3 out=$4
rm -rf "$out"
"$scaling" --block-mesh 0.05 --pack-blocks 16 --rounds 2 --steps 20 --out "$out" --fdem "$fdem" \
    --mpiexec "$mpiexec" --split > "$out.log" 2>&1 || { cat "$out.log"; exit 1; }
cat "$out.log"
/usr/bin/python3 - "$out/scaling.csv" "$out.log" <<'PY'
import csv, re, sys
rows = list(csv.DictReader(open(sys.argv[1])))
log = open(sys.argv[2]).read()
t = {}
for r in rows:
    t[(r["scene"], int(r["round"]), r["kind"])] = float(r["seconds"])
kinds = sorted({k for (_, _, k) in t})
assert kinds == ["serial", "serial_weak", "strong", "weak"], kinds
for scene in ("block", "pack"):
    for rnd in (1, 2):
        s, w, sw = (t[(scene, rnd, k)] for k in ("serial", "weak", "serial_weak"))
        weak, growth, par = s / w, 2 * s / sw, sw / (2 * w)
        assert abs(weak - growth * par) < 1e-12 * weak, (weak, growth, par)
        m = re.search(rf"^{scene} round {rnd}: .*\(weak efficiency ([0-9.]+)\); 2N on 1 [^:]+: = "
                      rf"size factor ([0-9.]+) x parallel efficiency at 2N ([0-9.]+)$", log, re.M)
        assert m, f"no split line for {scene} round {rnd}"
        for printed, value in zip(m.groups(), (weak, growth, par)):
            assert printed == f"{value:.2f}", (scene, rnd, printed, value)
    assert re.search(rf"^{scene}: .* over 2 round\(s\); size factor median [0-9.]+ \([0-9.-]+\), "
                     rf"parallel efficiency at 2N median [0-9.]+ \([0-9.-]+\)$", log, re.M), scene
print("OK: scaling split: 2N on 1 process run, weak = size factor x parallel efficiency")
PY
