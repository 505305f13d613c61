#!/usr/bin/env bash
# The same scene, build and rank count give the same result on a quiet and a busy machine: the coarse pull-off
# (xml/pull-off-coarse.xml, default solver settings) run alone on one core and again beside a busy loop pinned to
# that core gives the identical curve.csv in every column but the wall time, and the same solver counts.
# usage: busy_machine.sh <spatula> <source directory>
set -u
app=$1
source_directory=$2
here=$(cd "$(dirname "$0")" && pwd)
source "$here/rotation_scene.sh"
enter_scratch_directory
export OMPI_MCA_btl=self OMPI_MCA_pml=ob1
command -v taskset > /dev/null || { echo "SKIP: no taskset"; exit 77; }
core=$(taskset -cp $$ | sed 's/.*: //; s/[,-].*//')   # the first core this test may use
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }
without_wall_time() {   # curve.csv without its wall_s column
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "wall_s") skip = i }
           { line = ""; for (i = 1; i <= NF; ++i) if (i != skip) line = line (line == "" ? "" : ",") $i; print line }' "$1"
}
for run in quiet busy; do
  sed -e "s/value=\"pull-off-coarse\"/value=\"$run\"/" "$source_directory/xml/pull-off-coarse.xml" > "$run.xml"
done
taskset -c "$core" "$app" quiet.xml > quiet.log 2>&1 || fail "the run alone"
taskset -c "$core" sh -c 'while :; do :; done' &
busy_loop=$!
taskset -c "$core" "$app" busy.xml > busy.log 2>&1 || fail "the run beside the busy loop"
kill "$busy_loop"
if ! cmp -s <(without_wall_time quiet/curve.csv) <(without_wall_time busy/curve.csv); then
  fail "the curves differ:"
  diff <(without_wall_time quiet/curve.csv) <(without_wall_time busy/curve.csv) | head -n 6
fi
solver_line() { grep "^solver:" "$1" | sed 's/([^)]* s)//g'; }   # the counts, not the seconds
[ "$(solver_line quiet.log)" = "$(solver_line busy.log)" ] ||
  fail "the solver counts differ: $(solver_line quiet.log) | $(solver_line busy.log)"
wall() { tail -n 1 "$1/curve.csv" | awk -F, 'NR == 1 { print $0 }' | cut -d, -f23; }
rows=$(($(wc -l < quiet/curve.csv) - 1))
[ "$rows" -ge 20 ] || fail "only $rows rows"
[ "$failures" -eq 0 ] && echo "PASS: $rows identical rows; wall time alone $(wall quiet) s, beside a busy loop $(wall busy) s"
[ "$failures" -eq 0 ]
