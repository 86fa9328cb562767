#!/usr/bin/env bash
# Usage: rebalance.sh FDEM MPIEXEC SCENARIO OUT "NP..." PARTITION [fdem run options...]
# Spec parallel-and-python.md D10 / T3: load balancing at every broad-phase search
# (--rebalance-every 1 --imbalance 1: a new partition by PARTITION each time, so node groups,
# their candidate pairs and the element halo change owners many times during the run) keeps the
# run bitwise the one-process run: the state hash and history.csv are equal. Fails also when
# the run made no new partition (the test would then prove nothing).
set -euo pipefail
fdem=$1 mpiexec=$2 scenario=$3 out=$4 nps=$5 partition=$6
shift 6
rm -rf "$out"
mkdir -p "$out"
serial=$("$fdem" run "$scenario" --quiet --print-hash --out "$out/serial" "$@" 2>/dev/null)
echo "serial: $serial"
fail=0
for np in $nps; do
    text=$("$mpiexec" --oversubscribe --bind-to none --mca btl self,vader -np "$np" \
        "$fdem" run "$scenario" --out "$out/np$np" --partition "$partition" \
        --rebalance-every 1 --imbalance 1 "$@" 2>/dev/null)
    line=$(grep '^rebalance' <<<"$text" || true)
    hash=$(sed -n 's/^state .* hash \([0-9a-f]*\) .*/hash \1/p' <<<"$text")
    echo "np $np: $hash; $line"
    if [ "$hash" != "$serial" ]; then
        echo "FAIL: the state hash of -np $np with rebalancing differs"
        fail=1
    fi
    n=$(sed -n 's/^rebalance  \([0-9]*\) new partitions.*/\1/p' <<<"$line")
    if [ -z "$n" ] || [ "$n" -lt 1 ]; then
        echo "FAIL: -np $np made no new partition"
        fail=1
    fi
    if ! cmp -s "$out/serial/history.csv" "$out/np$np/history.csv"; then
        echo "FAIL: history.csv of -np $np differs"
        fail=1
    fi
done
if [ "$fail" = 0 ]; then echo "OK: bitwise the serial run through every rebalance"; fi
exit "$fail"
