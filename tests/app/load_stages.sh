#!/usr/bin/env bash
# A load path as data ('Loading/type' = stages, 'Loading/Stages'): the default scene written as one rotate stage and
# the coarse pull-off as a rotate and a lift stage give the same curve.csv as the fixed types (every column but the
# wall time; the stage column keeps the names 'rotation' and 'lift'). A path of three stages (rotate, lift, slide x on
# the stiction law) names its stages in the curve and ends each at its target; interrupted in its last stage and
# resumed, it ends where the uninterrupted run ends. Force stages end at their forces, or at the largest one; a
# stage's stop rule ends it at its force. Bad stage lists, and a restart from a stage the path does not
# have, are refused (exit 2) naming the stage.
# On two ranks, a run stopped inside its second stage and resumed ends where the one-rank uninterrupted run ends.
# usage: load_stages.sh <spatula> <source directory> <mpiexec> [mpiexec flags...]
set -u
app=$1
source_directory=$2
mpiexec=$3
shift 3
flags=("$@")
here=$(cd "$(dirname "$0")" && pwd)
source "$here/rotation_scene.sh"
enter_scratch_directory
check_counts
without_wall_time() { cut -d, -f1-22,24 "$1"; }   # (column 23: wall_s)
stage() {   # name, kind, target, extra parameters
  echo "<ParameterList name=\"$1\"><Parameter name=\"kind\" type=\"string\" value=\"$2\"/><Parameter name=\"target\" type=\"double\" value=\"$3\"/>${4:-}</ParameterList>"
}
# A scene file with its Loading list replaced by type = stages and the given stages, into directory $2.
as_stages() {   # scene, directory, stages...
  local scene=$1 directory=$2
  shift 2
  python3 - "$scene" "$directory" "$*" <<'PY'
import sys, xml.etree.ElementTree as ElementTree
root = ElementTree.parse(sys.argv[1]).getroot()
loading = next(c for c in root if c.get('name') == 'Loading')
root.remove(loading)
stages = ElementTree.fromstring(f'<ParameterList name="Stages">{sys.argv[3]}</ParameterList>')
new = ElementTree.SubElement(root, 'ParameterList', name='Loading')
ElementTree.SubElement(new, 'Parameter', name='type', type='string', value='stages')
new.append(stages)
for output in (c for c in root if c.get('name') == 'Output'):
    for p in output:
        if p.get('name') == 'directory':
            p.set('value', sys.argv[2])
print(ElementTree.tostring(root, encoding='unicode'))
PY
}
set_directory() { sed "s#<Parameter name=\"directory\" type=\"string\" value=\"[^\"]*\"/>#<Parameter name=\"directory\" type=\"string\" value=\"$2\"/>#" "$1"; }

# 1. The fixed types written as stages: the same curves.
set_directory "$source_directory/xml/default.xml" default-type > default-type.xml
as_stages "$source_directory/xml/default.xml" default-stages \
  "$(stage rotation rotate 90 '<ParameterList name="Steps"><Parameter name="maximum" type="double" value="2"/><Parameter name="minimum" type="double" value="0.01"/></ParameterList>')" \
  > default-stages.xml
set_directory "$source_directory/xml/pull-off-coarse.xml" pull-type > pull-type.xml
as_stages "$source_directory/xml/pull-off-coarse.xml" pull-stages "$(stage rotation rotate 25)" "$(stage lift lift 200)" \
  > pull-stages.xml
for scene in default pull; do
  for way in type stages; do
    "$app" "$scene-$way.xml" > "$scene-$way.log" 2>&1 || fail "$scene written as $way: exit $?"
  done
  if cmp -s <(without_wall_time "$scene-type/curve.csv") <(without_wall_time "$scene-stages/curve.csv"); then
    passed "$scene: $(($(wc -l < "$scene-type/curve.csv") - 1)) states, the same curve written either way"
  else
    fail "$scene: the curves differ"
    diff <(without_wall_time "$scene-type/curve.csv") <(without_wall_time "$scene-stages/curve.csv") | head -n 4
  fi
done

