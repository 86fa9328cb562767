#!/usr/bin/env bash
# Batch-friendly output (issue #12 item 16), with stderr and stdout redirected to files as on a
# cluster:
#  1. a progress line every --progress-every seconds of wall time, format pinned;
#  2. stdout is line-buffered: a run killed with SIGKILL has its summary in the log already;
#  3. --quiet prints no progress line;
#  4. bodies.csv and probes.csv open as CSV (Python's csv module), every row has the header's
#     length, and every column kind is documented in docs/output.md.
#   progress.sh FDEM SCENARIO WORKDIR DOCS_OUTPUT_MD
set -euo pipefail
fdem="$1" scenario="$2" work="$3" docs="$4"
rm -rf "$work"
mkdir -p "$work"
line='^progress   step [0-9]+ / [0-9]+  t = [0-9.e+-]+ s  [0-9.e+-]+ steps/s  ETA [0-9]+ s$'

"$fdem" run "$scenario" --out "$work/a" --end-time 1.5 --progress-every 0.05 \
    > "$work/a.out" 2> "$work/a.err"
n=$(grep -cE "$line" "$work/a.err" || true)
echo "progress lines: $n"; head -3 "$work/a.err"
[ "$n" -ge 2 ] || { echo "FAIL: expected >= 2 progress lines"; cat "$work/a.err"; exit 1; }
# (load-time warnings, "file:line:column: warning: ...", are allowed: restart.toml's base is two
# elements thick, docs/theory.md §6.13)
if grep -vE "$line" "$work/a.err" | grep -vE "^[^ ]+:[0-9]+:[0-9]+: warning: " | grep -q .; then
    echo "FAIL: other output on stderr"; cat "$work/a.err"; exit 1
fi

# SIGKILL mid-run: whatever was printed to stdout must be in the file
"$fdem" run "$scenario" --out "$work/k" --end-time 100 --progress-every 0.05 \
    > "$work/k.out" 2> "$work/k.err" &
pid=$!
for _ in $(seq 1 400); do
    grep -qE "$line" "$work/k.err" 2>/dev/null && break
    sleep 0.01
done
kill -KILL "$pid"
wait "$pid" || true
grep -q "^scenario " "$work/k.out" && grep -q "^dt " "$work/k.out" ||
    { echo "FAIL: the summary printed before SIGKILL is not in the log (stdout not line-buffered)";
      cat "$work/k.out"; exit 1; }

"$fdem" run "$scenario" --out "$work/q" --end-time 0.3 --progress-every 0.01 --quiet \
    > "$work/q.out" 2> "$work/q.err"
# --quiet: no progress on stderr (load-time warnings still show)
! grep -vE "^[^ ]+:[0-9]+:[0-9]+: warning: " "$work/q.err" | grep -q . ||
    { echo "FAIL: --quiet printed on stderr"; cat "$work/q.err"; exit 1; }

/usr/bin/python3 - "$work/a/bodies.csv" "$docs" <<'PY'
import csv, sys
rows = list(csv.reader(open(sys.argv[1], newline="")))
assert len(rows) > 2, "bodies.csv has no rows"
head = rows[0]
assert head[:2] == ["step", "time"], head[:2]
assert (len(head) - 2) % 12 == 0, len(head)
for r in rows[1:]:
    assert len(r) == len(head), (len(r), len(head))
    [float(x) for x in r]
docs = open(sys.argv[2]).read()
for kind in sorted({h.rsplit(".", 1)[1] for h in head[2:]}):
    assert "`SET." + kind + "`" in docs, "column " + kind + " not in docs/output.md"
print("bodies.csv: %d rows x %d columns, sets %s" %
      (len(rows) - 1, len(head), sorted({h.rsplit(".", 1)[0] for h in head[2:]})))
probes = list(csv.reader(open(sys.argv[1].replace("bodies.csv", "probes.csv"), newline="")))
assert len(probes) == len(rows), (len(probes), len(rows))
ph = probes[0]
assert ph[:2] == ["step", "time"] and (len(ph) - 2) % 7 == 0, ph
for r, b in zip(probes[1:], rows[1:]):
    assert len(r) == len(ph) and r[:2] == b[:2], (r[:2], b[:2])
    [float(x) for x in r]
for kind in sorted({h.rsplit(".", 1)[1] for h in ph[2:]}):
    assert "`NAME." + kind + "`" in docs, "probe column " + kind + " not in docs/output.md"
print("probes.csv: %d rows x %d columns" % (len(probes) - 1, len(ph)))
PY
echo "OK: batch progress, line-buffered stdout, bodies.csv, probes.csv"
