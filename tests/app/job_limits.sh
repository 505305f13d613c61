#!/usr/bin/env bash
# The limits a shell, a batch system or a container puts on a job. Before the run: an address-space limit (ulimit -v)
# too small for the coarse and the medium scene, a memory control group too small for the medium one, a file-size
# limit below the largest file the run writes or below what MPI needs to start, and too few open files are each
# refused with exit 2, naming the limit, and nothing is written. During the run: a file-size limit lowered under the
# fields file ends the run with exit 1 and "File too large" (never killed by SIGXFSZ); an address-space limit lowered
# under what the run maps ends it with exit 1 and "out of memory", the curve and a checkpoint kept (never a shift
# that grows without bound); a closed standard output (| head) does not kill it. The cgroup case needs a writable
# memory controller (root): skipped with a message otherwise.
# usage: job_limits.sh <spatula>
set -u
app=$1
here=$(cd "$(dirname "$0")" && pwd)
source "$here/rotation_scene.sh"
enter_scratch_directory
export OPENBLAS_NUM_THREADS=1 OMPI_MCA_btl=self OMPI_MCA_pml=ob1
check_counts
no_crash() {   # log, case
  ! grep -qE "terminate called|Segmentation fault|core dumped|Signal:|Aborted|PMIX ERROR|ORTE_ERROR" "$1" ||
    { fail "$2: crash text"; cat "$1"; }
}
refused() {   # case, log, status, expected text: exit 2, the text, nothing written
  [ "$3" -eq 2 ] || fail "$1: exit $3, expected 2"
  grep -q "spatula: input error: .*$4" "$2" || { fail "$1: the refusal does not say '$4':"; tail -n 3 "$2"; }
  [ -z "$(ls -d out* 2>/dev/null)" ] || fail "$1: a refused run wrote $(ls -d out*)"
  no_crash "$2" "$1"
}
medium() { rotation_scene out "$1" | sed 's#<ParameterList name="Output">#<ParameterList name="Mesh"><Parameter name="level" type="string" value="medium"/></ParameterList>\n  &#'; }

# 1. Memory limits before the run (each took minutes or forever before it was checked: a BLAS allocation retried
#    without end, or a memory failure reported as an indefinite tangent after 500 shifts).
rotation_scene out 40 > coarse.xml
medium 10 > medium.xml
status=0; (ulimit -v 600000; exec timeout -k 5 60 "$app" coarse.xml) > as-coarse.log 2>&1 || status=$?
refused "coarse, ulimit -v 600000" as-coarse.log "$status" "address-space limit (ulimit -v, RLIMIT_AS).*Nothing is left for any mesh"
passed "1a: $(grep -o "needs about .* available ([^)]*)" as-coarse.log | head -c 160)"
status=0; (ulimit -v 900000; exec timeout -k 5 60 "$app" medium.xml) > as-medium.log 2>&1 || status=$?
refused "medium, ulimit -v 900000" as-medium.log "$status" "needs about 0.20 GB .* available (the address-space limit"
passed "1b: $(grep -o "needs about .* available ([^)]*)" as-medium.log | head -c 160)"
status=0; (ulimit -d 300000; exec timeout -k 5 60 "$app" medium.xml) > data.log 2>&1 || status=$?
refused "medium, ulimit -d 300000" data.log "$status" "data-segment limit (ulimit -d, RLIMIT_DATA)"
passed "1c: $(grep -o "available ([^)]*)" data.log | head -c 160)"

# 2. A memory control group (what Slurm and containers set), cgroup v2 or v1.
group=""
for root in /sys/fs/cgroup /sys/fs/cgroup/unified /sys/fs/cgroup/memory; do
  if [ -f "$root/cgroup.controllers" ] && grep -qw memory "$root/cgroup.controllers"; then
    echo +memory > "$root/cgroup.subtree_control" 2>/dev/null
    mkdir "$root/spatula-test-$$" 2>/dev/null && [ -f "$root/spatula-test-$$/memory.max" ] &&
      { group="$root/spatula-test-$$"; echo 150M > "$group/memory.max"; break; }
    rmdir "$root/spatula-test-$$" 2>/dev/null
  elif [ -f "$root/memory.limit_in_bytes" ] && mkdir "$root/spatula-test-$$" 2>/dev/null; then
    group="$root/spatula-test-$$"; echo 150M > "$group/memory.limit_in_bytes"; break
  fi
