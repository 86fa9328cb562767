#!/usr/bin/env bash
# Usage: history_only.sh FDEM MPIEXEC OUT
# A distributed run whose only output is history.csv (vtu and bodies.csv off) gathers the joints'
# state alone at its output steps, not x, v, f and f_contact (run/simulation.cpp write_output()),
# and the whole State at the last step: its history rows, at every other step of the saturated
# pack, and its final state hash stay those of the serial run on 2 and 3 processes. (A model with
# joints gathers the whole State at every output, as before: its fracture output reads it.)
set -euo pipefail
fdem=$1 mpiexec=$2 out=$3
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out"
mkdir -p "$out"
/usr/bin/python3 "$here/../loading/make_pack_scenario.py" "$out/pack" 400 --gap 0 \
    --closing 0.5 --end-time 2e-3 > /dev/null
# (the pack's scenario: vtu = false, bodies = false; dt = 1.095e-5 s, a history row every other
# step)
sed -i 's/^vtu = false$/vtu = false\ninterval = 2.2e-5/' "$out/pack/scenario.toml"
grep -q '^interval = 2.2e-5$' "$out/pack/scenario.toml" || { echo "FAIL: no interval set"; exit 1; }
fail=0
serial=$("$fdem" run "$out/pack/scenario.toml" --quiet --print-hash --out "$out/serial")
rows=$(wc -l < "$out/serial/history.csv")
echo "serial: $serial ($rows history lines)"
[ "$rows" -gt 80 ] || { echo "FAIL: only $rows history lines"; fail=1; }
for np in 2 3; do
    par=$("$mpiexec" --oversubscribe --bind-to none --mca btl self,vader -np "$np" \
        "$fdem" run "$out/pack/scenario.toml" --quiet --print-hash --out "$out/np$np")
    echo "np $np: $par"
    [ "$par" = "$serial" ] || { echo "FAIL: the state hash of -np $np differs"; fail=1; }
    cmp -s "$out/serial/history.csv" "$out/np$np/history.csv" ||
        { echo "FAIL: history.csv of -np $np differs"; fail=1; }
done
if [ $fail -eq 0 ]; then echo "OK: history-only output, bitwise the serial run"; fi
