#!/usr/bin/env bash
# One output directory, one live run. Two runs started into one 'Output/directory' (at once, or one while the other
# is writing; a fresh run while another --resumes it; on 2 ranks too): exactly one complete result, the other
# refused with exit 2 naming the directory and the process that holds it, and nothing else left behind. The lock
# of a run killed with kill -9 does not block the next one. A script replacing a run's directory (run-study.py's
# put_back) takes the same lock.
# usage: shared_directory.sh <spatula> <source directory> <mpiexec> [mpiexec flags...]
set -u
app=$1
source_directory=$2
mpiexec=$3
shift 3
flags=("$@")
here=$(cd "$(dirname "$0")" && pwd)
source "$here/rotation_scene.sh"
enter_scratch_directory
export OPENBLAS_NUM_THREADS=1 OMPI_MCA_btl=self,vader OMPI_MCA_pml=ob1
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }
passed() { [ "$failures" -eq "$checked" ] && echo "ok   $*"; checked=$failures; }
checked=0
wait_for_step() {   # log file, step number: waits until the log shows that converged step (at most 120 s)
  for _ in $(seq 1200); do grep -q "^step \+$2 " "$1" 2>/dev/null && return 0; sleep 0.05; done
  return 1
}
# Only the complete result: no staging, incomplete or set-aside directory and no lock file.
only_result() {   # directory, case
  [ -f "$1/curve.csv" ] && [ "$(tail -n 1 "$1/curve.csv" | cut -d, -f3 | cut -d. -f1)" -ge 11 ] ||
    fail "$2: no complete result in $1/"
  local left
  left=$(ls -d "$1".* 2>/dev/null)
  [ -z "$left" ] || fail "$2: left behind: $left"
}
refused_by() {   # stderr file, holder pid (or empty), case
  grep -q "is being written by another run (process ${2}" "$1" || { fail "$3: the refusal does not name the holder:"; cat "$1"; }
  ! grep -qE "terminate called|Segmentation fault|core dumped|filesystem_error|Signal:" "$1" || fail "$3: crash text"
}

rotation_scene out 12 > scene.xml

# 1. One run writing, a second started into its directory.
"$app" scene.xml > first.log 2>&1 &
first=$!
wait_for_step first.log 1 || fail "the first run did not start"
kill -STOP "$first"   # held still while the second starts (it would otherwise finish first)
status=0
"$app" scene.xml > second.log 2>&1 || status=$?
kill -CONT "$first"
[ "$status" -eq 2 ] || fail "a second run while the first writes: exit $status, expected 2"
refused_by second.log "$first" "second run"
status=0
wait "$first" || status=$?
[ "$status" -eq 0 ] || fail "the first run: exit $status"
only_result out "second run"
passed "1: a second run into a directory being written is refused: $(grep -o "is being written.*" second.log | head -c 160)"

# 2. Two runs started at the same moment: one completes, the other is refused.
rm -rf out
"$app" scene.xml > a.log 2>&1 & a=$!
"$app" scene.xml > b.log 2>&1 & b=$!
status_a=0; status_b=0
wait "$a" || status_a=$?
wait "$b" || status_b=$?
if [ "$status_a$status_b" = 02 ]; then refused_by b.log "$a" "at once"
elif [ "$status_a$status_b" = 20 ]; then refused_by a.log "$b" "at once"
else fail "two runs at once: exits $status_a and $status_b, expected 0 and 2"; fi
only_result out "two runs at once"
passed "2: two runs at once: exits $status_a and $status_b"

# 3. A killed run's lock does not block the next run; a --resume and a fresh run at once: one of them is refused.
rm -rf out
rotation_scene out 12 "" "" '<Parameter name="checkpoint interval" type="double" value="0.001"/>' > scene.xml
"$app" scene.xml > killed.log 2>&1 &
killed=$!
wait_for_step killed.log 3 || fail "the run to be killed did not start"
kill -9 "$killed"; wait "$killed" 2>/dev/null
[ -f out.lock ] && [ -d out.partial ] || fail "kill -9 should leave out.partial and its (released) lock file"
"$app" scene.xml --resume > resume.log 2>&1 & resume=$!
for _ in $(seq 6000); do grep -q "^spatula: resuming" resume.log && break; sleep 0.02; done
kill -STOP "$resume"
status=0
"$app" scene.xml > fresh.log 2>&1 || status=$?
kill -CONT "$resume"
[ "$status" -eq 2 ] || fail "a fresh run while another resumes: exit $status, expected 2"
refused_by fresh.log "$resume" "fresh run while resuming"
status=0
wait "$resume" || status=$?
[ "$status" -eq 0 ] || fail "the resumed run: exit $status"
only_result out "resume"
passed "3: a killed run's lock is taken over; a fresh run while another resumes is refused"

# 4. The same on 2 ranks: a 2-rank run writing, a 2-rank run started into its directory.
rm -rf out
rotation_scene out 12 > scene.xml
"$mpiexec" "${flags[@]}" -np 2 "$app" scene.xml > np2-first.log 2>&1 &
first=$!
wait_for_step np2-first.log 1 || fail "the 2-rank run did not start"
ranks=$(pgrep -d ' ' -f "$app scene.xml" | tr ' ' '\n' | grep -vx "$first" | tr '\n' ' ')
kill -STOP $ranks
status=0
"$mpiexec" "${flags[@]}" -np 2 "$app" scene.xml > np2-second.log 2>&1 || status=$?
kill -CONT $ranks
[ "$status" -eq 2 ] || fail "a second 2-rank run: exit $status, expected 2"
refused_by np2-second.log "" "2 ranks"
status=0
wait "$first" || status=$?
[ "$status" -eq 0 ] || fail "the first 2-rank run: exit $status"
only_result out "2 ranks"
passed "4: on 2 ranks"

# 5. A script that replaces a run's directory takes the same lock: refused while the run writes.
"$app" scene.xml > written.log 2>&1 &
first=$!
wait_for_step written.log 1 || fail "the run did not start"
kill -STOP "$first"
PYTHONPATH="$source_directory/scripts" python3 - <<'PY' || fail "the script took the lock of a directory being written"
from run_lock import DirectoryInUse, directory_lock
try:
    with directory_lock('out'):
        raise SystemExit(1)
except DirectoryInUse as error:
    print('ok   5: the script is refused:', str(error)[:120])
PY
kill -CONT "$first"
wait "$first" || fail "the run beside the script"
PYTHONPATH="$source_directory/scripts" python3 -c "
from run_lock import directory_lock
with directory_lock('out'): pass" || fail "the script could not take the lock of a finished run"
only_result out "script"

[ "$failures" -eq 0 ] && echo "PASS" || echo "$failures failure(s)"
[ "$failures" -eq 0 ]
