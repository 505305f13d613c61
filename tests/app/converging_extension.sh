#!/usr/bin/env bash
# An attempt at its iteration limit goes on while it converges (Nonlinear Solver/converging extension): the coarse
# rotation's first step needs 4 Newton iterations, converging fast at the end. With 'maximum iterations' = 3 and no
# extension it fails and is cut; with the extension it converges in 4 iterations at the full increment.
# usage: converging_extension.sh <spatula>
set -u
app=$1
here=$(cd "$(dirname "$0")" && pwd)
source "$here/rotation_scene.sh"
enter_scratch_directory
export OPENBLAS_NUM_THREADS=1 OMPI_MCA_btl=self OMPI_MCA_pml=ob1
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }
scene() {   # directory, extension
  rotation_scene "$1" 6 | sed "s#<ParameterList name=\"Output\">#<ParameterList name=\"Nonlinear Solver\"><Parameter name=\"maximum iterations\" type=\"int\" value=\"3\"/><Parameter name=\"converging extension\" type=\"int\" value=\"$2\"/></ParameterList>\n  <ParameterList name=\"Output\">#"
}
first_step() { sed -n 3p "$1/curve.csv" | cut -d, -f3,21; }   # theta_y, Newton iterations of the first step (row 2 is the start)
scene limited 0 > limited.xml
scene extended 8 > extended.xml
"$app" limited.xml > limited.log 2>&1 || fail "the run without extension"
"$app" extended.xml > extended.log 2>&1 || fail "the run with extension"
grep -q "failed (no convergence after 3 iterations" limited.log || fail "without extension the first attempt should fail at 3 iterations"
! grep -q "failed (no convergence" extended.log || fail "with extension an attempt failed: $(grep -m1 'failed (no' extended.log)"
[ "$(first_step extended | cut -d, -f2)" = 4 ] || fail "the first state should take 4 iterations: $(first_step extended)"
awk -F, -v full="$(first_step extended | cut -d, -f1)" -v cut_="$(first_step limited | cut -d, -f1)" \
  'BEGIN { exit !(cut_ < full) }' || fail "without extension the first state should come at a cut increment ($(first_step limited) against $(first_step extended))"
[ "$failures" -eq 0 ] && echo "PASS: first state $(first_step extended) (theta_y, iterations) with the extension, $(first_step limited) without"
[ "$failures" -eq 0 ]
