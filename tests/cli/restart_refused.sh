#!/usr/bin/env bash
# A checkpoint is refused (exit 2, message naming the problem) when it belongs to another model,
# is truncated or corrupt, or is not a checkpoint at all.
#   restart_refused.sh FDEM CLI_DIR WORKDIR
set -euo pipefail
fdem="$1" dir="$2" work="$3"
rm -rf "$work"
mkdir -p "$work"
"$fdem" run "$dir/restart.toml" --out "$work/a" --end-time 0.002 --checkpoint-every 0.001 --quiet
ck="$work/a/checkpoint.fdck"

expect() {  # expect NAME REGEX CHECKPOINT SCENARIO
    local rc=0
    "$fdem" run "$4" --out "$work/$1" --quiet --restart "$3" 2> "$work/$1.err" || rc=$?
    if [ "$rc" -ne 2 ]; then echo "FAIL $1: exit code $rc, expected 2"; cat "$work/$1.err"; exit 1; fi
    if ! grep -Eq "$2" "$work/$1.err"; then
        echo "FAIL $1: message does not match '$2':"; cat "$work/$1.err"; exit 1
    fi
    echo "ok $1: $(head -1 "$work/$1.err")"
}

# another scenario (finer mesh): different model
expect other_model "checkpoint '.*' is unusable: it was written for a different model or time step \(model hash [0-9a-f]{16}, this scenario gives [0-9a-f]{16}\)" \
    "$ck" "$dir/determinism.toml"
# truncated file
head -c 1000 "$ck" > "$work/trunc.fdck"
expect truncated "unusable: checksum mismatch \(the file is truncated or corrupt\)" "$work/trunc.fdck" "$dir/restart.toml"
# one flipped byte in the middle
cp "$ck" "$work/flip.fdck"
printf '\xff' | dd of="$work/flip.fdck" bs=1 seek=500 conv=notrunc status=none
expect corrupt "unusable: checksum mismatch" "$work/flip.fdck" "$dir/restart.toml"
# not a checkpoint
expect not_checkpoint "unusable: not an fdem checkpoint \(wrong magic bytes\)" "$dir/restart.toml" "$dir/restart.toml"
# missing file
expect missing "cannot open checkpoint '.*no_such.fdck': No such file" "$work/no_such.fdck" "$dir/restart.toml"
