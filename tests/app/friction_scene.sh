#!/usr/bin/env bash
# The adhesive friction law in the app, on the coarse adhesive rotation: with the friction coefficient 0 it follows
# the frictionless law (M_y and Pi_sa to 1e-6 at Newton's tolerance 1e-9); with mu = 0.3 the pad's sliding shows
# (another moment, energy dissipated by sliding, the energy balance held, a field of it where the pad slid whose
# integral is the curve's dissipation); and a friction run stopped by SIGTERM and
# restarted from its last state (the contact points' histories stored with it) starts from the stopped state exactly
# and ends where the uninterrupted run ends (to 1e-4: with friction the state depends a little on the steps). A
# frictionless checkpoint cannot restart a friction scene (no history): an input error naming the key; with
# 'Adhesion/stiction anchors' = 'restart state' it can, the friction law starting there unstrained; a state of such a
# run goes on only with its own anchors (--resume) or new ones, never with undeformed ones. The variational
# update follows the same rotation within 1 % with LDL^T factors.
# usage: friction_scene.sh <spatula> <source dir>
set -u
app=$1
source_dir=$2
source "$source_dir/tests/app/rotation_scene.sh"
enter_scratch_directory
export OPENBLAS_NUM_THREADS=1
check_counts
friction() {   # <directory> <final theta_y> <coefficient> [extra Loading parameters]: the rotation with friction
  rotation_scene "$1" "$2" "<ParameterList name=\"Friction\"><Parameter name=\"coefficient\" type=\"double\" value=\"$3\"/></ParameterList>" "${4:-}" |
    sed 's#value="frictionless"#value="adhesive friction"#' | tight_newton
}
rotation_scene frictionless 10 | tight_newton > frictionless.xml
friction none 10 0 > none.xml
friction sliding 10 0.3 | sed 's#name="write mesh" type="bool" value="false"#name="write mesh" type="bool" value="true"#' > sliding.xml
for name in frictionless none sliding; do
  "$app" $name.xml > $name.log 2>&1 || { fail "the $name rotation"; tail -5 $name.log; }
done
/usr/bin/python3 - <<'PY' || fail "friction against frictionless"
import csv
rows = {name: list(csv.DictReader(open(f'{name}/curve.csv'))) for name in ('frictionless', 'none', 'sliding')}
assert abs(float(rows['none'][-1]['theta_y_deg']) - 10) < 1e-9
# (LU factors instead of LDL^T change Newton's iteration counts, so the step sizes may differ: the states at the
# same inclination are compared, the final one always.)
common = 0
for a in rows['frictionless']:
    for b in rows['none']:
        if abs(float(a['theta_y_deg']) - float(b['theta_y_deg'])) < 1e-9:
            common += 1
            for key in ('M_y_nNnm', 'Pi_sa_1e-18J'):
                x, y = float(a[key]), float(b[key])
                assert abs(x - y) <= 1e-6 * max(1.0, abs(x)), ('mu = 0', a['theta_y_deg'], key, x, y)
assert common >= 3, common
last, free = rows['sliding'][-1], rows['frictionless'][-1]
moment, moment_free = float(last['M_y_nNnm']), float(free['M_y_nNnm'])
dissipated = float(last['dissipated_per_Pi_c0'])
assert abs(moment / moment_free - 1) > 1e-4, (moment, moment_free)
assert dissipated > 0, dissipated
assert max(float(r['balance_error_per_Pi_c0']) for r in rows['sliding']) < 1e-3
print(f"mu = 0 follows the frictionless rotation over {len(rows['none'])} states; mu = 0.3: M_y {moment:.4f} against "
      f"{moment_free:.4f} nN nm at 10 deg, dissipated {dissipated:.3e} Pi_c0")
PY
passed "friction coefficient 0 and 0.3"

# Where the pad slid: the field states carry the energy dissipated per unit area on the contact faces' elements
# (zero elsewhere, never negative), whose integral over the contact surface is the curve's dissipation (no jumps
# here: all of it sliding) at the last state.
/usr/bin/python3 - <<'PY' || fail "the dissipation field"
import csv
import h5py
import numpy
with h5py.File('sliding/mesh.h5', 'r') as f:
    X, quads, hexes = f['mesh/coordinates'][:], f['mesh/contact_quadrilaterals'][:], f['mesh/hexahedra'][:]
    last = sorted(f['states'].keys())[-1]
    field = f[f'states/{last}/dissipated_by_friction'][:]
elements = [next(e for e, h in enumerate(hexes) if set(q) <= set(h)) for q in quads]
area = [0.5 * numpy.linalg.norm(numpy.cross(X[q[2]] - X[q[0]], X[q[3]] - X[q[1]])) for q in quads]
others = numpy.delete(field, elements)
assert field.min() >= 0 and not others.any(), (field.min(), abs(others).max())
row = list(csv.DictReader(open('sliding/curve.csv')))[-1]
pi_c0 = float(row['Pi_ext_1e-18J']) / float(row['Pi_ext_per_Pi_c0'])
integral = 2 * sum(field[e] * a for e, a in zip(elements, area))   # the half model's faces, the full spatula's curve
curve = float(row['dissipated_per_Pi_c0']) * pi_c0
assert row['after_jump'] == '0' and abs(integral / curve - 1) < 1e-6, (integral, curve)
print(f'dissipation field: {integral:.6f} nN nm over {numpy.count_nonzero(field)} elements, curve {curve:.6f}')
PY
passed "the dissipation field"

