#!/usr/bin/env bash
# The `timing` table of the run summary (docs/output.md, docs/parallel.md "Timing breakdown"):
# one row per phase and "other", in this order; a distributed run adds "communication" and
# prints min <= mean <= max per row; the mean column (the seconds of a one-process run) adds up
# to the wall time the table names ("other" is the rest of it, so a phase total above the wall
# would show), the percentages to 100; the state hash is that of the same run with --quiet
# (which reads no clock for the table: timing changes no bit); timing.csv has a row per process
# whose means are the table's.
#   timing.sh FDEM SCENARIO WORKDIR END_TIME [MPIEXEC NP]
set -euo pipefail
fdem="$1" scenario="$2" work="$3" end="$4"
launch=()
if [ $# -ge 6 ]; then
    launch=("$5" --oversubscribe --bind-to none --mca btl self,vader -np "$6")
fi
rm -rf "$work"
mkdir -p "$work"
"${launch[@]}" "$fdem" run "$scenario" --out "$work/out" --end-time "$end" > "$work/run.out" \
    2> "$work/run.err"
"${launch[@]}" "$fdem" run "$scenario" --out "$work/quiet" --end-time "$end" --quiet \
    --print-hash > "$work/quiet.out" 2> "$work/quiet.err"
cat "$work/run.out" | sed -n '/^timing/,/^output/p'
head_re='^timing     wall seconds of the ([0-9]+) steps by phase'
grep -qE "$head_re" "$work/run.out" || { echo "FAIL: no timing table"; exit 1; }
steps=$(grep -E '^done ' "$work/run.out" | awk '{print $2}')
tsteps=$(grep -E "$head_re" "$work/run.out" | sed -E "s/$head_re.*/\1/")
[ "$steps" = "$tsteps" ] || { echo "FAIL: table of $tsteps steps, run of $steps"; exit 1; }
if [ ${#launch[@]} -eq 0 ]; then
    names="elements|joints|broad phase|narrow phase|contact apply|node update|other"
else
    names="elements|joints|broad phase|narrow phase|contact apply|node update|communication|other"
fi
rows=$(sed -n '/^timing/,/^output/p' "$work/run.out" | sed '1d;$d')
got=$(echo "$rows" | sed -E 's/^ +//; s/ +[0-9].*//' | paste -sd'|')
[ "$got" = "$names" ] || { echo "FAIL: rows '$got', expected '$names'"; exit 1; }
wall=$(grep -E "$head_re" "$work/run.out" | sed -E 's/.*of (the mean )?([0-9.]+) s\).*/\2/')
echo "$rows" | awk -v wall="$wall" -v mpi=${#launch[@]} '
    { pct += $(NF - 1)
      mean = mpi ? $(NF - 4) : $(NF - 3); sum += mean
      if (mean < 0) { print "FAIL: negative " $0; bad = 1 }
      if (mpi && !($(NF - 5) <= mean && mean <= $(NF - 3))) { print "FAIL: min/mean/max " $0; bad = 1 } }
    END { tol = 1e-3 * wall + 1e-4 * NR
          if (sum < wall - tol || sum > wall + tol) { print "FAIL: rows add to " sum " s, not " wall; bad = 1 }
          if (pct < 99 || pct > 101) { print "FAIL: percentages add to " pct; bad = 1 }
          exit bad }'
# timing.csv: a row per process whose means are the table's mean column
csv="$work/out/timing.csv"
[ -f "$csv" ] || { echo "FAIL: no timing.csv"; exit 1; }
np=${6:-1}
header="rank,steps,elements,joints,broad_phase,narrow_phase,contact_apply,node_update,communication,other,wall"
[ "$(head -1 "$csv")" = "$header" ] || { echo "FAIL: timing.csv header $(head -1 "$csv")"; exit 1; }
[ "$(tail -n +2 "$csv" | wc -l)" = "$np" ] || { echo "FAIL: timing.csv rows != $np"; exit 1; }
table_means=$(echo "$rows" | awk -v mpi=${#launch[@]} '{ print (mpi ? $(NF - 4) : $(NF - 3)) }')
csv_means=$(tail -n +2 "$csv" | awk -F, -v mpi=${#launch[@]} -v steps="$steps" '
    { if ($2 != steps) { print "FAIL: steps " $2; exit 1 }
      for (k = 3; k <= 10; ++k) m[k] += $k; n++ }
    END { for (k = 3; k <= 10; ++k) if (mpi || k != 9) print m[k] / n }')
paste <(echo "$table_means") <(echo "$csv_means") | awk '
    { d = $1 - $2; if (d < 0) d = -d
      if (d > 1e-3 * ($1 < 0 ? -$1 : $1) + 1e-9) { print "FAIL: table " $1 " csv " $2; bad = 1 } }
    END { exit bad }'
h1=$(grep -E '^state ' "$work/run.out" | sed -E 's/.*hash ([0-9a-f]+).*/\1/')
h2=$(sed -E 's/hash //' "$work/quiet.out" | head -1)
[ "$h1" = "$h2" ] || { echo "FAIL: hash $h1 with the table, $h2 without"; exit 1; }
echo "OK: timing table"
