#!/usr/bin/env bash
# Usage: same_as_serial.sh FDEM MPIEXEC SCENARIO OUT "NP..." [fdem run options...]
# Runs SCENARIO with one process, then under mpirun with each NP, and checks that the state hash
# (x, v, energies), history.csv, bodies.csv and the last VTU frame are byte-identical to the
# one-process run's (issue #15, spec parallel-and-python.md T1). OMP_NUM_THREADS is the caller's.
set -euo pipefail
fdem=$1 mpiexec=$2 scenario=$3 out=$4 nps=$5
shift 5
rm -rf "$out"
mkdir -p "$out"
serial=$("$fdem" run "$scenario" --quiet --print-hash --out "$out/serial" "$@" 2>/dev/null)
echo "serial: $serial"
fail=0
for np in $nps; do
    par=$("$mpiexec" --oversubscribe --bind-to none --mca btl self,vader -np "$np" \
        "$fdem" run "$scenario" --quiet --print-hash --out "$out/np$np" "$@" 2>/dev/null)
    echo "np $np: $par"
    if [ "$par" != "$serial" ]; then
        echo "FAIL: the state hash of -np $np differs"
        fail=1
    fi
    for f in history.csv bodies.csv; do
        if [ -f "$out/serial/$f" ] && ! cmp -s "$out/serial/$f" "$out/np$np/$f"; then
            echo "FAIL: $f of -np $np differs"
            fail=1
        fi
    done
    last=$(cd "$out/serial" && ls frame_*.vtu | tail -1)
    if ! cmp -s "$out/serial/$last" "$out/np$np/$last"; then
        echo "FAIL: $last of -np $np differs"
        fail=1
    fi
done
if [ $fail -eq 0 ]; then echo "OK: bitwise the serial run"; fi
exit $fail
