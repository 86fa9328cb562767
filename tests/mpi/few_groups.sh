#!/usr/bin/env bash
# Usage: few_groups.sh FDEM MPIEXEC OUT
# Models with fewer node groups (64 nodes each) than processes: a pack of 16 two-triangle blocks
# (64 nodes, one group) and one of 30 (120 nodes, two groups) on 2, 3 and 4 processes with the
# default partition (Zoltan RCB). Zoltan refuses a process without points (ZOLTAN_FATAL), which
# stopped one process while the others waited for ever; now such a partition gives group g to
# process g (parallel/mpi/rcb.cpp) and the runs are bitwise the serial ones.
set -euo pipefail
fdem=$1 mpiexec=$2 out=$3
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out"
mkdir -p "$out"
for n in 16 30; do
    /usr/bin/python3 "$here/../loading/make_pack_scenario.py" "$out/pack$n" "$n" --gap 0 \
        --closing 0.5 --end-time 2e-4 > /dev/null
    # frames at 0, 0.1 and 0.2 ms (same_as_serial.sh compares the last one) and bodies.csv
    sed -i 's/^vtu = false$/interval = 1e-4/; s/^bodies = false$/bodies = true/' \
        "$out/pack$n/scenario.toml"
    # (the frames: only the processes with a group hold cells)
    FDEM_TEST_GROUPS=$(( (4 * n + 63) / 64 )) "$here/same_as_serial.sh" "$fdem" "$mpiexec" "$out/pack$n/scenario.toml" "$out/runs$n" \
        "2 3 4" > "$out/pack$n.log" || { cat "$out/pack$n.log"; exit 1; }
    echo "pack of $n blocks:"
    cat "$out/pack$n.log"
done
echo "OK: fewer node groups than processes, bitwise the serial run"
