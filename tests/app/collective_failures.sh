#!/usr/bin/env bash
# Under MPI every check that one rank makes (the output directory, the restart file, the memory estimate, the mesh)
# ends every rank together: exit 2 within seconds (no rank left waiting), the message printed once, nothing written.
# usage: collective_failures.sh <spatula> <mpiexec> [mpiexec flags...]
set -u
app=$1
mpiexec=$2
shift 2
flags=("$@")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
failures=0
case_of() {   # name, expected message, sublists
  printf '<ParameterList>%s</ParameterList>\n' "$3" > "$work/$1.xml"
  local status=0 started=$SECONDS
  timeout 60 "$mpiexec" "${flags[@]}" -np 2 "$app" "$work/$1.xml" > stdout.txt 2> stderr.txt || status=$?
  local seconds=$((SECONDS - started)) count
  count=$(grep -cF -- "$2" stderr.txt)
  if [ "$status" -eq 124 ]; then echo "FAIL $1: hung (killed after 60 s)"; failures=$((failures + 1))
  elif [ "$status" -ne 2 ]; then echo "FAIL $1: exit $status, expected 2"; cat stderr.txt; failures=$((failures + 1))
  elif [ "$count" -ne 1 ]; then echo "FAIL $1: '$2' printed $count times"; cat stderr.txt; failures=$((failures + 1))
  elif [ -n "$(ls -A | grep -v -e '^stdout.txt$' -e '^stderr.txt$' -e '\.xml$')" ]; then
    echo "FAIL $1: wrote files:"; ls -A; failures=$((failures + 1))
  else echo "ok   $1 (${seconds} s): $(grep -F -- "$2" stderr.txt | head -c 160)"; fi
}
case_of output_cannot_be_made "nothing can be created in '/proc'" \
  '<ParameterList name="Output"><Parameter name="directory" type="string" value="/proc/spatula-output"/></ParameterList>'
case_of restart_file_missing "parameter 'Loading/restart file' = 'none.h5': no such file" \
  '<ParameterList name="Loading"><Parameter name="type" type="string" value="lift"/><Parameter name="restart file" type="string" value="none.h5"/></ParameterList>'
case_of mesh_beyond_memory "'Mesh/refinement factor' = 16, 'Mesh/layers' = 0) has about" \
  '<ParameterList name="Mesh"><Parameter name="level" type="string" value="fine"/><Parameter name="refinement factor" type="int" value="16"/></ParameterList>'
case_of inverted_mesh "'Geometry/l_p' = 150 is too small" \
  '<ParameterList name="Geometry"><Parameter name="l_p" type="double" value="150"/></ParameterList>'
[ "$failures" -eq 0 ] && echo "every failed check ended both ranks together"
exit "$failures"
