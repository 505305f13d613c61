#!/usr/bin/env bash
# A write that fails ends the run cleanly. On a file system too small for the run's output from the start, the
# preflight refuses it (exit 2, the estimate, nothing written); one that fills during the run, one made read-only
# and an output directory removed while the run goes each end it with exit 1 and a message naming the file and the
# system's reason, no crash, never a complete-looking directory, and a curve whose every row is whole. Needs a tmpfs
# mount (root): skipped (exit 77) where mounting is not allowed.
# usage: failing_writes.sh <spatula>
set -u
app=$1
here=$(cd "$(dirname "$0")" && pwd)
source "$here/rotation_scene.sh"
enter_scratch_directory
export OPENBLAS_NUM_THREADS=1 OMPI_MCA_btl=self OMPI_MCA_pml=ob1
mkdir disk
cleanup() { umount -l "$work"/disk/out.* 2>/dev/null; umount -l "$work/disk" 2>/dev/null; rm -rf "$work"; }
trap cleanup EXIT
mount_disk() {   # size
  umount -l disk 2>/dev/null
  mount -t tmpfs -o "size=$1" tmpfs disk 2>/dev/null
}
mount_disk 96k || { echo "SKIP: cannot mount a tmpfs here (needs root)"; exit 77; }
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }
passed() { [ "$failures" -eq "$checked" ] && echo "ok   $*"; checked=$failures; }
checked=0
wait_for_step() {   # log file, step number (at most 120 s)
  for _ in $(seq 2400); do grep -q "^step \+$2 " "$1" 2>/dev/null && return 0; sleep 0.05; done
  return 1
}
no_crash() {   # log, case
  ! grep -qE "terminate called|Segmentation fault|core dumped|filesystem_error|Signal:|Aborted" "$1" || { fail "$2: crash text"; cat "$1"; }
}
whole_rows() {   # curve, case: every row has the header's number of fields
  [ -f "$1" ] || { fail "$2: no curve kept"; return; }
  awk -F, 'NR == 1 { n = NF } NF != n { bad = 1 } END { exit bad }' "$1" || fail "$2: the curve has a cut row"
}
# A rotation with its mesh and field states written at every step (enough output to fill a small disk).
rotation_scene disk/out 40 "" "" '<Parameter name="field interval" type="int" value="1"/>' |
  sed 's#<Parameter name="write mesh" type="bool" value="false"/>##' > scene.xml

# 1. Too small from the start: refused by the preflight with the estimate.
status=0
"$app" scene.xml > small.log 2>&1 || status=$?
[ "$status" -eq 2 ] || fail "a 96 KiB disk: exit $status, expected 2"
grep -q "the run will write up to about .* MB .* has 0.* MB free" small.log || { fail "no estimate in the refusal"; cat small.log; }
[ -z "$(ls -A disk)" ] || fail "a refused run wrote into the disk: $(ls -A disk)"
no_crash small.log "small disk"
passed "1: refused from the start: $(grep -o "the run will write.*free" small.log)"

# 2-4. A disk that fills, is made read-only, or loses the output directory while the run goes.
for case in full read-only removed; do
  mount_disk 16m || fail "$case: cannot mount"
  "$app" scene.xml > "$case.log" 2>&1 &
  pid=$!
  wait_for_step "$case.log" 3 || fail "$case: the run did not start"
  case $case in
    full) dd if=/dev/zero of=disk/filler bs=4k > /dev/null 2>&1; reason="No space left on device" ;;
    read-only)   # a read-only view of the output directory over it (the run's open files stay writable)
      # The remount is refused (busy) while the run has a file open for writing through the new view: the run
      # opens one at every step, so try again until it falls between two writes.
      mount --bind disk/out.partial disk/out.partial || fail "read-only: cannot bind"
      remounted=false
      for _ in $(seq 200); do
        mount -o remount,bind,ro disk/out.partial 2>/dev/null && { remounted=true; break; }
        sleep 0.01
      done
      $remounted || fail "read-only: cannot remount"
      reason="Read-only file system" ;;
    removed) rm -rf disk/out.partial; reason="No such file or directory" ;;
  esac
  status=0
  wait "$pid" || status=$?
  [ "$case" != read-only ] || umount -l disk/out.incomplete disk/out.partial 2>/dev/null
  [ "$status" -eq 1 ] || fail "$case: exit $status, expected 1"
  grep -q "spatula: error (rank 0): .*'.*disk/out.partial/[^']*'.*$reason" "$case.log" ||
    { fail "$case: the error does not name the file and '$reason':"; tail -n 5 "$case.log"; }
  no_crash "$case.log" "$case"
  [ ! -e disk/out ] || fail "$case: a complete-looking disk/out"
  [ ! -e disk/out.lock ] || fail "$case: the lock file is left"
  if [ "$case" = full ]; then
    whole_rows disk/out.incomplete/curve.csv "$case"
    [ "$(wc -l < disk/out.incomplete/curve.csv)" -ge 4 ] || fail "$case: the curve's rows up to the failure are lost"
  fi
  passed "$case: exit $status, $(grep -o "spatula: error (rank 0): .*" "$case.log" | head -c 200)"
done

[ "$failures" -eq 0 ] && echo "PASS" || echo "$failures failure(s)"
[ "$failures" -eq 0 ]