# 2. Three stages: rotate to 20 deg (the face free in Z), lift by 5 nm, slide along X by 10 nm (stiction holds the pad).
three_stages() {   # directory
  rotation_scene "$1" 20 | sed 's#value="frictionless"#value="stiction"#' > base.xml
  as_stages base.xml "$1" "$(stage peel rotate 20)" \
    "$(stage pull lift 5 '<Parameter name="relative" type="bool" value="true"/><ParameterList name="Steps"><Parameter name="initial" type="double" value="0.5"/><Parameter name="maximum" type="double" value="0.5"/></ParameterList>')" \
    "$(stage shear 'slide x' 10 '<Parameter name="relative" type="bool" value="true"/>')"
}
three_stages three > three.xml
"$app" three.xml > three.log 2>&1 || fail "three stages: exit $?"
python3 - three/curve.csv <<'PY' || fail "three stages: the curve does not follow the stages"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
stages = [r['stage'] for r in rows]
order = [s for i, s in enumerate(stages) if i == 0 or s != stages[i - 1]]
assert order == ['peel', 'pull', 'shear'], order
last = {s: [r for r in rows if r['stage'] == s][-1] for s in order}
first_pull = next(i for i, r in enumerate(rows) if r['stage'] == 'pull')
start = rows[first_pull - 1]
assert abs(float(last['peel']['theta_y_deg']) - 20) < 1e-9, last['peel']['theta_y_deg']
assert abs(float(last['pull']['u_z_nm']) - float(start['u_z_nm']) - 5) < 1e-6, (last['pull']['u_z_nm'], start['u_z_nm'])
assert abs(float(last['shear']['u_x_nm']) - float(last['pull']['u_x_nm']) - 10) < 1e-6, last['shear']['u_x_nm']
assert abs(float(last['shear']['u_z_nm']) - float(last['pull']['u_z_nm'])) < 1e-6   # u_z held while sliding
print(f"three stages: {len(rows) - 1} states, u_z {float(start['u_z_nm']):.2f} -> {float(last['pull']['u_z_nm']):.2f}, "
      f"u_x -> {float(last['shear']['u_x_nm']):.2f} nm")
PY
passed "three stages named in the curve, each at its target"

# 2b. Force stages (stiction): rotate to 20 deg, pull the face with P_z = 3 nN, push it along X with P_x = 2 nN: each
# ends at its force, the face held in X while pulled and in Z while pushed. Asked for a pull of 1000 nN, the path ends
# at the largest pull the spatula carries (a detachment under load control: exit 0, named in the log).
force_stages() {   # directory, pull target, push stage
  rotation_scene "$1" 20 | sed 's#value="frictionless"#value="stiction"#' > force-base.xml
  as_stages force-base.xml "$1" "$(stage peel rotate 20)" "$(stage pull 'lift force' "$2")" ${3:+"$3"}
}
force_stages forces 3 "$(stage push 'slide x force' 2)" > forces.xml
"$app" forces.xml > forces.log 2>&1 || fail "force stages: exit $?"
python3 - forces/curve.csv <<'PY' || fail "force stages: the forces are not where the stages end"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
pull = [r for r in rows if r['stage'] == 'pull']
push = [r for r in rows if r['stage'] == 'push']
assert pull and push, 'a force stage took no step'
assert abs(float(pull[-1]['P_z_nN']) - 3) < 1e-6, pull[-1]['P_z_nN']
assert abs(float(push[-1]['P_x_nN']) - 2) < 1e-6, push[-1]['P_x_nN']
assert all(float(r['u_x_nm']) == float(pull[0]['u_x_nm']) for r in pull), 'the face moved in X while pulled'
assert all(float(r['u_z_nm']) == float(pull[-1]['u_z_nm']) for r in push), 'the face moved in Z while pushed'
assert float(pull[-1]['u_z_nm']) > float(pull[0]['u_z_nm']), 'the pull did not lift the face'
assert float(push[-1]['u_x_nm']) > float(push[0]['u_x_nm']), 'the push did not move the face along X'
print(f"force stages: P_z 3 nN at u_z {float(pull[-1]['u_z_nm']):.3f} nm, P_x 2 nN at u_x {float(push[-1]['u_x_nm']):.3f} nm")
PY
force_stages limit 1000 > limit.xml
"$app" limit.xml > limit.log 2>&1 || fail "a pull beyond the largest force: exit $?"
grep -q "^detachment: under a prescribed force the end face carries at most [0-9.]* nN (pull)" limit.log ||
  fail "a pull beyond the largest force: no detachment in the log"
