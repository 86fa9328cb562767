#!/usr/bin/env bash
# Usage: saturated_pack.sh FDEM MPIEXEC OUT "NP..."
# The contact-saturated pack (1 600 two-triangle blocks touching and converging on their centre,
# ~16 000 pairs in contact: more than the contact apply's threshold for running on several
# threads) run with 2 OpenMP threads per process: the distributed apply with threads (node spans
# of the gathered records, the bookkeeping split over the threads) and the one-process run with
# threads must both give the bits of the one-process, one-thread run.
set -euo pipefail
fdem=$1 mpiexec=$2 out=$3 nps=$4
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out"
mkdir -p "$out"
/usr/bin/python3 "$here/../loading/make_pack_scenario.py" "$out/scene" 1600 --gap 0 \
    --closing 0.5 --end-time 2e-3
# frames at 0, 1 and 2 ms (same_as_serial.sh compares the last one) and bodies.csv
sed -i 's/^vtu = false$/interval = 1e-3/; s/^bodies = false$/bodies = true/' \
    "$out/scene/scenario.toml"
one=$(OMP_NUM_THREADS=1 "$fdem" run "$out/scene/scenario.toml" --quiet --print-hash \
    --out "$out/one_thread" 2>/dev/null)
echo "one process, one thread: $one"
export OMP_NUM_THREADS=2
"$here/same_as_serial.sh" "$fdem" "$mpiexec" "$out/scene/scenario.toml" "$out/runs" "$nps" \
    > "$out/same_as_serial.log" || { cat "$out/same_as_serial.log"; exit 1; }
cat "$out/same_as_serial.log"
two=$(sed -n 's/^serial: //p' "$out/same_as_serial.log")
if [ "$two" != "$one" ]; then
    echo "FAIL: one process with 2 threads ($two) differs from one thread ($one)"
    exit 1
fi