# The variational update: the same rotation with a symmetric tangent (LDL^T: the negative pivots are counted), within
# 1 % of the return mapping's moment (the two differ by tau'(g) times each step's slip in the normal traction).
friction variational 10 0.3 | sed 's#<ParameterList name="Friction">#&<Parameter name="update" type="string" value="variational"/>#' > variational.xml
"$app" variational.xml > variational.log 2>&1 || { fail "the variational rotation"; tail -5 variational.log; }
/usr/bin/python3 - <<'PY' || fail "the variational update against the return mapping"
import csv
variational, mapping = (list(csv.DictReader(open(f'{name}/curve.csv'))) for name in ('variational', 'sliding'))
assert abs(float(variational[-1]['theta_y_deg']) - 10) < 1e-9
# (a state after a jump carries no count: the descent's factors are not the Newton tangent's)
stepped = lambda rows: [r for r in rows[1:] if r['after_jump'] == '0']
assert all(int(r['negative_pivots']) >= 0 for r in stepped(variational)), 'no inertia from LDL^T'
assert all(int(r['negative_pivots']) == -1 for r in stepped(mapping)), 'the return mapping is factored LU'
a, b = float(mapping[-1]['M_y_nNnm']), float(variational[-1]['M_y_nNnm'])
assert abs(b / a - 1) < 1e-2, (a, b)
print(f"variational update: M_y {b:.4f} nN nm at 10 deg, return mapping {a:.4f} ({100 * (b / a - 1):+.3f} %)")
PY
passed "the variational update"

friction stopped 10 0.3 > stopped.xml
"$app" stopped.xml > stopped.log 2>&1 &
pid=$!
wait_for_step stopped.log 3 || fail "the stopped run did not start"
kill -TERM "$pid"
wait "$pid"
[ -s stopped.incomplete/checkpoints.h5 ] || fail "no checkpoint from the stopped run"
friction resumed 10 0.3 "<Parameter name=\"restart file\" type=\"string\" value=\"stopped.incomplete/checkpoints.h5\"/>
  <Parameter name=\"restart from\" type=\"string\" value=\"last state\"/>" > resumed.xml
"$app" resumed.xml > resumed.log 2>&1 || { fail "the restarted friction run"; tail -5 resumed.log; }
/usr/bin/python3 - <<'PY' || fail "the restarted friction run ends elsewhere"
import csv
stopped, resumed, uninterrupted = (list(csv.DictReader(open(f'{name}/curve.csv')))
                                   for name in ('stopped.incomplete', 'resumed', 'sliding'))
# The restart state measured again from the stored histories is the stopped run's last state: its moment (the
# tangential tractions hold the pad) and its stored energy (the friction springs') to the last digits.
for key in ('theta_y_deg', 'M_y_nNnm', 'Pi_sa_1e-18J', 'dissipated_per_Pi_c0'):
    x, y = float(stopped[-1][key]), float(resumed[0][key])
    assert abs(x - y) <= 1e-9 * max(1e-6, abs(x)), ('restart state', key, x, y)
# From there its steps differ from the uninterrupted run's (the predictor starts afresh), and with friction the state
# depends on the steps a little (the return mapping over another increment): the same final state to 1e-4.
for key in ('theta_y_deg', 'M_y_nNnm', 'Pi_sa_1e-18J'):
    x, y = float(uninterrupted[-1][key]), float(resumed[-1][key])
    assert abs(x - y) <= 1e-4 * max(1.0, abs(x)), (key, x, y)
print(f"restart state as stopped (M_y {float(resumed[0]['M_y_nNnm']):.6f} nN nm); at 10 deg M_y "
      f"{float(resumed[-1]['M_y_nNnm']):.4f}, uninterrupted {float(uninterrupted[-1]['M_y_nNnm']):.4f} nN nm")
PY
passed "a friction run restarted from its last state"

rotation_scene checkpointed 8 "" "<Parameter name=\"checkpoints at theta_y\" type=\"string\" value=\"8\"/>" > checkpointed.xml
"$app" checkpointed.xml > checkpointed.log 2>&1 || fail "the frictionless rotation with a checkpoint"
friction from-frictionless 10 0.3 "<Parameter name=\"restart file\" type=\"string\" value=\"checkpointed/checkpoints.h5\"/>
  <Parameter name=\"restart theta_y\" type=\"double\" value=\"8\"/>" > from-frictionless.xml
status=0
"$app" from-frictionless.xml > from-frictionless.log 2> from-frictionless.err || status=$?
[ "$status" -eq 2 ] && grep -qF "holds no contact history for 'Adhesion/law' = 'adhesive friction'" from-frictionless.err ||
  { fail "a frictionless checkpoint restarting a friction scene: exit $status"; cat from-frictionless.err; }
