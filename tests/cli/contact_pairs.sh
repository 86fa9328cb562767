#!/usr/bin/env bash
# The contact-pairs line of the run summary (issue #16 item 1, docs/output.md): format pinned,
# and its numbers against what else the run reports: "in contact" is the active_contacts of the
# last row of history.csv (written at end_time, the last step), candidates >= in contact > 0
# (the block of restart.toml is on the base at t = 0.025 s: it lands at ~0.02 s and bounces off
# by ~0.03 s), at least one broad-phase search.
#   contact_pairs.sh FDEM SCENARIO WORKDIR
set -euo pipefail
fdem="$1" scenario="$2" work="$3"
rm -rf "$work"
mkdir -p "$work"
"$fdem" run "$scenario" --out "$work/out" --end-time 0.025 > "$work/run.out" 2> "$work/run.err"
re='^pairs      last step: ([0-9]+) candidate \(node, body\) pairs, ([0-9]+) in contact; ([0-9]+) broad-phase searches since t = 0$'
line=$(grep -E "$re" "$work/run.out" || true)
[ -n "$line" ] || { echo "FAIL: no contact-pairs line"; cat "$work/run.out"; exit 1; }
echo "$line"
[[ "$line" =~ $re ]]
cand=${BASH_REMATCH[1]} inc=${BASH_REMATCH[2]} searches=${BASH_REMATCH[3]}
hist=$(tail -n 1 "$work/out/history.csv" | awk -F, '{print $NF}')
echo "history.csv active_contacts at the end: $hist"
[ "$inc" = "$hist" ] || { echo "FAIL: in contact $inc != history.csv $hist"; exit 1; }
[ "$inc" -gt 0 ] || { echo "FAIL: nothing in contact"; exit 1; }
[ "$cand" -ge "$inc" ] || { echo "FAIL: fewer candidates than pairs in contact"; exit 1; }
[ "$searches" -ge 1 ] || { echo "FAIL: no broad-phase search"; exit 1; }
echo "OK: contact pairs line"
