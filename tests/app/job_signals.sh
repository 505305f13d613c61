#!/usr/bin/env bash
# Every signal that ends or warns a job stops the run at its next converged state, like SIGTERM and SIGINT
# (interrupted_run.sh): SIGHUP (a terminal that closes), SIGQUIT, SIGUSR1 and SIGUSR2 (a batch system's warning
# before its time limit) and SIGXCPU (the CPU-time limit, ulimit -t) each end it with exit 128 + the signal, FAILURE.txt
# naming the signal, the curve and a 'last state' checkpoint in <directory>.incomplete (a run under nohup goes on
# after SIGHUP). Where no converged state comes
# within 'Job/stop grace' of the signal, the watchdog ends the process itself (exit 128 + the signal), FAILURE.txt
# says so, and --resume goes on from the last checkpoint to the end. The program sets its BLAS threads itself (one per
# rank, the parameter, or OPENBLAS_NUM_THREADS) and says so.
# usage: job_signals.sh <spatula>
set -u
app=$1
here=$(cd "$(dirname "$0")" && pwd)
source "$here/rotation_scene.sh"
enter_scratch_directory
export OMPI_MCA_btl=self OMPI_MCA_pml=ob1
unset OPENBLAS_NUM_THREADS
check_counts
stopped_cleanly() {   # case, directory, status, expected exit, expected text in FAILURE.txt
  [ "$3" -eq "$4" ] || fail "$1: exit $3, expected $4"
  [ ! -e "$2" ] && [ ! -e "$2.partial" ] || fail "$1: a directory that looks complete or staging left"
  grep -q "$5" "$2.incomplete/FAILURE.txt" 2>/dev/null || fail "$1: FAILURE.txt does not say '$5'"
  [ -s "$2.incomplete/checkpoints.h5" ] && [ "$(wc -l < "$2.incomplete/curve.csv")" -ge 4 ] ||
    fail "$1: no checkpoint or curve kept"
}

# 1. The signals a terminal, a user or a batch system sends to end or warn a job.
for signal in HUP QUIT USR1 USR2; do
  rotation_scene "stopped-$signal" 40 > "$signal.xml"
  "$app" "$signal.xml" > "$signal.log" 2>&1 &
  pid=$!
  wait_for_step "$signal.log" 3 || fail "SIG$signal: the run did not start"
  kill -"$signal" "$pid"
  status=0
  wait "$pid" || status=$?
  stopped_cleanly "SIG$signal" "stopped-$signal" "$status" $((128 + $(kill -l "$signal"))) "interrupted by SIG$signal"
  passed "SIG$signal: exit $status, $(grep -o "interrupted by SIG$signal.*" "$signal.log" | head -n 1)"
done

# A run started with nohup goes on when its terminal closes.
rotation_scene kept 10 > kept.xml
nohup "$app" kept.xml > kept.log 2>&1 &
pid=$!
wait_for_step kept.log 3 || fail "nohup: the run did not start"
kill -HUP "$pid"
status=0
wait "$pid" || status=$?
[ "$status" -eq 0 ] && [ -f kept/curve.csv ] || fail "nohup: SIGHUP stopped the run (exit $status)"
passed "nohup: SIGHUP ignored, exit $status"

# 2. The CPU-time limit: the kernel sends SIGXCPU at the soft limit (and again every second until the hard one).
rotation_scene cpu 90 > cpu.xml
status=0
(ulimit -S -t 2; exec "$app" cpu.xml) > cpu.log 2>&1 || status=$?
stopped_cleanly "ulimit -t 2" cpu "$status" $((128 + $(kill -l XCPU))) "interrupted by SIGXCPU (the CPU-time limit"
passed "ulimit -t 2: exit $status, $(grep -o "interrupted by SIGXCPU.*" cpu.log | head -n 1)"

# 3. The watchdog: with a grace shorter than any step, no converged state comes in time.
rotation_scene watched 20 "" "" '<Parameter name="checkpoint interval" type="double" value="0.0001"/>' |
  sed '$ s#^</ParameterList>#  <ParameterList name="Job"><Parameter name="stop grace" type="double" value="0.000001"/></ParameterList>\n&#' > watched.xml
"$app" watched.xml > watched.log 2>&1 &
pid=$!
wait_for_step watched.log 3 || fail "watchdog: the run did not start"
kill -TERM "$pid"
status=0
wait "$pid" || status=$?
[ "$status" -eq 143 ] || fail "watchdog: exit $status, expected 143"
grep -q "no converged state within 'Job/stop grace' of SIGTERM: the watchdog ends the run now" watched.log ||
  fail "watchdog: the log does not say so"
grep -q "ended by its watchdog" watched.incomplete/FAILURE.txt 2>/dev/null && grep -q "last checkpoint .* is kept" \
  watched.incomplete/FAILURE.txt || fail "watchdog: FAILURE.txt does not say what happened and what is kept"
[ ! -e watched.partial ] && [ ! -e watched ] || fail "watchdog: not left as watched.incomplete"
status=0
"$app" watched.xml --resume > resumed.log 2>&1 || status=$?
[ "$status" -eq 0 ] && grep -q "spatula: resuming the stopped run" resumed.log && [ -f watched/curve.csv ] ||
  { fail "watchdog: --resume did not go on to the end (exit $status)"; tail -n 3 resumed.log; }
awk -F, 'NR > 1 { last = $3 } END { exit !(last > 19.99) }' watched/curve.csv 2>/dev/null ||
  fail "watchdog: the resumed curve does not reach 20 deg"
passed "watchdog: exit 143 within the grace, resumed to 20 deg"

# 4. BLAS threads: one per rank unless the parameter or OPENBLAS_NUM_THREADS says otherwise.
rotation_scene threads 1 > threads.xml
"$app" threads.xml --validate-only > default-threads.log 2>&1
grep -q "threads per rank: BLAS 1 (OpenBLAS, the default, one per rank), Kokkos" default-threads.log ||
  fail "BLAS threads by default: $(grep threads default-threads.log)"
OPENBLAS_NUM_THREADS=2 "$app" threads.xml --validate-only > environment-threads.log 2>&1
grep -q "threads per rank: BLAS 2 (OpenBLAS, OPENBLAS_NUM_THREADS)" environment-threads.log ||
  fail "BLAS threads from the environment: $(grep threads environment-threads.log)"
sed '$ s#^</ParameterList>#  <ParameterList name="Job"><Parameter name="BLAS threads" type="int" value="2"/></ParameterList>\n&#' \
  threads.xml > two.xml
OPENBLAS_NUM_THREADS=1 "$app" two.xml --validate-only > parameter-threads.log 2>&1
grep -q "threads per rank: BLAS 2 (OpenBLAS, 'Job/BLAS threads')" parameter-threads.log ||
  fail "BLAS threads from the parameter: $(grep threads parameter-threads.log)"
passed "BLAS threads: $(grep -o "threads per rank.*" default-threads.log)"

[ "$failures" -eq 0 ] && echo "PASS" || echo "$failures failure(s)"
[ "$failures" -eq 0 ]
