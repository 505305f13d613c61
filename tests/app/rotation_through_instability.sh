#!/usr/bin/env bash
# The coarse spatula (Q1C2 adhesion) rotated from theta_s to 36 deg passes its first instability: the moment drops,
# the interface takes up energy, the jump's released energy is recorded, Pi_ext = Pi_int + Pi_sa + D holds to
# 2e-3 Pi_c0 at every state, and no load that failed twice is tried a third time. Then restart: the same rotation
# split at a checkpoint (12 deg) ends where the continuous one does; and a lift from that checkpoint with the stiction law anchored there starts from the
# frictionless state's energy, converges, and is stiffer than the frictionless lift (the pad cannot slide), more so
# with the end face held in X than free in X.
# usage: rotation_through_instability.sh <spatula>
set -eu
app=$1
here=$(cd "$(dirname "$0")" && pwd)
source "$here/rotation_scene.sh"
enter_scratch_directory
rotation_scene through 36 > through.xml
"$app" through.xml > through.log
/usr/bin/python3 - <<'PY'
import collections
import csv
import re
rows = list(csv.DictReader(open('through/curve.csv')))
jumps = [i for i, r in enumerate(rows) if r['after_jump'] == '1']
assert jumps, 'no instability passed'
j = jumps[0]
before, after = rows[j - 1], rows[j]
m0, m1 = float(before['M_y_nNnm']), float(after['M_y_nNnm'])
assert m1 < 0.8 * m0, f'no moment drop: {m0} -> {m1}'
sa0, sa1 = float(before['Pi_sa_per_Pi_c0']), float(after['Pi_sa_per_Pi_c0'])
assert sa1 > sa0 + 0.02, f'interface energy did not grow: {sa0} -> {sa1}'
assert float(after['dissipated_per_Pi_c0']) > 0.0
worst = max(float(r['balance_error_per_Pi_c0']) for r in rows)
assert worst < 2e-3, worst
assert abs(float(rows[-1]['theta_y_deg']) - 36.0) < 1e-9
# On the way to a limit point a load that failed from two converged states is not tried from a third: the steps
# bisect the gap to it (each retry would be a whole failed Newton attempt).
failed = collections.Counter(re.findall(r'step to .* = (-?[0-9.]+) (?:failed|converged on another branch)',
                                        open('through.log').read()))
assert failed and max(failed.values()) <= 2, failed.most_common(3)
print(f'instability at theta_y {float(before["theta_y_deg"]):.2f} -> {float(after["theta_y_deg"]):.2f} deg: '
      f'M_y {m0:.0f} -> {m1:.0f} nN nm, Pi_sa/Pi_c0 {sa0:.3f} -> {sa1:.3f}, released '
      f'{float(after["dissipated_per_Pi_c0"]):.3f} Pi_c0; balance error <= {worst:.1e} Pi_c0')
PY
rotation_scene continuous 20 > continuous.xml
rotation_scene first 12 '' '<Parameter name="checkpoints at theta_y" type="string" value="12"/>' > first.xml
rotation_scene second 20 '' '<Parameter name="restart file" type="string" value="first/checkpoints.h5"/>
    <Parameter name="restart theta_y" type="double" value="12"/>' > second.xml
"$app" continuous.xml > continuous.log
"$app" first.xml > first.log
"$app" second.xml > second.log
grep -q "restart from 'theta_y=12'" second.log
/usr/bin/python3 - <<'PY'
import csv
a = list(csv.DictReader(open('continuous/curve.csv')))[-1]
b = list(csv.DictReader(open('second/curve.csv')))[-1]
for key in ('theta_y_deg', 'M_y_nNnm', 'u_z_nm', 'Pi_int_1e-18J', 'Pi_sa_1e-18J'):
    x, y = float(a[key]), float(b[key])
    assert abs(x - y) <= 1e-6 * max(1.0, abs(x)), (key, x, y)
# The restarted run carries the work done before the checkpoint.
x, y = float(a['Pi_ext_1e-18J']), float(b['Pi_ext_1e-18J'])
assert abs(x - y) <= 2e-3 * abs(x), ('Pi_ext', x, y)
print(f'restart at 12 deg reproduces the continuous run at 20 deg: M_y {float(b["M_y_nNnm"]):.4f} nN nm')
PY
lift() {   # directory, law, extra Adhesion parameters, extra Loading parameters: 2 nm of lift in 1 nm steps from
           # the 12 deg checkpoint
  lift_scene "$1" "$2" first/checkpoints.h5 12 2 1 "$3" "$4"
}
anchors='<Parameter name="stiction anchors" type="string" value="restart state"/>'
lift frictionless frictionless "" "" > frictionless.xml
lift stiction stiction "$anchors" "" > stiction.xml
lift free stiction "$anchors" '<Parameter name="free slide during lift" type="bool" value="true"/>' > free.xml
"$app" frictionless.xml > frictionless.log
"$app" stiction.xml > stiction.log
"$app" free.xml > free.log
grep -q "contact anchors set at this state" stiction.log
/usr/bin/python3 - <<'PY'
import csv
a = list(csv.DictReader(open('frictionless/curve.csv')))
b = list(csv.DictReader(open('stiction/curve.csv')))
# The restart state: no tangential travel yet, so the stiction law stores the frictionless energy there.
for key in ('Pi_sa_per_Pi_c0', 'Pi_int_1e-18J', 'M_y_nNnm'):
    x, y = float(a[0][key]), float(b[0][key])
    assert abs(x - y) <= 1e-9 * max(1.0, abs(x)), (key, x, y)
for rows in (a, b):
    assert abs(float(rows[-1]['u_z_nm']) - float(rows[0]['u_z_nm']) - 2.0) < 1e-9, 'final lift not reached'
    assert all(r['after_jump'] == '0' for r in rows), 'unexpected jump'
worst = max(float(r['balance_error_per_Pi_c0']) for r in b)
assert worst < 2e-3, worst
pa, pb = float(a[1]['P_z_nN']), float(b[1]['P_z_nN'])
assert pb > 1.5 * pa > 0.0, (pa, pb)
# Free in X, the face moves sideways and the pull stays between the two: stiction adds tangential stiffness to the
# frictionless system, holding the face adds a constraint to that.
c = list(csv.DictReader(open('free/curve.csv')))
pc = float(c[1]['P_z_nN'])
assert pa * (1 - 1e-3) <= pc <= pb, (pa, pc, pb)
assert abs(float(c[-1]['u_x_nm']) - float(c[0]['u_x_nm'])) > 1e-3, 'the free face did not move in X'
assert all(float(r['u_x_nm']) == 0.0 for r in b), 'the held face moved in X'
assert max(float(r['balance_error_per_Pi_c0']) for r in c) < 2e-3
print(f'stiction anchored at the 12 deg checkpoint: Pi_sa continuous at the switch, P_z after 1 nm {pb:.3f} nN '
      f'face held in X, {pc:.3f} nN free in X (frictionless {pa:.3f} nN), balance error <= {worst:.1e} Pi_c0')
PY
