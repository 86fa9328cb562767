#!/usr/bin/env bash
# Usage: same_as_serial.sh FDEM MPIEXEC SCENARIO OUT "NP..." [fdem run options...]
# Runs SCENARIO with one process, then under mpirun with each NP, and checks that the state hash
# (x, v, energies), history.csv, bodies.csv and (with joints) cracks.csv and fragments.csv are
# byte-identical to the one-process run's and its last frame is bitwise the serial one (issue
# #15, spec parallel-and-python.md T1, T6).
# OMP_NUM_THREADS is the caller's. FDEM_TEST_GROUPS (optional): the model's node groups, when
# fewer than the processes (then only that many processes hold cells of the frames).
set -euo pipefail
fdem=$1 mpiexec=$2 scenario=$3 out=$4 nps=$5
shift 5
rm -rf "$out"
mkdir -p "$out"
# (a run that fails prints its stderr and the exit code: a failure under load says why)
if ! serial=$("$fdem" run "$scenario" --quiet --print-hash --out "$out/serial" "$@" \
    2>"$out/serial.err"); then
    echo "FAIL: the one-process run exited with an error:"
    cat "$out/serial.err"
    exit 1
fi
echo "serial: $serial"
fail=0
for np in $nps; do
    if ! par=$("$mpiexec" --oversubscribe --bind-to none --mca btl self,vader -np "$np" \
        "$fdem" run "$scenario" --quiet --print-hash --out "$out/np$np" "$@" 2>"$out/np$np.err"); then
        echo "FAIL: mpiexec -np $np exited with an error:"
        cat "$out/np$np.err"
        exit 1
    fi
    echo "np $np: $par"
    if [ "$par" != "$serial" ]; then
        echo "FAIL: the state hash of -np $np differs"
        fail=1
    fi
    for f in history.csv bodies.csv cracks.csv fragments.csv; do
        if [ -f "$out/serial/$f" ] && ! cmp -s "$out/serial/$f" "$out/np$np/$f"; then
            echo "FAIL: $f of -np $np differs"
            fail=1
        fi
    done
    # the last frame: a .pvtu of np pieces, merged by node_id/tri_id with VTK's reader
    # (T6), or with [output] merge = true (and for one process) the serial .vtu, byte for byte
    last=$(cd "$out/serial" && ls frame_*.vtu | tail -1)
    if [ -f "$out/np$np/${last%.vtu}.pvtu" ]; then
        if ! /usr/bin/python3 "$(dirname "$0")/check_pvtu.py" "$out/serial/$last" \
            "$out/np$np/${last%.vtu}.pvtu" "$np" \
            "$(( ${FDEM_TEST_GROUPS:-$np} < np ? ${FDEM_TEST_GROUPS:-$np} : np ))"; then
            echo "FAIL: ${last%.vtu}.pvtu of -np $np differs from the serial $last"
            fail=1
        fi
        if ! grep -q "file=\"${last%.vtu}.pvtu\"" "$out/np$np/series.pvd"; then
            echo "FAIL: series.pvd of -np $np does not list ${last%.vtu}.pvtu"
            fail=1
        fi
    elif ! cmp -s "$out/serial/$last" "$out/np$np/$last"; then
        echo "FAIL: $last of -np $np differs"
        fail=1
    fi
done
if [ $fail -eq 0 ]; then echo "OK: bitwise the serial run"; fi
exit $fail
