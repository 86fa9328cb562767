#!/usr/bin/env bash
# Usage: signal_one_process.sh FDEM MPIEXEC SCENARIO OUT END
# Spec D9 for signals: SIGTERM sent to process 1 only of a 2-process run (as a batch system or a
# user may do). Every process stops after the same step (the stop request is reduced over the
# processes each step), process 0 writes the checkpoint and the stop message, mpirun exits 143;
# the restart from that checkpoint ends with the uninterrupted one-process run's hash and
# history.csv.
set -euo pipefail
fdem=$1 mpiexec=$2 scenario=$3 out=$4 end=$5
rm -rf "$out"
mkdir -p "$out"
ref=$("$fdem" run "$scenario" --quiet --print-hash --end-time "$end" --out "$out/ref" 2>/dev/null)
# each process records its pid under its rank, then becomes fdem
"$mpiexec" --oversubscribe --bind-to none --mca btl self,vader -np 2 \
    sh -c 'echo $$ > "$0/pid.$OMPI_COMM_WORLD_RANK"; exec "$@"' "$out" \
    "$fdem" run "$scenario" --end-time "$end" --checkpoint-every "$end" --out "$out/int" \
    --progress-every 0 > "$out/int.log" 2>&1 &
job=$!
for _ in $(seq 1 4000); do
    [ -s "$out/pid.1" ] && [ -e "$out/int/history.csv" ] && break
    sleep 0.005
done
sleep 0.3
kill -s TERM "$(cat "$out/pid.1")" || { echo "FAIL: the run ended before it could be interrupted"; exit 1; }
rc=0
wait "$job" || rc=$?
cat "$out/int.log"
[ "$rc" -eq 143 ] || { echo "FAIL: mpirun exited with $rc, expected 143"; exit 1; }
grep -q "stopped by SIGTERM after step [0-9]* (t = .* s); checkpoint written" "$out/int.log" ||
    { echo "FAIL: no stop message from process 0"; exit 1; }
[ -e "$out/int/checkpoint.fdck" ] || { echo "FAIL: no checkpoint"; exit 1; }
got=$("$fdem" run "$scenario" --quiet --print-hash --end-time "$end" --out "$out/int" \
      --restart "$out/int/checkpoint.fdck" 2>/dev/null)
echo "uninterrupted: $ref; stopped by a signal to process 1 and restarted: $got"
if [ "$got" = "$ref" ] && cmp -s "$out/ref/history.csv" "$out/int/history.csv"; then
    echo "OK: a signal to one process stops all of them at one step"
else
    echo "FAIL"
    exit 1
fi
