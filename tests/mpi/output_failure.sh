#!/usr/bin/env bash
# Usage: output_failure.sh FDEM MPIEXEC SCENARIO OUT NP KIND END_TIME
# An output error that only process 0 meets (it alone writes the CSVs and checkpoints) stops
# every process with the one-process run's exit code (1) and message, never a hang (the test's
# timeout; before the fix the other processes waited in the next step's collectives for ever).
# KIND history: history.csv is a link to /dev/full (the first write fails: no space left);
# KIND checkpoint: a non-empty folder is in the place of checkpoint.fdck (the first checkpoint,
# mid-run, cannot be renamed into place; failure.vtu must then be the serial one byte for byte).
set -uo pipefail
fdem=$1 mpiexec=$2 scenario=$3 out=$4 np=$5 kind=$6 end=$7
rm -rf "$out"
fail=0
for run in serial "np$np"; do
    mkdir -p "$out/$run"
    extra=()
    if [ "$kind" = history ]; then
        ln -s /dev/full "$out/$run/history.csv"
    else
        mkdir -p "$out/$run/checkpoint.fdck/in_the_way"
        extra=(--checkpoint-every "$(awk -v e="$end" 'BEGIN { print e / 2 }')")
    fi
    if [ "$run" = serial ]; then
        "$fdem" run "$scenario" --quiet --out "$out/$run" --end-time "$end" "${extra[@]}" \
            2>"$out/$run.err"
    else
        timeout 120 "$mpiexec" --oversubscribe --bind-to none --mca btl self,vader -np "$np" \
            "$fdem" run "$scenario" --quiet --out "$out/$run" --end-time "$end" "${extra[@]}" \
            2>"$out/$run.err"
    fi
    rc=$?
    echo "$run: exit code $rc"
    if [ "$rc" != 1 ]; then echo "FAIL: $run exited with $rc, expected 1"; fail=1; fi
done
msg=$(grep -m1 "^error" "$out/serial.err" | sed "s|$out/serial|OUT|g")
echo "serial message: $msg"
par=$(grep -m1 "^error" "$out/np$np.err" | sed "s|$out/np$np|OUT|g")
if [ -z "$msg" ] || [ "$msg" != "$par" ]; then
    echo "FAIL: -np $np printed: $par"
    fail=1
fi
if [ "$kind" = checkpoint ] && ! cmp -s "$out/serial/failure.vtu" "$out/np$np/failure.vtu"; then
    echo "FAIL: failure.vtu differs (or is missing)"
    fail=1
fi
if [ "$fail" = 0 ]; then echo "OK: an output error of process 0 stops every process"; fi
exit "$fail"
