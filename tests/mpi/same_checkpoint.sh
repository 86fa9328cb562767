#!/usr/bin/env bash
# Usage: same_checkpoint.sh FDEM MPIEXEC SCENARIO OUT "NP..." END CHECKPOINT_EVERY
# The checkpoint a distributed run writes is byte for byte the one-process run's (spec D12): each
# process holds only its own targets' candidate pairs (the local broad phase), and the file must
# still hold the serial list, the serial pair histories and state. The scenario is copied with
# [output] merge = true (mesh paths made absolute), so that the frame names the checkpoint lists
# are the same .vtu names in both runs.
set -euo pipefail
fdem=$1 mpiexec=$2 scenario=$3 out=$4 nps=$5 end=$6 every=$7
rm -rf "$out"
mkdir -p "$out"
dir=$(cd "$(dirname "$scenario")" && pwd)
sed -e "s|^mesh = \"|mesh = \"$dir/|" -e 's|^\[output\]|[output]\nmerge = true|' "$scenario" \
    > "$out/merged.toml"
grep -q '^merge = true' "$out/merged.toml" || { echo "FAIL: no [output] table to merge"; exit 1; }
"$fdem" run "$out/merged.toml" --quiet --out "$out/serial" --end-time "$end" \
    --checkpoint-every "$every" > /dev/null 2>&1
fail=0
for np in $nps; do
    "$mpiexec" --oversubscribe --bind-to none --mca btl self,vader -np "$np" \
        "$fdem" run "$out/merged.toml" --quiet --out "$out/np$np" --end-time "$end" \
        --checkpoint-every "$every" > /dev/null 2>&1
    if cmp "$out/serial/checkpoint.fdck" "$out/np$np/checkpoint.fdck"; then
        echo "np $np: checkpoint.fdck bitwise the serial one"
    else
        echo "FAIL: checkpoint.fdck of -np $np differs"
        fail=1
    fi
done
if [ $fail -eq 0 ]; then echo "OK: the serial checkpoint"; fi
exit $fail
