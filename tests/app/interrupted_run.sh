#!/usr/bin/env bash
# An interrupted run never leaves a directory that looks complete. SIGTERM or SIGINT stops it at the next converged
# state: exit 128 + signal, the partial results, a 'last state' checkpoint and FAILURE.txt in <directory>.incomplete;
# a run restarted from that checkpoint reaches the same state as one never interrupted. kill -9 of one of two ranks
# leaves only the staging directory <directory>.partial: `--resume` goes on from its last periodic checkpoint and
# reproduces the uninterrupted curve; a run without --resume replaces it.
# usage: interrupted_run.sh <spatula> <mpiexec> [mpiexec flags...]
set -u
app=$1
mpiexec=$2
shift 2
flags=("$@")
here=$(cd "$(dirname "$0")" && pwd)
source "$here/rotation_scene.sh"
enter_scratch_directory
export OPENBLAS_NUM_THREADS=1
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }
wait_for_step() {   # log file, step number: waits until the log shows that converged step (at most 120 s)
  for _ in $(seq 1200); do grep -q "^step \+$2 " "$1" 2>/dev/null && return 0; sleep 0.1; done
  return 1
}
# A resumed run starts its predictor afresh (from the last converged state alone), so it meets the uninterrupted path
# to the Newton tolerance: the scenes here use an absolute tolerance of 1e-9 (tight_newton).
tight_scene() { rotation_scene "$@" | tight_newton; }
final_moment() { tail -n 1 "$1/curve.csv" | cut -d, -f3,5; }   # theta_y, M_y

tight_scene reference 15 > reference.xml
"$app" reference.xml > reference.log 2>&1 || fail "the uninterrupted rotation"

for signal in TERM INT; do
  tight_scene "stopped-$signal" 15 > "stopped-$signal.xml"
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
tight_scene resumed 15 "" "<Parameter name=\"restart file\" type=\"string\" value=\"stopped-TERM.incomplete/checkpoints.h5\"/>
  <Parameter name=\"restart from\" type=\"string\" value=\"last state\"/>" > resumed.xml
"$app" resumed.xml > resumed.log 2>&1 || { fail "the resumed run"; tail -3 resumed.log; }
grep -q "restart from 'last state'" resumed.log || fail "the resumed run did not restart from the last state"
/usr/bin/python3 - "$(final_moment reference)" "$(final_moment resumed)" <<'PY' || fail "resumed run ends elsewhere"
import sys
(theta_a, moment_a), (theta_b, moment_b) = (map(float, arg.split(',')) for arg in sys.argv[1:3])
assert abs(theta_a - theta_b) < 1e-9 and abs(moment_a - moment_b) <= 1e-6 * abs(moment_a), (theta_a, moment_a, theta_b, moment_b)
print(f'resumed: M_y {moment_b:.6f} at {theta_b} deg, uninterrupted {moment_a:.6f}')
PY

# `--resume` goes on with the SIGINT run in its own directory (from <directory>.incomplete) to the same final state,
# also when the stopped run was made by an earlier version of the program, whose scene.xml lacks the parameters added
# since (here 'Loading/Jump/reused factors'): they take their defaults.
sed -i '/name="reused factors"/d' stopped-INT.incomplete/scene.xml
grep -q 'name="step balance tolerance"' stopped-INT.incomplete/scene.xml &&
  ! grep -q 'name="reused factors"' stopped-INT.incomplete/scene.xml || fail "could not age the stopped run's scene.xml"
"$app" stopped-INT.xml --resume > resumed-INT.log 2>&1 || { fail "--resume of the SIGINT run"; tail -3 resumed-INT.log; }
[ -f stopped-INT/curve.csv ] && [ ! -e stopped-INT.incomplete ] || fail "--resume of the SIGINT run: not committed"
[ "$(final_moment reference)" = "$(final_moment stopped-INT)" ] ||
  python3 -c "import sys; a, b = (list(map(float, x.split(','))) for x in sys.argv[1:]); assert abs(a[1]-b[1]) <= 1e-6*abs(a[1])" \
    "$(final_moment reference)" "$(final_moment stopped-INT)" || fail "--resume of the SIGINT run ends elsewhere"

