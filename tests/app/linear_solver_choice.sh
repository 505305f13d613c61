#!/usr/bin/env bash
# Linear Solver/type: gmres-amg (MueLu smoothed aggregation on the node blocks, Q1C2 enrichment nodes included) and
# mumps with single-precision factors (on 1 and 2 ranks) follow a coarse adhesive rotation as mumps with
# double-precision factors does (M_y and Pi_sa to 1e-6 at Newton's tolerance 1e-9), and 'auto' picks MUMPS where its
# factors fit in memory and the multigrid where they do not.
# usage: linear_solver_choice.sh <spatula> <source dir> <mpiexec> [mpiexec flags...]
set -eu
app=$1
source_dir=$2
mpiexec=$3
shift 3
source "$source_dir/tests/app/rotation_scene.sh"
enter_scratch_directory
export OMPI_MCA_btl=self OMPI_MCA_pml=ob1
with_solver() {   # <directory> <solver>: the rotation scene with that linear solver
  rotation_scene "$1" 12 | tight_newton | sed "s#<ParameterList name=\"Output\">#<ParameterList name=\"Linear Solver\"><Parameter name=\"type\" type=\"string\" value=\"$2\"/></ParameterList>\n  <ParameterList name=\"Output\">#"
}
with_solver direct mumps > direct.xml
with_solver multigrid gmres-amg > multigrid.xml
with_single() {   # <directory>: mumps with single-precision factors
  with_solver "$1" mumps | sed 's#<Parameter name="type" type="string" value="mumps"/>#&<ParameterList name="MUMPS"><Parameter name="factor precision" type="string" value="single"/></ParameterList>#'
}
with_single single > single.xml
with_single single2 > single2.xml
"$app" direct.xml > direct.log
"$app" multigrid.xml > multigrid.log
"$app" single.xml > single.log
OMPI_MCA_btl=self,vader "$mpiexec" -np 2 "$@" "$app" single2.xml > single2.log
grep -q "AMG: 1 hierarchy," multigrid.log || { echo "no AMG line in the log:"; grep '^solver:' multigrid.log; exit 1; }
/usr/bin/python3 - <<'PY'
import csv
names = ('direct', 'multigrid', 'single', 'single2')
rows = {name: list(csv.DictReader(open(f'{name}/curve.csv'))) for name in names}
assert abs(float(rows['direct'][-1]['theta_y_deg']) - 12) < 1e-9
for other in names[1:]:
    assert len(rows['direct']) == len(rows[other]), (other, len(rows['direct']), len(rows[other]))
    for a, b in zip(rows['direct'], rows[other]):
        for key in ('M_y_nNnm', 'Pi_sa_1e-18J'):
            x, y = float(a[key]), float(b[key])
            assert abs(x - y) <= 1e-6 * max(1.0, abs(x)), (other, a['step'], key, x, y)
print(f"gmres-amg, and mumps with single-precision factors on 1 and 2 ranks, agree with mumps over "
      f"{len(rows['direct'])} steps to theta_y = 12 deg (M_y {float(rows['direct'][-1]['M_y_nNnm']):.4f} nN nm)")
PY
# auto: MUMPS on the coarse mesh; on a mesh whose factors cannot fit, the multigrid (which does not fit either here,
# so the memory check names it).
with_solver automatic auto > automatic.xml
"$app" automatic.xml --validate-only > automatic.log
grep -qF "linear solver                       mumps (chosen by 'Linear Solver/type' = auto" automatic.log ||
  { echo "auto did not choose mumps on the coarse mesh:"; cat automatic.log; exit 1; }
sed 's#<ParameterList name="Loading">#<ParameterList name="Mesh"><Parameter name="level" type="string" value="fine"/><Parameter name="refinement factor" type="int" value="16"/></ParameterList>\n  <ParameterList name="Loading">#' automatic.xml > huge.xml
status=0
"$app" huge.xml --validate-only > huge.log 2> huge.err || status=$?
[ "$status" -eq 2 ] && grep -qF "with 'Linear Solver/type' = 'gmres-amg'" huge.err ||
  { echo "auto on a mesh beyond MUMPS' memory: exit $status"; cat huge.err; exit 1; }
echo "auto: mumps on the coarse mesh, gmres-amg beyond MUMPS' memory"
