#!/usr/bin/env bash
# 'Loading/pull angle': a coarse spatula with adhesive friction rotated to 20 deg (pull angle 90, the paper's), then
# pulled at 45 deg from that checkpoint with the slide free. The restart turns the checkpoint's lift and slide into
# the 45-degree directions: the restart state is the checkpointed one (u_z, u_x, M_y as stored). With the slide free the
# net force on the face lies along the pull: P_x = P_z cot(45 deg) at every pulled state, the face's reported
# components being the substrate's Z and X.
# usage: pull_angle.sh <spatula> <source dir>
set -u
app=$1
source_dir=$2
source "$source_dir/tests/app/rotation_scene.sh"
enter_scratch_directory
export OPENBLAS_NUM_THREADS=1
check_counts
friction='<ParameterList name="Friction"><Parameter name="coefficient" type="double" value="0.3"/></ParameterList>'
rotation_scene rotation 20 "$friction" '<Parameter name="checkpoints at theta_y" type="string" value="20"/>' |
  sed 's#value="frictionless"#value="adhesive friction"#' > rotation.xml
"$app" rotation.xml > rotation.log 2>&1 || { fail "the rotation"; tail -5 rotation.log; }
lift_scene pulled "adhesive friction" rotation/checkpoints.h5 20 3 1 "$friction" \
  '<Parameter name="pull angle" type="double" value="45"/><Parameter name="free slide during lift" type="bool" value="true"/>' > pulled.xml
"$app" pulled.xml > pulled.log 2>&1 || { fail "the pull at 45 deg"; tail -5 pulled.log; }
/usr/bin/python3 - <<'PY' || fail "the pull at 45 deg"
import csv
rotation, pulled = (list(csv.DictReader(open(f'{name}/curve.csv'))) for name in ('rotation', 'pulled'))
for key in ('theta_y_deg', 'u_z_nm', 'u_x_nm', 'M_y_nNnm', 'P_z_nN'):
    x, y = float(rotation[-1][key]), float(pulled[0][key])
    assert abs(x - y) <= 1e-9 * max(1.0, abs(x)), ('restart state', key, x, y)
lifted = [r for r in pulled if r['stage'] == 'lift']
assert len(lifted) >= 3, len(lifted)
for r in lifted:
    p_z, p_x = float(r['P_z_nN']), float(r['P_x_nN'])
    assert abs(p_z) > 1e-3 and abs(p_x - p_z) <= 1e-6 * abs(p_z), (r['step'], p_z, p_x)
last = lifted[-1]
print(f"pulled at 45 deg from the rotation's state at 20 deg: {len(lifted)} states, at the last P_z {float(last['P_z_nN']):.4f} "
      f"= P_x {float(last['P_x_nN']):.4f} nN, u_z {float(last['u_z_nm']):.3f}, u_x {float(last['u_x_nm']):.3f} nm")
PY
passed "a pull at 45 deg with the slide free"
[ "$failures" -eq 0 ]