python3 - limit/curve.csv <<'PY' || fail "a pull beyond the largest force: the curve does not rise to it"
import csv, sys
pull = [float(r['P_z_nN']) for r in csv.DictReader(open(sys.argv[1])) if r['stage'] == 'pull']
assert pull[-1] == max(pull) and pull[-1] > 5, pull[-3:]
print(f"the largest pull: {pull[-1]:.4f} nN after {len(pull)} force steps")
PY
passed "force stages end at their forces; beyond the largest, detachment under load control"

# 2c. A stop rule: a lift by up to 50 nm that ends once P_z reaches 2 nN, then a rotation to 22 deg.
rotation_scene stopped-by-force 20 > stop-base.xml
as_stages stop-base.xml stopped-by-force "$(stage peel rotate 20)" \
  "$(stage pull lift 50 '<Parameter name="relative" type="bool" value="true"/><Parameter name="stop at force" type="double" value="2"/>')" \
  "$(stage turn rotate 22)" > stop-force.xml
"$app" stop-force.xml > stop-force.log 2>&1 || fail "a stop rule: exit $?"
grep -q "^stage 'pull' ends at its stop force 2 nN" stop-force.log || fail "a stop rule: not named in the log"
python3 - stopped-by-force/curve.csv <<'PY' || fail "a stop rule: the pull did not end where P_z reached 2 nN"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
pull = [r for r in rows if r['stage'] == 'pull']
turn = [r for r in rows if r['stage'] == 'turn']
start = rows[rows.index(pull[0]) - 1]
assert float(pull[-1]['P_z_nN']) >= 2 and all(float(r['P_z_nN']) < 2 for r in pull[:-1]), [r['P_z_nN'] for r in pull]
assert float(pull[-1]['u_z_nm']) < float(start['u_z_nm']) + 50
assert turn and abs(float(turn[-1]['theta_y_deg']) - 22) < 1e-9
print(f"stop rule: the pull ended at P_z {float(pull[-1]['P_z_nN']):.3f} nN after "
      f"{float(pull[-1]['u_z_nm']) - float(start['u_z_nm']):.3f} nm; the next stage ran to 22 deg")
PY
passed "a stage's stop rule ends it at its force, and the path goes on"

# 3. Stopped inside the last stage and resumed: the uninterrupted run's end.
three_stages stopped | sed 's#<Parameter name="directory"#<Parameter name="checkpoint interval" type="double" value="0.0001"/>&#' > stopped.xml
"$app" stopped.xml > stopped.log 2>&1 &
pid=$!
for _ in $(seq 2400); do grep -q "^step \+[0-9]\+ \+shear " stopped.log && break; sleep 0.05; done
kill -TERM "$pid"
status=0
wait "$pid" || status=$?
[ "$status" -eq 143 ] || fail "stopped in the shear stage: exit $status, expected 143"
grep -q "where: .*stage 'shear'" stopped.incomplete/FAILURE.txt 2>/dev/null || fail "FAILURE.txt does not name the stage"
"$app" stopped.xml --resume > resumed.log 2>&1 || fail "the resumed run: exit $?"
python3 - three/curve.csv stopped/curve.csv <<'PY' || fail "the resumed run ends elsewhere"
import csv, sys
a, b = ([r for r in csv.DictReader(open(f))][-1] for f in sys.argv[1:3])
for key in ('u_x_nm', 'u_z_nm', 'M_y_nNnm', 'P_z_nN'):
    assert abs(float(a[key]) - float(b[key])) <= 1e-6 * max(1.0, abs(float(a[key]))), (key, a[key], b[key])
print(f"resumed in 'shear': M_y {float(b['M_y_nNnm']):.6f} against {float(a['M_y_nNnm']):.6f}")
PY
passed "stopped in the shear stage and resumed: the same end"

# 3b. The same on two ranks, stopped inside the second stage ('pull').
three_stages ranks | sed 's#<Parameter name="directory"#<Parameter name="checkpoint interval" type="double" value="0.0001"/>&#' > ranks.xml
"$mpiexec" "${flags[@]}" -np 2 "$app" "$PWD/ranks.xml" > ranks.log 2>&1 &
pid=$!
# (the curve, written by rank 0 row by row: mpiexec's forwarding of the log may lag behind)
for _ in $(seq 2400); do grep -q "^[0-9]\+,pull," ranks.partial/curve.csv 2>/dev/null && break; sleep 0.02; done
pkill -TERM -P "$pid"   # both ranks at once (mpiexec forwards a signal late)
wait "$pid"
grep -q "where: .*stage 'pull'" ranks.incomplete/FAILURE.txt 2>/dev/null ||
  fail "2 ranks: not stopped inside 'pull' ($(grep -o "where: .*" ranks.incomplete/FAILURE.txt 2>/dev/null))"
