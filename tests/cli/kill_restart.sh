#!/usr/bin/env bash
# Interrupt a run with a signal mid-way, restart it from its last checkpoint and require the
# final state, the CSV files (history, bodies, probes) and the PVD series to be identical to an uninterrupted run.
#   kill_restart.sh FDEM SCENARIO WORKDIR KILL|TERM|INT
# KILL: SIGKILL, the last periodic checkpoint is used (the run has no chance to react).
# TERM/INT: the run finishes its step, writes a checkpoint and exits with 143/130.
set -euo pipefail
fdem="$1" scenario="$2" work="$3" sig="$4"
end=1.0  # simulated seconds: ~30000 steps, about a second of wall time
rm -rf "$work"
mkdir -p "$work"

ref=$("$fdem" run "$scenario" --out "$work/ref" --end-time $end --quiet --print-hash)

"$fdem" run "$scenario" --out "$work/int" --end-time $end --checkpoint-every 0.01 --quiet \
    --print-hash > "$work/int.log" 2>&1 &
pid=$!
# wait for the first periodic checkpoint, then interrupt
for _ in $(seq 1 2000); do
    [ -e "$work/int/checkpoint.fdck" ] && break
    sleep 0.005
done
kill -s "$sig" "$pid" || { echo "FAIL: the run ended before it could be interrupted"; exit 1; }
rc=0
wait "$pid" || rc=$?
case "$sig" in
    KILL) want=137 ;;
    TERM) want=143 ;;
    INT) want=130 ;;
esac
if [ "$rc" -ne "$want" ]; then
    echo "FAIL: interrupted run exited with $rc, expected $want"; cat "$work/int.log"; exit 1
fi
if [ "$sig" != KILL ] && ! grep -q "stopped by SIG$sig after step [0-9]* (t = .* s); checkpoint written" "$work/int.log"; then
    echo "FAIL: no stop message"; cat "$work/int.log"; exit 1
fi
if grep -q "^hash" "$work/int.log"; then
    echo "FAIL: the run was not interrupted mid-way"; exit 1
fi

got=$("$fdem" run "$scenario" --out "$work/int" --end-time $end --quiet --print-hash \
      --restart "$work/int/checkpoint.fdck")
echo "reference: $ref"
echo "restarted: $got"
[ "$ref" = "$got" ] || { echo "FAIL: restarted run differs from the uninterrupted run"; exit 1; }
cmp "$work/ref/history.csv" "$work/int/history.csv" || { echo "FAIL: history.csv differs"; exit 1; }
cmp "$work/ref/series.pvd" "$work/int/series.pvd" || { echo "FAIL: series.pvd differs"; exit 1; }
cmp "$work/ref/bodies.csv" "$work/int/bodies.csv" || { echo "FAIL: bodies.csv differs"; exit 1; }
cmp "$work/ref/probes.csv" "$work/int/probes.csv" || { echo "FAIL: probes.csv differs"; exit 1; }
echo "OK: bitwise identical after SIG$sig and restart"
