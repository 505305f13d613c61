#!/usr/bin/env bash
# `spatula --stop-after-checkpoint THETA` (a workflow's rotation in parts, each pull-off started once its checkpoint
# exists): the rotation stops once its checkpoint at THETA is written, exit 0, its results and a last state in
# <directory>.incomplete; `--resume --stop-after-checkpoint` takes it to the next checkpoint and `--resume` to the end,
# where it meets the rotation run in one go (a resumed part starts its step control afresh, as the one-go run does at
# every checkpoint; only a reused factorization differs, within the Newton tolerance). A checkpoint at the end of the
# path just completes the run. Bad values and a checkpoint already passed are input errors (exit 2) naming the
# option, the value and the inclinations allowed.
# usage: stop_after_checkpoint.sh <spatula>
set -u
app=$1
here=$(cd "$(dirname "$0")" && pwd)
source "$here/rotation_scene.sh"
enter_scratch_directory
export OPENBLAS_NUM_THREADS=1
check_counts
checkpoints='<Parameter name="checkpoints at theta_y" type="string" value="8,14,20"/>'
final_moment() { tail -n 1 "$1/curve.csv" | cut -d, -f3,5; }   # theta_y, M_y

# The rotation in one go; a stop asked at its end (20 deg) completes it.
rotation_scene whole 20 "" "$checkpoints" | tight_newton > whole.xml
status=0
"$app" whole.xml --stop-after-checkpoint 20 > whole.log 2>&1 || status=$?
[ "$status" -eq 0 ] && [ -f whole/curve.csv ] || fail "a stop at the end of the path: exit $status, no complete run"
passed "a stop at the path's end completes the run: $(final_moment whole)"

# In three parts.
rotation_scene parts 20 "" "$checkpoints" | tight_newton > parts.xml
status=0
"$app" parts.xml --stop-after-checkpoint 8 > part-1.log 2>&1 || status=$?
[ "$status" -eq 0 ] || fail "part 1: exit $status, expected 0"
[ -d parts.incomplete ] && [ ! -e parts ] || fail "part 1: not left stopped in parts.incomplete/"
grep -q "stopped as asked after writing the checkpoint 'theta_y=8'" parts.incomplete/FAILURE.txt ||
  fail "part 1: FAILURE.txt does not say why it stopped"
[ "$(final_moment parts.incomplete | cut -d, -f1)" = 8 ] || fail "part 1: the curve ends at $(final_moment parts.incomplete)"
passed "part 1 stops at theta_y = 8 deg, exit 0"

status=0
"$app" parts.xml --resume --stop-after-checkpoint 8 > passed.log 2>&1 || status=$?
[ "$status" -eq 2 ] && grep -q "input error: --stop-after-checkpoint 8 with --resume: the stopped run has passed" passed.log ||
  { fail "a checkpoint already written: exit $status"; tail -n 2 passed.log; }
passed "a checkpoint already passed: $(grep -o 'input error: .*' passed.log | head -c 120)"

status=0
"$app" parts.xml --resume --stop-after-checkpoint 14 > part-2.log 2>&1 || status=$?
[ "$status" -eq 0 ] && [ "$(final_moment parts.incomplete | cut -d, -f1)" = 14 ] || fail "part 2: exit $status"
status=0
"$app" parts.xml --resume > part-3.log 2>&1 || status=$?
[ "$status" -eq 0 ] && [ -f parts/curve.csv ] && [ ! -e parts.incomplete ] || fail "part 3: exit $status, not complete"
[ "$(wc -l < parts/curve.csv)" -eq "$(wc -l < whole/curve.csv)" ] || fail "the parts took other steps than the whole"
awk -F, -v a="$(final_moment whole | cut -d, -f2)" -v b="$(final_moment parts | cut -d, -f2)" \
  'BEGIN { exit !(a > 0 && (a - b) ^ 2 <= (1e-6 * a) ^ 2) }' ||
  fail "the parts end at M_y $(final_moment parts), the whole at $(final_moment whole)"
passed "three parts end where the whole does: $(final_moment parts) against $(final_moment whole)"

# Bad values.
for value in 10 abc; do
  status=0
  "$app" whole.xml --stop-after-checkpoint "$value" --validate-only > bad.log 2>&1 || status=$?
  [ "$status" -eq 2 ] && grep -q "input error: --stop-after-checkpoint" bad.log || fail "--stop-after-checkpoint $value: exit $status"
done
grep -q "not one of the scene's 'Loading/checkpoints at theta_y' = 8, 14, 20" \
  <("$app" whole.xml --stop-after-checkpoint 10 --validate-only 2>&1) || fail "the error does not list the checkpoints"
passed "bad values refused: $(grep -o 'input error: .*' bad.log | head -c 120)"

[ "$failures" -eq 0 ] && echo "PASS" || echo "$failures failure(s)"
[ "$failures" -eq 0 ]