# kill -9 of one of two ranks: nothing that looks complete; `--resume` goes on from the last periodic checkpoint
# (every converged step here) on two ranks and reproduces the uninterrupted curve row by row.
every_step='<Parameter name="checkpoint interval" type="double" value="0.00001"/>'
kill_a_rank() {   # scene name, step to wait for
  timeout 120 "$mpiexec" "${flags[@]}" -np 2 "$app" "$work/$1.xml" > "$1.log" 2>&1 &
  local launcher=$!
  wait_for_step "$1.log" "$2" || fail "kill -9 ($1): the run did not start"
  local victim
  victim=$(pgrep -f "$app $work/$1.xml" | tail -n 1)
  [ -n "$victim" ] && kill -9 "$victim"
  wait "$launcher"
}
tight_scene killed 15 "" "" "$every_step" > killed.xml
kill_a_rank killed 3
[ ! -e killed ] && [ ! -e killed.incomplete ] && [ -f killed.partial/.spatula-output ] || { fail "kill -9: left"; ls -A; }
grep -q "checkpoint 'last state' written" killed.log || fail "kill -9: no periodic checkpoint was written"
timeout 120 "$mpiexec" "${flags[@]}" -np 2 "$app" "$work/killed.xml" --resume > resumed-killed.log 2>&1 ||
  { fail "--resume after kill -9"; tail -3 resumed-killed.log; }
grep -q "resuming the stopped run" resumed-killed.log || fail "--resume does not say what it resumes"
[ -f killed/curve.csv ] && [ ! -e killed.partial ] && [ ! -e killed/FAILURE.txt ] || { fail "--resume: not committed"; ls -A; }
/usr/bin/python3 - reference/curve.csv killed/curve.csv <<'PY' || fail "the resumed curve is not the uninterrupted one"
import csv, sys
a, b = (list(csv.DictReader(open(f))) for f in sys.argv[1:3])
assert [r['step'] for r in a] == [r['step'] for r in b], ([r['step'] for r in a], [r['step'] for r in b])
for ra, rb in zip(a, b):
    for key in ('theta_y_deg', 'M_y_nNnm', 'Pi_int_1e-18J'):
        x, y = float(ra[key]), float(rb[key])
        assert abs(x - y) <= 1e-6 * max(1.0, abs(x)), (ra['step'], key, x, y)
assert float(b[-1]['wall_s']) > float(b[1]['wall_s'])
print(f'resumed after kill -9: {len(b)} rows, the uninterrupted curve to 1e-6')
PY

# A killed run started again without --resume is replaced; --resume with nothing stopped, or with another load,
# is an input error that names what is wrong.
tight_scene killed-again 15 > killed-again.xml
kill_a_rank killed-again 3
[ -f killed-again.partial/.spatula-output ] || fail "kill -9 (again): no staging directory"
sed -i 's/value="15"/value="6"/' killed-again.xml
status=0
"$app" killed-again.xml --resume > wrong-resume.log 2>&1 || status=$?
[ "$status" -eq 2 ] && grep -q "no 'last state' checkpoint" wrong-resume.log ||
  { fail "--resume without a periodic checkpoint: exit $status"; cat wrong-resume.log; }
tight_scene killed-again 6 "" "" "$every_step" > killed-again.xml
"$app" killed-again.xml > killed-again.log 2>&1 || fail "the run after kill -9"
[ -f killed-again/curve.csv ] && [ ! -e killed-again.partial ] || fail "the run after kill -9 did not replace the staging directory"
status=0
"$app" killed-again.xml --resume > nothing-to-resume.log 2>&1 || status=$?
[ "$status" -eq 2 ] && grep -q "no stopped run to go on from" nothing-to-resume.log ||
  { fail "--resume with nothing stopped: exit $status"; cat nothing-to-resume.log; }
kill_a_rank killed 3; sed -i 's/value="15"/value="16"/' killed.xml
status=0
"$app" killed.xml --resume > other-load.log 2>&1 || status=$?
[ "$status" -eq 2 ] && grep -q "other 'Loading' parameters" other-load.log ||
  { fail "--resume with another load: exit $status"; cat other-load.log; }

