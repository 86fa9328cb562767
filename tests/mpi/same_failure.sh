#!/usr/bin/env bash
# Usage: same_failure.sh FDEM MPIEXEC SCENARIO OUT NP RC
# A scenario that fails (input error: RC 2, simulation failure: RC 1) fails under mpirun -np NP
# with the same exit code and the same error message as the one-process run, never a hang (the
# test's timeout), and failure.vtu, where the one-process run writes one, is byte-identical
# (issue #15, spec parallel-and-python.md T7, D9).
set -uo pipefail
fdem=$1 mpiexec=$2 scenario=$3 out=$4 np=$5 want=$6
rm -rf "$out"
mkdir -p "$out"
"$fdem" run "$scenario" --quiet --out "$out/serial" 2>"$out/serial.err"
rc_s=$?
"$mpiexec" --oversubscribe --bind-to none --mca btl self,vader -np "$np" \
    "$fdem" run "$scenario" --quiet --out "$out/np$np" 2>"$out/np$np.err"
rc_p=$?
echo "exit codes: serial $rc_s, -np $np $rc_p (expected $want)"
fail=0
if [ "$rc_s" != "$want" ] || [ "$rc_p" != "$want" ]; then fail=1; fi
msg=$(grep -m1 "error" "$out/serial.err")
echo "serial message: $msg"
if [ -z "$msg" ] || ! grep -qF -- "$msg" "$out/np$np.err"; then
    echo "FAIL: -np $np did not print the serial message; it printed:"
    cat "$out/np$np.err"
    fail=1
fi
n=$(grep -cF -- "$msg" "$out/np$np.err")
if [ "$n" != 1 ]; then echo "FAIL: the message appears $n times (process 0 alone prints)"; fail=1; fi
if [ -f "$out/serial/failure.vtu" ] && ! cmp -s "$out/serial/failure.vtu" "$out/np$np/failure.vtu"; then
    echo "FAIL: failure.vtu differs"
    fail=1
fi
if [ $fail -eq 0 ]; then echo "OK: the same failure"; fi
exit $fail
