#!/usr/bin/env bash
# Usage: raster_example.sh FDEM MPIEXEC OUT N NP END_TIME [FRAMES]
# Runs examples/12_particles_mpi/run (N x N raster, NP processes, to END_TIME, FRAMES frames,
# default 4) into OUT/np$NP, then the scenario it generated with one process into OUT/serial,
# and checks that the state hash, history.csv and bodies.csv are byte-identical and the last
# .pvtu merges to the serial .vtu bit for bit (check_pvtu.py), and that series.pvd lists it and
# the example drew its picture. With N = 0 it only checks that the run at the example's default
# size finishes and writes its .pvtu series (no serial run: label full).
set -euo pipefail
fdem=$1 mpiexec=$2 out=$3 n=$4 np=$5 end=$6 frames=${7:-4}
here=$(cd "$(dirname "$0")" && pwd)
run=$here/../../examples/12_particles_mpi/run
rm -rf "$out"
mkdir -p "$out"
size=()
if [ "$n" -gt 0 ]; then size=(--n "$n"); fi
par=$(FDEM=$fdem MPIRUN=$mpiexec "$run" "${size[@]}" --np "$np" --end-time "$end" \
    --frames "$frames" --out "$out/np$np" -- --quiet --print-hash 2>"$out/run.err" |
    grep '^hash ' || true)
echo "np $np: $par"
fail=0
last=$(cd "$out/np$np" && ls frame_*.pvtu | tail -1)
if [ -z "$par" ] || [ -z "$last" ]; then
    echo "FAIL: the example did not run"; cat "$out/run.err"; exit 1
fi
if ! grep -q "file=\"$last\"" "$out/np$np/series.pvd"; then
    echo "FAIL: series.pvd does not list $last"; fail=1
fi
if [ ! -s "$out/np$np/particles.png" ]; then
    echo "FAIL: no particles.png"; fail=1
fi
if [ "$n" -eq 0 ]; then
    pieces=$(grep -c '<Piece ' "$out/np$np/$last")
    echo "$(ls "$out/np$np"/frame_*.pvtu | wc -l) frames of $pieces pieces"
    if [ "$pieces" -ne "$np" ]; then echo "FAIL: $pieces pieces, expected $np"; fail=1; fi
    if [ $fail -eq 0 ]; then echo "OK: the example ran and wrote its .pvtu series"; fi
    exit $fail
fi
serial=$("$fdem" run "$out/np$np/scenario.toml" --quiet --print-hash --out "$out/serial" \
    2>/dev/null)
echo "serial: $serial"
if [ "$par" != "$serial" ]; then echo "FAIL: the state hash of -np $np differs"; fail=1; fi
for f in history.csv bodies.csv; do
    if ! cmp -s "$out/serial/$f" "$out/np$np/$f"; then echo "FAIL: $f differs"; fail=1; fi
done
if ! awk -F, 'NR > 1 && $12 > 0 {found = 1} END {exit !found}' "$out/serial/history.csv"; then
    echo "FAIL: no contact during the run (make END_TIME longer)"; fail=1
fi
if ! /usr/bin/python3 "$here/check_pvtu.py" "$out/serial/${last%.pvtu}.vtu" "$out/np$np/$last" \
    "$np"; then
    echo "FAIL: $last of -np $np differs from the serial ${last%.pvtu}.vtu"; fail=1
fi
if [ $fail -eq 0 ]; then echo "OK: the example is bitwise the serial run"; fi
exit $fail
