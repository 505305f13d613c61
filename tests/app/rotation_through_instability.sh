#!/usr/bin/env bash
# The coarse spatula (Q1C2 adhesion) rotated from theta_s to 36 deg passes its first instability: the moment drops,
# the interface takes up energy, the jump's released energy is recorded, and Pi_ext = Pi_int + Pi_sa + D holds to
# 2e-3 Pi_c0 at every state. Then restart: the same rotation split at a checkpoint (12 deg) ends where the
# continuous one does. usage: rotation_through_instability.sh <spatula>
set -eu
app=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
scene() {   # directory, final theta_y, extra Loading parameters
  cat <<XML
<ParameterList>
  <ParameterList name="Adhesion"><Parameter name="law" type="string" value="frictionless"/></ParameterList>
  <ParameterList name="Loading">
    <Parameter name="type" type="string" value="rotation"/>
    <Parameter name="theta_y" type="double" value="$2"/>
    $3
    <ParameterList name="Rotation Steps"><Parameter name="initial" type="double" value="1"/>
      <Parameter name="maximum" type="double" value="2"/><Parameter name="minimum" type="double" value="0.01"/></ParameterList>
  </ParameterList>
  <ParameterList name="Output"><Parameter name="directory" type="string" value="$1"/></ParameterList>
</ParameterList>
XML
}
scene through 36 "" > through.xml
"$app" through.xml > through.log
/usr/bin/python3 - <<'PY'
import csv
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
print(f'instability at theta_y {float(before["theta_y_deg"]):.2f} -> {float(after["theta_y_deg"]):.2f} deg: '
      f'M_y {m0:.0f} -> {m1:.0f} nN nm, Pi_sa/Pi_c0 {sa0:.3f} -> {sa1:.3f}, released '
      f'{float(after["dissipated_per_Pi_c0"]):.3f} Pi_c0; balance error <= {worst:.1e} Pi_c0')
PY
scene continuous 20 "" > continuous.xml
scene first 12 '<Parameter name="checkpoints at theta_y" type="string" value="12"/>' > first.xml
scene second 20 '<Parameter name="restart file" type="string" value="first/checkpoints.h5"/>
    <Parameter name="restart theta_y" type="double" value="12"/>' > second.xml
"$app" continuous.xml > continuous.log
"$app" first.xml > first.log
"$app" second.xml > second.log
grep -q "restart from theta_y=12" second.log
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