done
if [ -n "$group" ]; then
  status=0
  sh -c 'echo $$ > "$1/cgroup.procs" 2>/dev/null || exit 77; exec timeout -k 5 60 "$2" medium.xml' sh "$group" "$app" \
    > cgroup.log 2>&1 || status=$?
  rmdir "$group" 2>/dev/null
  if [ "$status" -eq 77 ]; then
    echo "skip 2: cannot move a process into the control group $group"
  else
    refused "medium in a 150 MB control group" cgroup.log "$status" "the memory limit of the control group $group (0.157 GB"
    passed "2: $(grep -o "available ([^)]*)" cgroup.log | head -c 200)"
  fi
else
  echo "skip 2: no writable memory control group here (needs root)"
fi

# 3. File-size and open-file limits before the run.
rotation_scene out 90 "" "" '<Parameter name="field interval" type="int" value="1"/>' |
  sed 's#<Parameter name="write mesh" type="bool" value="false"/>##' > fields.xml
status=0; (ulimit -f 9000; exec "$app" fields.xml) > fsize.log 2>&1 || status=$?
refused "ulimit -f 9000" fsize.log "$status" "a file of up to about .* MB (mesh.h5), above the file-size limit"
status=0; (ulimit -f 100; exec "$app" fields.xml) > fsize-mpi.log 2>&1 || status=$?
refused "ulimit -f 100" fsize-mpi.log "$status" "file-size limit (ulimit -f, RLIMIT_FSIZE) is 100 kB, but MPI needs"
status=0; (ulimit -n 20; exec "$app" fields.xml) > files.log 2>&1 || status=$?
refused "ulimit -n 20" files.log "$status" "open-files limit (ulimit -n, RLIMIT_NOFILE) is 20"
passed "3: file size and open files refused before the run"

# 4. Limits lowered while the run goes (prlimit): a refused write and a failed allocation end it cleanly.
rotation_scene out 60 > no-fields.xml   # (the memory case writes no fields: the failing allocation is the solver's)
for case in file-size memory; do
  rm -rf out out.*
  scene=fields.xml
  [ "$case" = memory ] && scene=no-fields.xml
  "$app" "$scene" > "$case.log" 2>&1 &
  pid=$!
  wait_for_step "$case.log" 3 || fail "$case: the run did not start"
  if [ "$case" = file-size ]; then
    prlimit --pid "$pid" --fsize=$(($(stat -c %s out.partial/mesh.h5) + 1000)); reason="File too large"
  else
    prlimit --pid "$pid" --as=$((($(awk '/^VmSize/ { print $2 }' "/proc/$pid/status") + 2000) * 1024))
    reason="out of memory: "
  fi
  status=0
  wait "$pid" || status=$?
  [ "$status" -eq 1 ] || fail "$case: exit $status, expected 1 (not a kill by a signal)"
  grep -q "spatula: .*$reason" "$case.log" || { fail "$case: the log does not say '$reason':"; tail -n 3 "$case.log"; }
  ! grep -q "indefinite tangent" "$case.log" || fail "$case: an allocation failure reported as an indefinite tangent"
  [ -d out.incomplete ] && [ ! -e out ] && [ ! -e out.partial ] || fail "$case: not left as out.incomplete"
  [ "$(wc -l < out.incomplete/curve.csv)" -ge 4 ] || fail "$case: the curve up to the failure is lost"
  awk -F, 'NR == 1 { n = NF } NF != n { bad = 1 } END { exit bad }' out.incomplete/curve.csv || fail "$case: a cut row"
  [ "$case" = file-size ] || grep -q "out of memory" out.incomplete/FAILURE.txt || fail "$case: FAILURE.txt does not say why"
  no_crash "$case.log" "$case"
  passed "4 $case: exit $status, $(grep -o "spatula: .*$reason.*" "$case.log" | head -n 1 | head -c 170)"
done

# 5. A closed standard output (spatula ... | head) does not kill the run: it completes.
rm -rf out out.*
rotation_scene out 10 > short.xml
"$app" short.xml | head -n 1 > /dev/null
status=${PIPESTATUS[0]}
[ "$status" -eq 0 ] && [ -f out/curve.csv ] || fail "| head -n 1: exit $status (141: killed by SIGPIPE), $(ls -d out* 2>/dev/null)"
passed "5: | head -n 1: exit $status, out/ complete"

[ "$failures" -eq 0 ] && echo "PASS" || echo "$failures failure(s)"
[ "$failures" -eq 0 ]
