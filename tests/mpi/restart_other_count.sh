#!/usr/bin/env bash
# Usage: restart_other_count.sh FDEM MPIEXEC SCENARIO OUT T_HALF T_END [fdem run options...]
# T4 of spec parallel-and-python.md: -np 2 to T_HALF writing a checkpoint, then a restart with
# -np 3 and one with 1 process to T_END: both final state hashes equal an uninterrupted
# one-process run's, and the two restarted history.csv files are byte-identical. The options
# (e.g. --rebalance-every 1 --imbalance 1: a new partition at every search, before and after
# the restart) go to the distributed runs.
set -euo pipefail
fdem=$1 mpiexec=$2 scenario=$3 out=$4 half=$5 end=$6
shift 6
opts=("$@")
mpi() {
    local np=$1
    shift
    "$mpiexec" --oversubscribe --bind-to none --mca btl self,vader -np "$np" "$@" "${opts[@]}"
}
rm -rf "$out"
mkdir -p "$out"
ref=$("$fdem" run "$scenario" --quiet --print-hash --end-time "$end" --out "$out/ref" 2>/dev/null)
mpi 2 "$fdem" run "$scenario" --quiet --end-time "$half" --checkpoint-every "$half" \
    --out "$out/first" 2>/dev/null
r3=$(mpi 3 "$fdem" run "$scenario" --quiet --print-hash --end-time "$end" \
    --restart "$out/first/checkpoint.fdck" --out "$out/np3" 2>/dev/null)
r1=$("$fdem" run "$scenario" --quiet --print-hash --end-time "$end" \
    --restart "$out/first/checkpoint.fdck" --out "$out/np1" 2>/dev/null)
echo "uninterrupted: $ref; restarted with -np 3: $r3; with 1 process: $r1"
# the summary's pairs line right after a restore (no step, no broad phase yet): each process of a
# distributed run holds only its own targets' candidates once it has searched, so the count it
# prints must come from the restored serial list, as with one process
pairs() { grep '^pairs' || true; }
p3=$(mpi 3 "$fdem" run "$scenario" --end-time "$half" --restart "$out/first/checkpoint.fdck"     --out "$out/np3_0" 2>/dev/null | pairs)
p1=$("$fdem" run "$scenario" --end-time "$half" --restart "$out/first/checkpoint.fdck"     --out "$out/np1_0" 2>/dev/null | pairs)
echo "pairs after the restore, -np 3: $p3; 1 process: $p1"
if [ -z "$p1" ] || [ "$p3" != "$p1" ]; then
    echo "FAIL: the pairs line after a restore differs"
    exit 1
fi
if [ "$r3" = "$ref" ] && [ "$r1" = "$ref" ] && cmp -s "$out/np3/history.csv" "$out/np1/history.csv"; then
    echo "OK: restart on another process count is bitwise"
else
    echo "FAIL"
    exit 1
fi
