#!/usr/bin/env bash
# The app runs xml/elastic-rotation.xml on 1 and 2 ranks: the M_y(theta_y) curve reaches 14.908 deg, the work of
# the moment equals the stored energy, both runs agree to 1e-8, and ParaView reads the deformed states with I1.
# usage: elastic_rotation.sh <spatula> <source dir> <mpiexec> [mpiexec flags...]
set -eu
app=$1
source_dir=$2
mpiexec=$3
shift 3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
source "$source_dir/tests/app/rotation_scene.sh"
# The 1e-8 agreement of 1 and 2 ranks is checked at Newton's absolute tolerance 1e-9 (tight_newton says why).
for name in one two; do
  sed "s/value=\"elastic-rotation\"/value=\"$name\"/" "$source_dir/xml/elastic-rotation.xml" | tight_newton > $name.xml
done
"$mpiexec" -np 1 "$@" "$app" one.xml > one.log
"$mpiexec" -np 2 "$@" "$app" two.xml > two.log
/usr/bin/python3 - <<'PY'
import csv, sys
rows = {name: list(csv.DictReader(open(f'{name}/curve.csv'))) for name in ('one', 'two')}
last = rows['one'][-1]
assert abs(float(last['theta_y_deg']) - 14.908063349) < 1e-6, last['theta_y_deg']
moment = float(last['M_y_nNnm'])
assert moment > 0, moment
internal, external = float(last['Pi_int_1e-18J']), float(last['Pi_ext_1e-18J'])
assert abs(internal / external - 1) < 1e-3, (internal, external)
for a, b in zip(rows['one'], rows['two']):
    for key in ('M_y_nNnm', 'u_z_nm', 'Pi_int_1e-18J'):
        x, y = float(a[key]), float(b[key])
        assert abs(x - y) <= 1e-8 * max(1.0, abs(x)), (key, x, y)
print(f'elastic rotation: M_y({last["theta_y_deg"]} deg) = {moment:.4f} nN nm, Pi_int = {internal:.4f}, '
      f'Pi_ext = {external:.4f} (1e-18 J); 1 and 2 ranks agree')
PY
if command -v pvbatch > /dev/null && command -v xvfb-run > /dev/null; then
  cat > check.py <<'PY'
import os
from paraview.simple import Xdmf3ReaderT
states = Xdmf3ReaderT(FileName=[os.path.abspath('one/mesh_states.xmf')])
states.UpdatePipelineInformation()
times = states.TimestepValues
assert len(times) >= 5, times
states.UpdatePipeline(times[-1])
i1 = states.GetCellDataInformation().GetArray('I1')
assert i1 is not None
low, high = i1.GetRange()
assert low < 0 < high, (low, high)
print('ParaView read', len(times), 'states; I1 range at the last one', low, high)
PY
  bash "$source_dir/scripts/render.sh" check.py
fi
