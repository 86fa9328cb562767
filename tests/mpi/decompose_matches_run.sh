#!/usr/bin/env bash
# Usage: decompose_matches_run.sh FDEM MPIEXEC SCENARIO OUT "NP..." PARTITION END_TIME
# Spec parallel-and-python.md T8: for each NP, `mpirun -np NP fdem run` writes partition.csv
# (what each process owned, ran and exchanged per step at its last step, from its own plan and
# the ghost lists it built with the other processes), and `fdem decompose --parts NP` (one
# process, no MPI run) must print the same rows byte for byte. Also requires that some process
# has ghost nodes, so that the comparison is not one of zeros.
set -euo pipefail
fdem=$1 mpiexec=$2 scenario=$3 out=$4 nps=$5 partition=$6 end=$7
rm -rf "$out"
mkdir -p "$out"
fail=0
for np in $nps; do
    "$mpiexec" --oversubscribe --bind-to none --mca btl self,vader -np "$np" \
        "$fdem" run "$scenario" --quiet --out "$out/np$np" --end-time "$end" \
        --partition "$partition" --rebalance-every 0 2>/dev/null
    "$fdem" decompose "$scenario" --parts "$np" --partition "$partition" --end-time "$end" \
        --csv "$out/decompose$np.csv" 2>/dev/null | grep '^parts'
    if ! cmp "$out/np$np/partition.csv" "$out/decompose$np.csv"; then
        echo "FAIL: fdem decompose --parts $np differs from the run's partition.csv:"
        diff "$out/np$np/partition.csv" "$out/decompose$np.csv" || true
        fail=1
    fi
    # column 7: ghost_nodes
    if ! awk -F, 'NR > 1 && $7 > 0 { ok = 1 } END { exit !ok }' "$out/decompose$np.csv"; then
        echo "FAIL: no part of -np $np has ghost nodes"
        fail=1
    fi
done
if [ "$fail" = 0 ]; then echo "OK: fdem decompose counts what the processes exchanged"; fi
exit "$fail"
