#!/usr/bin/env bash
# An interrupted run never leaves a directory that looks complete. SIGTERM or SIGINT stops it at the next converged
# state: exit 128 + signal, the partial results, a 'last state' checkpoint and FAILURE.txt in <directory>.incomplete;
# a run restarted from that checkpoint reaches the same state as one never interrupted. kill -9 of one of two ranks
# leaves only the staging directory <directory>.partial, which the next run replaces.
# usage: interrupted_run.sh <spatula> <mpiexec> [mpiexec flags...]
set -u
app=$1
mpiexec=$2
shift 2
flags=("$@")
here=$(cd "$(dirname "$0")" && pwd)
source "$here/rotation_scene.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
export OPENBLAS_NUM_THREADS=1
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }
wait_for_step() {   # log file, step number: waits until the log shows that converged step (at most 120 s)
  for _ in $(seq 1200); do grep -q "^step \+$2 " "$1" 2>/dev/null && return 0; sleep 0.1; done
  return 1
}
final_moment() { tail -n 1 "$1/curve.csv" | cut -d, -f3,5; }   # theta_y, M_y

rotation_scene reference 15 > reference.xml
"$app" reference.xml > reference.log 2>&1 || fail "the uninterrupted rotation"

for signal in TERM INT; do
  rotation_scene "stopped-$signal" 15 > "stopped-$signal.xml"
  "$app" "stopped-$signal.xml" > "stopped-$signal.log" 2>&1 &
  pid=$!
  wait_for_step "stopped-$signal.log" 4 || fail "SIG$signal: the run did not start"
  kill -"$signal" "$pid"
  status=0
  wait "$pid" || status=$?
  expected=$([ "$signal" = TERM ] && echo 143 || echo 130)
  incomplete="stopped-$signal.incomplete"
  [ "$status" -eq "$expected" ] || fail "SIG$signal: exit $status, expected $expected"
  [ ! -e "stopped-$signal" ] && [ ! -e "stopped-$signal.partial" ] || fail "SIG$signal: a directory that looks complete or staging left"
  grep -q "interrupted by SIG$signal" "$incomplete/FAILURE.txt" 2>/dev/null || fail "SIG$signal: FAILURE.txt does not say why"
  grep -q "Loading/restart from = 'last state'" "$incomplete/FAILURE.txt" 2>/dev/null || fail "SIG$signal: FAILURE.txt does not say how to go on"
  [ -s "$incomplete/checkpoints.h5" ] && [ "$(wc -l < "$incomplete/curve.csv")" -ge 5 ] || fail "SIG$signal: no checkpoint or curve"
  grep -q "interrupted by SIG$signal" "stopped-$signal.log" || fail "SIG$signal: the log does not say so"
done

# Going on from the last state of the SIGTERM run reaches the reference's final state.
rotation_scene resumed 15 "" "<Parameter name=\"restart file\" type=\"string\" value=\"stopped-TERM.incomplete/checkpoints.h5\"/>
  <Parameter name=\"restart from\" type=\"string\" value=\"last state\"/>" > resumed.xml
"$app" resumed.xml > resumed.log 2>&1 || { fail "the resumed run"; tail -3 resumed.log; }
grep -q "restart from 'last state'" resumed.log || fail "the resumed run did not restart from the last state"
/usr/bin/python3 - "$(final_moment reference)" "$(final_moment resumed)" <<'PY' || fail "resumed run ends elsewhere"
import sys
(theta_a, moment_a), (theta_b, moment_b) = (map(float, arg.split(',')) for arg in sys.argv[1:3])
assert abs(theta_a - theta_b) < 1e-9 and abs(moment_a - moment_b) <= 1e-6 * abs(moment_a), (theta_a, moment_a, theta_b, moment_b)
print(f'resumed: M_y {moment_b:.6f} at {theta_b} deg, uninterrupted {moment_a:.6f}')
PY

# kill -9 of one of two ranks: nothing that looks complete; the next run replaces the staging directory.
rotation_scene killed 15 > killed.xml
timeout 120 "$mpiexec" "${flags[@]}" -np 2 "$app" "$work/killed.xml" > killed.log 2>&1 &
launcher=$!
wait_for_step killed.log 3 || fail "kill -9: the run did not start"
victim=$(pgrep -f "$app $work/killed.xml" | tail -n 1)
[ -n "$victim" ] && kill -9 "$victim"
wait "$launcher"
[ ! -e killed ] && [ ! -e killed.incomplete ] && [ -f killed.partial/.spatula-output ] || { fail "kill -9: left"; ls -A; }
sed -i 's/value="15"/value="6"/' killed.xml
"$app" killed.xml > killed-again.log 2>&1 || fail "the run after kill -9"
[ -f killed/curve.csv ] && [ ! -e killed.partial ] || fail "the run after kill -9 did not replace the staging directory"

[ "$failures" -eq 0 ] && echo "interrupted runs: stopped cleanly, resumable, never complete-looking"
exit "$failures"