# A stiction pull-off whose anchors were set at its restart state ('Adhesion/stiction anchors' = 'restart state')
# keeps that state in its checkpoints: `--resume` after SIGTERM measures the travel from the same anchors and ends
# where the uninterrupted pull-off ends (anchored at the resumed state instead, the tangential forces would start
# again from zero). Every step is checkpointed so the resumed run starts from the step it was stopped at; the
# restarted curve counts on from the rotation's steps (its first lift step is step 6 here).
tight_scene anchor-rotation 12 "" '<Parameter name="checkpoints at theta_y" type="string" value="12"/>' > anchor-rotation.xml
"$app" anchor-rotation.xml > anchor-rotation.log 2>&1 || fail "the rotation the stiction pull-off starts from"
stiction_scene() {   # directory
  lift_scene "$1" stiction anchor-rotation/checkpoints.h5 12 45 3 \
    '<Parameter name="stiction anchors" type="string" value="restart state"/>' \
    '<Parameter name="free slide during lift" type="bool" value="true"/>' "$every_step" | tight_newton
}
stiction_scene stiction-reference > stiction-reference.xml
"$app" stiction-reference.xml > stiction-reference.log 2>&1 || { fail "the uninterrupted stiction pull-off"; tail -3 stiction-reference.log; }
stiction_scene stiction-stopped > stiction-stopped.xml
"$app" stiction-stopped.xml > stiction-stopped.log 2>&1 &
pid=$!
wait_for_step stiction-stopped.log 8 || fail "the stiction pull-off to stop did not start"
kill -TERM "$pid"
wait "$pid"
"$app" stiction-stopped.xml --resume > stiction-resumed.log 2>&1 || { fail "--resume of the stiction pull-off"; tail -3 stiction-resumed.log; }
/usr/bin/python3 - stiction-reference/curve.csv stiction-stopped/curve.csv <<'PY' || fail "the resumed stiction pull-off is not the uninterrupted one"
import csv, sys
a, b = (list(csv.DictReader(open(f))) for f in sys.argv[1:3])
assert [r['step'] for r in a] == [r['step'] for r in b], ([r['step'] for r in a], [r['step'] for r in b])
for ra, rb in zip(a, b):
    for key in ('u_z_nm', 'P_z_nN', 'u_x_nm', 'Pi_int_1e-18J'):
        x, y = float(ra[key]), float(rb[key])
        assert abs(x - y) <= 1e-6 * max(1.0, abs(x)), (ra['step'], key, x, y)
assert abs(float(a[-1]['u_x_nm'])) > 1e-3, 'no tangential travel: the test could not tell the anchors apart'
print(f"resumed stiction pull-off: {len(b)} rows as uninterrupted to 1e-6 (u_x {float(b[-1]['u_x_nm']):.4f} nm)")
PY

# A carried stopped run (run-study.py --carry keeps its checkpoints, curve and scene, not its fields) resumed past
# several field intervals: its fields start again at the resumed state, and mesh.h5 and the states index hold exactly
# the states the resumed run wrote, numbered from 0, at its steps divisible by the interval and its last one.
tight_scene carried 40 "" "" "$every_step"'<Parameter name="field interval" type="int" value="2"/>' > carried.xml
"$app" carried.xml > carried.log 2>&1 &
pid=$!
wait_for_step carried.log 3 || fail "the run to carry did not start"
kill -TERM "$pid"
wait "$pid"
rm -f carried.incomplete/mesh.h5 carried.incomplete/mesh*.xmf
stopped_at=$(tail -n 1 carried.incomplete/curve.csv | cut -d, -f1)
"$app" carried.xml --resume > carried-resumed.log 2>&1 || { fail "--resume of the carried run"; tail -3 carried-resumed.log; }
grep -q "field states cannot be kept" carried-resumed.log || fail "the carried run's resume does not say its fields start again"
/usr/bin/python3 - carried "$stopped_at" <<'PY' || fail "the carried run's fields are not the states it wrote"
import csv, re, sys
import h5py
directory, stopped_at = sys.argv[1], int(sys.argv[2])
rows = [r for r in csv.DictReader(open(f'{directory}/curve.csv')) if int(r['step']) > stopped_at]
expected = [float(r['theta_y_deg']) for r in rows if int(r['step']) % 2 == 0]
if int(rows[-1]['step']) % 2:
    expected.append(float(rows[-1]['theta_y_deg']))
with h5py.File(f'{directory}/mesh.h5', 'r') as fields:
    names = sorted(fields['states'])
    times = [float(fields['states'][name]['time'][0]) for name in names]
assert names == [f'{k:06d}' for k in range(len(names))], names
assert len(times) == len(expected) >= 3 and all(abs(a - b) < 1e-9 for a, b in zip(times, expected)), (times, expected)
indexed = [float(t) for t in re.findall(r'<Time Value="([^"]+)"', open(f'{directory}/mesh_states.xmf').read())]
assert len(indexed) == len(times) and all(abs(a - b) < 1e-4 for a, b in zip(indexed, times)), (indexed, times)
print(f'carried run resumed at step {stopped_at}: {len(times)} field states from there, indexed')
PY

[ "$failures" -eq 0 ] && echo "interrupted runs: stopped cleanly, resumable, never complete-looking"
exit "$failures"
