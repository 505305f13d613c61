#!/usr/bin/env bash
# The app adheres the coarse spatula (Q1C2) and pulls it off at fixed rotation (xml/pull-off-coarse.xml, lift cut
# short for CI): the start is traction-free with Pi_c = -Pi_c0, the pull force rises, the interface stores energy,
# and Pi_ext balances Pi_int + Pi_sa while the peeling is smooth. usage: pull_off.sh <spatula> <source dir>
set -eu
app=$1
source_dir=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
sed -e 's/value="pull-off-coarse"/value="out"/' -e 's/name="final lift" type="double" value="200"/name="final lift" type="double" value="195"/' \
  "$source_dir/xml/pull-off-coarse.xml" > scene.xml
"$app" scene.xml > log.txt
grep -q "Pi_c0 = A_c w_adh" log.txt
/usr/bin/python3 - <<'PY'
import csv
rows = list(csv.DictReader(open('out/curve.csv')))
first, last = rows[0], rows[-1]
assert abs(float(first['Pi_sa_per_Pi_c0'])) < 1e-12, first['Pi_sa_per_Pi_c0']
lift = [r for r in rows if r['stage'] == 'lift']
assert lift, 'no lift steps'
forces = [float(r['P_z_nN']) for r in lift]
assert max(forces) > 1.0, f'pull force did not rise: {max(forces)}'
assert abs(float(last["u_z_nm"]) - 195.0) < 1e-9
assert float(last['Pi_sa_per_Pi_c0']) > 0.01
rotation = [r for r in rows if r['stage'] == 'rotation']
worst = max(float(r['balance_error_per_Pi_c0']) for r in rotation)
assert worst < 2e-3, f'energy balance error {worst} during rotation'
for r in rows:
    for key, value in r.items():
        if key != 'stage':
            assert value not in ('nan', 'inf', '-nan', '-inf'), (key, value)
print(f'pull-off: P_z up to {max(forces):.3f} nN by u_z = 195 nm, Pi_sa/Pi_c0 = {float(last["Pi_sa_per_Pi_c0"]):.4f}, '
      f'rotation balance error <= {worst:.1e} Pi_c0')
PY