passed "a frictionless checkpoint refused"

# With the anchors at the restart state the friction law starts there unstrained: the frictionless state is its
# equilibrium too (the same moment and stored energy), and the rotation goes on from it with friction.
friction relaxed 10 0.3 "<Parameter name=\"restart file\" type=\"string\" value=\"checkpointed/checkpoints.h5\"/>
  <Parameter name=\"restart theta_y\" type=\"double\" value=\"8\"/>" |
  sed 's#<ParameterList name="Friction">#<Parameter name="stiction anchors" type="string" value="restart state"/>&#' > relaxed.xml
"$app" relaxed.xml > relaxed.log 2>&1 || { fail "a friction rotation from a frictionless state"; tail -5 relaxed.log; }
/usr/bin/python3 - <<'PY' || fail "the relaxed start"
import csv
frictionless, relaxed = (list(csv.DictReader(open(f'{name}/curve.csv'))) for name in ('checkpointed', 'relaxed'))
for key in ('theta_y_deg', 'M_y_nNnm', 'Pi_sa_1e-18J'):
    x, y = float(frictionless[-1][key]), float(relaxed[0][key])
    assert abs(x - y) <= 1e-9 * max(1e-6, abs(x)), ('restart state', key, x, y)
assert abs(float(relaxed[-1]['theta_y_deg']) - 10) < 1e-9 and float(relaxed[-1]['dissipated_per_Pi_c0']) >= 0
print(f"from the frictionless state at 8 deg (M_y {float(relaxed[0]['M_y_nNnm']):.4f} nN nm) to 10 deg with friction: "
      f"M_y {float(relaxed[-1]['M_y_nNnm']):.4f} nN nm")
PY
passed "a friction run from a frictionless state, anchored there"

# A run anchored at its restart state measures its tangential tractions from those anchors (stored with its
# checkpoints): a restart from its last state with the anchors undeformed is refused by name; --resume goes on with
# them, also with another 'Loading/Jump/maximum iterations' (a change of the scene it accepts), and keeps the stopped
# rows.
from_8="<Parameter name=\"restart file\" type=\"string\" value=\"checkpointed/checkpoints.h5\"/>
  <Parameter name=\"restart theta_y\" type=\"double\" value=\"8\"/>"
anchor='s#<ParameterList name="Friction">#<Parameter name="stiction anchors" type="string" value="restart state"/>&#'
friction anchored 16 0.3 "$from_8" | sed "$anchor" > anchored.xml
"$app" anchored.xml > anchored.log 2>&1 &
pid=$!
for _ in $(seq 2400); do [ "$(grep -c '^step ' anchored.log)" -ge 2 ] && break; sleep 0.05; done
kill -TERM "$pid"
wait "$pid"
[ -s anchored.incomplete/checkpoints.h5 ] || fail "no checkpoint from the anchored run"
cp anchored.incomplete/curve.csv anchored-stopped.csv   # (--resume takes the directory over)
friction unanchored 16 0.3 "<Parameter name=\"restart file\" type=\"string\" value=\"anchored.incomplete/checkpoints.h5\"/>
  <Parameter name=\"restart from\" type=\"string\" value=\"last state\"/>" > unanchored.xml
status=0
"$app" unanchored.xml > unanchored.log 2> unanchored.err || status=$?
[ "$status" -eq 2 ] && grep -qF "this scene has 'Adhesion/stiction anchors' = 'undeformed'" unanchored.err ||
  { fail "a restart from an anchored run's state with undeformed anchors: exit $status"; cat unanchored.err; }
passed "a restart with other anchors refused"
friction anchored 16 0.3 "$from_8
  <ParameterList name=\"Jump\"><Parameter name=\"maximum iterations\" type=\"int\" value=\"500\"/></ParameterList>" |
  sed "$anchor" > anchored-more.xml
"$app" anchored-more.xml --resume > anchored-more.log 2>&1 ||
  { fail "resuming the anchored run"; tail -5 anchored-more.log; }
/usr/bin/python3 - <<'PY' || fail "the resumed anchored run"
import csv
stopped, resumed = (list(csv.DictReader(open(name))) for name in ('anchored-stopped.csv', 'anchored/curve.csv'))
assert len(resumed) > len(stopped) >= 2, (len(stopped), len(resumed))
for a, b in zip(stopped, resumed):
    for key in ('theta_y_deg', 'M_y_nNnm', 'dissipated_per_Pi_c0'):
        assert abs(float(a[key]) - float(b[key])) <= 1e-9 * max(1e-6, abs(float(a[key]))), (key, a[key], b[key])
assert abs(float(resumed[-1]['theta_y_deg']) - 16) < 1e-9
print(f"resumed with its anchors from {float(stopped[-1]['theta_y_deg']):.2f} to 16 deg: "
      f"M_y {float(resumed[-1]['M_y_nNnm']):.4f} nN nm")
PY
passed "an anchored friction run resumed with another jump limit"
[ "$failures" -eq 0 ]
