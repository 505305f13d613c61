#!/usr/bin/env bash
# A snap hidden inside a load step: with weak adhesion (gamma_W = 1.5^3 gamma_W0, a 3.4 times smaller Hamaker
# constant) the coarse spatula's moment drops near 25 deg within one 0.27 deg rotation step, and Newton converges
# on the far branch. Without a check the energy the snap released goes missing: the balance error jumps from 2e-5
# to 1e-3 Pi_c0 in that step (and past 1e-2 later). The step balance check must catch it: no state may add more
# than 2e-4 Pi_c0 to the balance error, and the snap must be logged and recorded as a jump.
# usage: snap_within_step.sh <spatula>
set -eu
app=$1
source "$(dirname "$0")/rotation_scene.sh"
rotation_scene strong 27 '<Parameter name="specification" type="string" value="normalized"/>
    <Parameter name="gamma_W" type="double" value="85.2727"/><Parameter name="gamma_L" type="double" value="2.5"/>' > strong.xml
"$app" strong.xml > strong.log
grep -q "a snap within the step" strong.log
/usr/bin/python3 - <<'PY'
import csv
rows = list(csv.DictReader(open('strong/curve.csv')))
balance = [float(r['balance_error_per_Pi_c0']) for r in rows]
growth = max(b - a for a, b in zip(balance, balance[1:]))
assert growth <= 2e-4, f'a step added {growth:.1e} Pi_c0 to the balance error'
assert max(balance) <= 2e-3, max(balance)
jumps = [r for r in rows if r['after_jump'] == '1']
assert jumps and float(rows[-1]['dissipated_per_Pi_c0']) > 0.0, 'the snap was not recorded as a jump'
assert abs(float(rows[-1]['theta_y_deg']) - 27.0) < 1e-9
print(f'{len(jumps)} snap(s) recorded up to 27 deg, released {float(rows[-1]["dissipated_per_Pi_c0"]):.4f} Pi_c0; '
      f'largest growth of the balance error in one step {growth:.1e}, worst {max(balance):.1e} Pi_c0')
PY