timeout 300 "$mpiexec" "${flags[@]}" -np 2 "$app" "$PWD/ranks.xml" --resume > ranks-resumed.log 2>&1 ||
  fail "2 ranks: the resumed run: exit $?"
python3 - three/curve.csv ranks/curve.csv <<'PY' || fail "2 ranks: the resumed run ends elsewhere"
import csv, sys
a, b = ([r for r in csv.DictReader(open(f))][-1] for f in sys.argv[1:3])
for key in ('u_x_nm', 'u_z_nm', 'M_y_nNnm', 'P_z_nN'):
    assert abs(float(a[key]) - float(b[key])) <= 1e-6 * max(1.0, abs(float(a[key]))), (key, a[key], b[key])
print(f"2 ranks resumed in 'pull': M_y {float(b['M_y_nNnm']):.6f} against {float(a['M_y_nNnm']):.6f} on one rank")
PY
passed "2 ranks, stopped in the pull stage and resumed: the one-rank end"

# 4. Bad stage lists: exit 2 naming the stage.
bad() {   # case, expected text, stages...
  local case=$1 expected=$2
  shift 2
  rotation_scene bad 10 > bad-base.xml
  as_stages bad-base.xml bad "$@" > bad.xml
  status=0
  "$app" bad.xml --validate-only > "bad-$case.log" 2>&1 || status=$?
  [ "$status" -eq 2 ] && grep -q "input error: .*$expected" "bad-$case.log" ||
    { fail "$case: exit $status, $(tail -n 1 "bad-$case.log")"; }
}
bad unknown-kind "Loading/Stages/twist/kind' = 'twist': allowed kinds are rotate, lift, slide x" "$(stage twist twist 3)"
bad no-target "stage 'Loading/Stages/up' has no 'target'" '<ParameterList name="up"><Parameter name="kind" type="string" value="lift"/></ParameterList>'
bad free-slide-in-rotation "unknown parameter 'Loading/Stages/peel/free slide'" \
  "$(stage peel rotate 10 '<Parameter name="free slide" type="bool" value="true"/>')"
bad free-slide-frictionless "stage 'up' of 'Loading/Stages': 'free slide' = true needs 'Adhesion/law' = 'stiction'" \
  "$(stage up lift 10 '<Parameter name="free slide" type="bool" value="true"/>')"
bad slide-force-frictionless "stage 'push' of 'Loading/Stages': kind 'slide x force' needs 'Adhesion/law' = 'stiction'" \
  "$(stage push 'slide x force' 1)"
bad no-stages "needs at least one stage in 'Loading/Stages'"
bad comma "a stage's name is a column of curve.csv" "$(stage 'a,b' lift 3)"
# A checkpoint that lies in a stage this scene's path does not have (the lift of a stopped two-stage run, restarted
# by a one-stage rotation) is refused before anything is written.
rotation_scene two 10 "" '<Parameter name="type" type="string" value="lift"/><Parameter name="final lift" type="double" value="40"/><Parameter name="final lift relative" type="bool" value="true"/>' \
  '<Parameter name="checkpoint interval" type="double" value="0.0001"/>' | sed 's#<Parameter name="type" type="string" value="rotation"/>##' > two.xml
"$app" two.xml > two.log 2>&1 &
pid=$!
for _ in $(seq 2400); do grep -q "^step \+[0-9]\+ \+lift " two.log && break; sleep 0.05; done
kill -TERM "$pid"
wait "$pid"
rotation_scene one 12 "" '<Parameter name="restart file" type="string" value="two.incomplete/checkpoints.h5"/><Parameter name="restart from" type="string" value="last state"/>' > one.xml
status=0
"$app" one.xml > one.log 2>&1 || status=$?
[ "$status" -eq 2 ] && grep -q "input error: .*checkpoint 'last state' lies in stage 2 of its path, but this scene has 1 stage" one.log &&
  [ ! -e one ] && [ ! -e one.partial ] && [ ! -e one.incomplete ] ||
  fail "a restart from another path's later stage: exit $status, $(tail -n 1 one.log)"
passed "bad stage lists refused by name"

[ "$failures" -eq 0 ] && echo "PASS" || echo "$failures failure(s)"
[ "$failures" -eq 0 ]
