#!/usr/bin/env bash
# The energy descent of a jump stops at the minimum it reaches. The coarse spatula with Q1C1 contact elements and
# 3 x 3 points per face, rotated to 30 deg, snaps near 26 deg. Its descent reaches the far minimum (|f| ~ 1e-10 nN)
# in a dozen iterations while its tangent shift is still positive; the app used to read the absence of any further
# decrease of Pi as a reason to raise the shift, until 500 iterations were spent and the run stopped ("no stable
# state within 500 iterations"). It must now pass the snap in a few dozen iterations and reach 30 deg.
# usage: descent_settles.sh <spatula>
set -eu
app=$1
source "$(dirname "$0")/rotation_scene.sh"
rotation_scene q1c1 30 '<Parameter name="enrichment" type="string" value="Q1C1"/>
    <Parameter name="quadrature" type="int" value="3"/>' > q1c1.xml
"$app" q1c1.xml > q1c1.log
/usr/bin/python3 - <<'PY'
import csv, re
rows = list(csv.DictReader(open('q1c1/curve.csv')))
assert abs(float(rows[-1]['theta_y_deg']) - 30.0) < 1e-9, rows[-1]['theta_y_deg']
jumps = [r for r in rows if r['after_jump'] == '1']
assert jumps, 'no snap passed'
counts = [int(n) for n in re.findall(r'jumped in (\d+) iterations', open('q1c1.log').read())]
assert counts and max(counts) < 100, counts
print(f'{len(jumps)} snap(s) passed at theta_y {float(jumps[0]["theta_y_deg"]):.2f} deg, descents of {counts} '
      f'iterations; 30 deg reached')
PY
