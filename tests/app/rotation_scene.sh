# Sourced by the app tests: enter_scratch_directory makes a temporary working directory ($work, removed when the
# script exits) and enters it; rotation_scene <directory> <final theta_y> [<extra Adhesion parameters> [<extra Loading
# parameters> [<extra Output parameters>]]] prints a coarse frictionless rotation scene (steps of at most 2 deg, smallest 0.01, no mesh output);
# lift_scene <directory> <law> <restart file> <theta_y> <final lift> <lift step> [<extra Adhesion parameters> [<extra
# Loading parameters> [<extra Output parameters>]]] prints a lift from a rotation's checkpoint at theta_y, by the final
# lift from there in steps of the lift step (no mesh output). check_counts starts a test's tally: fail <what> counts a
# failure, passed <what> prints "ok" for a case that added none; wait_for_step <log> <step> waits (at most 120 s) for
# that converged step's progress line.
rotation_scene() {
  cat <<XML
<ParameterList>
  <ParameterList name="Adhesion"><Parameter name="law" type="string" value="frictionless"/>
    ${3:-}
  </ParameterList>
  <ParameterList name="Loading">
    <Parameter name="type" type="string" value="rotation"/>
    <Parameter name="theta_y" type="double" value="$2"/>
    ${4:-}
    <ParameterList name="Rotation Steps"><Parameter name="maximum" type="double" value="2"/>
      <Parameter name="minimum" type="double" value="0.01"/></ParameterList>
  </ParameterList>
  <ParameterList name="Output"><Parameter name="directory" type="string" value="$1"/>
    <Parameter name="write mesh" type="bool" value="false"/>
    ${5:-}
  </ParameterList>
</ParameterList>
XML
}

lift_scene() {
  cat <<XML
<ParameterList>
  <ParameterList name="Adhesion"><Parameter name="law" type="string" value="$2"/>
    ${7:-}
  </ParameterList>
  <ParameterList name="Loading">
    <Parameter name="type" type="string" value="lift"/>
    <Parameter name="theta_y" type="double" value="$4"/>
    <Parameter name="restart file" type="string" value="$3"/>
    <Parameter name="restart theta_y" type="double" value="$4"/>
    <Parameter name="final lift" type="double" value="$5"/>
    <Parameter name="final lift relative" type="bool" value="true"/>
    ${8:-}
    <ParameterList name="Lift Steps"><Parameter name="initial" type="double" value="$6"/>
      <Parameter name="maximum" type="double" value="$6"/></ParameterList>
  </ParameterList>
  <ParameterList name="Output"><Parameter name="directory" type="string" value="$1"/>
    <Parameter name="write mesh" type="bool" value="false"/>
    ${9:-}
  </ParameterList>
</ParameterList>
XML
}

enter_scratch_directory() {
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  cd "$work" || exit 1
}

# Filters a scene on stdin to Newton's absolute tolerance 1e-9 (for the tests that compare two runs with each other:
# at the default 1e-6 runs agree to about 3e-5 of M_y, since the refactor rule decides from measured times).
tight_newton() {
  sed 's#<ParameterList name="Output">#<ParameterList name="Nonlinear Solver"><Parameter name="absolute tolerance" type="double" value="1e-9"/></ParameterList>\n  <ParameterList name="Output">#'
}

check_counts() {
  failures=0
  checked=0
}
fail() { echo "FAIL $*"; failures=$((failures + 1)); }
passed() { [ "$failures" -eq "$checked" ] && echo "ok   $*"; checked=$failures; }
wait_for_step() {
  for _ in $(seq 2400); do grep -q "^step \+$2 " "$1" 2>/dev/null && return 0; sleep 0.05; done
  return 1
}
